//! # Lesson 01: the depth map
//!
//! A directional light renders the scene's depth into a shadow map (the
//! shadow pass); the lit pass then asks, for each pixel, whether the surface
//! is farther from the light than what the map stored. No bias yet: the
//! report measures the acne that lesson 02 fixes.
//!
//! The technique is in [`shadow_map`] (the map, the shadow pass, how the lit
//! pass samples it) and `shaders/lesson_01/`.
//!
//! Run: `cargo run --release --bin lesson_01 -- --headless`
//! Book: chapter "01 depth map" (`book/src/lesson_01.md`).

use std::path::Path;

use clap::ValueEnum;
use common::app;
use common::gpu::Gpu;
use common::lesson::Lesson;
use common::lit::LitPass;
use common::render::SceneGpu;
use common::scene::Scene;
use common::targets::FrameTargets;
use common::timing::Frame;
use common::Result;
use workbook::lesson_01::shadow_map::{self, ShadowMap, ShadowPassState};

// ANCHOR: variants
/// The variants sweep the shadow map's resolution: error against time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    #[value(name = "res_256")]
    Res256,
    #[value(name = "res_512")]
    Res512,
    #[value(name = "res_1024")]
    Res1024,
    #[value(name = "res_2048")]
    Res2048,
    #[value(name = "res_4096")]
    Res4096,
}

impl Variant {
    /// The shadow map's width and height, in texels.
    fn resolution(self) -> u32 {
        match self {
            Variant::Res256 => 256,
            Variant::Res512 => 512,
            Variant::Res1024 => 1024,
            Variant::Res2048 => 2048,
            Variant::Res4096 => 4096,
        }
    }
}
// ANCHOR_END: variants

struct DepthMap {
    shadow_pipeline: wgpu::RenderPipeline,
    lit_pipeline: wgpu::RenderPipeline,
    /// One shadow map (and its bind group) per variant, in variant order.
    maps: Vec<(ShadowMap, wgpu::BindGroup)>,
}

impl Lesson for DepthMap {
    const NAME: &'static str = "lesson_01";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_01.toml");
    type Variant = Variant;

    fn check_scene(scene: &Scene) -> Result<()> {
        shadow_map::refuse_point_lights(scene, Self::NAME)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let module = shadow_map::shader_module(
            gpu,
            "lesson_01",
            include_str!("../../shaders/lesson_01/depth_map.wgsl"),
        );
        let layout = shadow_map::shadow_map_layout(gpu);
        let shadow_pipeline =
            shadow_map::shadow_pipeline(gpu, scene, &module, ShadowPassState::default());
        let lit_pipeline =
            scene.lit_pipeline(gpu, &module, "fs_lit", &[&layout], Default::default());
        let maps = Variant::value_variants()
            .iter()
            .map(|v| {
                let map = ShadowMap::new(gpu, v.resolution());
                let group =
                    shadow_map::shadow_map_group(gpu, &layout, &map, wgpu::FilterMode::Nearest);
                (map, group)
            })
            .collect();
        Ok(DepthMap {
            shadow_pipeline,
            lit_pipeline,
            maps,
        })
    }

    // ANCHOR: render
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        let (map, group) = &self.maps[variant as usize];
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for light in 0..scene.scene.lights.len() {
            // Pass 1: depth from the light. Pass 2: compare and add the light.
            frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, &self.shadow_pipeline, map, light, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    LitPass::new(light, &self.lit_pipeline, &[group]),
                    ts.render(),
                )
            });
        }
        Ok(())
    }
    // ANCHOR_END: render

    fn write_extras(&self, gpu: &Gpu, _: &SceneGpu, variant: Variant, out: &Path) -> Result<()> {
        let name = common::lesson::variant_name(variant);
        let (map, _) = &self.maps[variant as usize];
        map.write_png(gpu, &out.join(format!("{name}_depth_map.png")))
    }
}

fn main() -> std::process::ExitCode {
    app::main::<DepthMap>()
}
