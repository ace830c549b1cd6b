//! # Lesson 01: the depth map
//!
//! A directional light renders the scene's depth into a shadow map (the
//! shadow pass); the lit pass then asks, for each pixel, whether the surface
//! is farther from the light than what the map stored. No bias yet: the
//! report measures the acne that lesson 02 fixes.
//!
//! Run: `cargo run --release --bin lesson_01 -- --headless`
//! Book: chapter "01 depth map" (`book/src/lesson_01.md`).

use std::path::Path;

use common::app::{self, Lesson};
use common::gpu::Gpu;
use common::render::{FrameTargets, SceneGpu};
use common::scene::Scene;
use common::shadow_map::{self, ShadowMap, ShadowPassState};
use common::timing::Frame;
use common::Result;

// ANCHOR: variants
/// The variants sweep the shadow map's resolution: error against time.
const RESOLUTIONS: [u32; 5] = [256, 512, 1024, 2048, 4096];

fn resolution(variant: &str) -> Option<u32> {
    variant.strip_prefix("res_")?.parse().ok()
}
// ANCHOR_END: variants

struct DepthMap {
    shadow_pipeline: wgpu::RenderPipeline,
    lit_pipeline: wgpu::RenderPipeline,
    /// One shadow map (and its bind group) per resolution.
    maps: Vec<(ShadowMap, wgpu::BindGroup)>,
}

impl Lesson for DepthMap {
    const NAME: &'static str = "lesson_01";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_01.toml");

    fn variants() -> Vec<String> {
        RESOLUTIONS.iter().map(|r| format!("res_{r}")).collect()
    }

    fn check_scene(scene: &Scene) -> Result<()> {
        shadow_map::refuse_point_lights(scene, Self::NAME)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let module =
            shadow_map::shader_module(gpu, "lesson_01", include_str!("../shaders/lesson_01.wgsl"));
        let layout = shadow_map::shadow_map_layout(gpu);
        let shadow_pipeline =
            shadow_map::shadow_pipeline(gpu, scene, &module, ShadowPassState::default());
        let lit_pipeline =
            scene.lit_pipeline(gpu, &module, "fs_lit", &[&layout], Default::default());
        let maps = RESOLUTIONS
            .iter()
            .map(|&r| {
                let map = ShadowMap::new(gpu, r);
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
        variant: &str,
    ) -> Result<()> {
        let (map, group) = self.map_for(variant)?;
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
                    light,
                    &self.lit_pipeline,
                    &[group],
                    0,
                    ts.render(),
                )
            });
        }
        Ok(())
    }
    // ANCHOR_END: render

    fn write_extras(&self, gpu: &Gpu, _scene: &SceneGpu, variant: &str, out: &Path) -> Result<()> {
        let (map, _) = self.map_for(variant)?;
        map.write_png(gpu, &out.join(format!("{variant}_depth_map.png")))
    }
}

impl DepthMap {
    fn map_for(&self, variant: &str) -> Result<&(ShadowMap, wgpu::BindGroup)> {
        let size = resolution(variant);
        self.maps
            .iter()
            .find(|(m, _)| Some(m.size) == size)
            .ok_or_else(|| anyhow::anyhow!("unknown variant {variant}"))
    }
}

fn main() -> std::process::ExitCode {
    app::main::<DepthMap>()
}
