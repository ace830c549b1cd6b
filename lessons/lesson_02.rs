//! # Lesson 02: bias
//!
//! Lesson 01's shadow map, with the comparison moved off the surface so that
//! a surface stops shadowing itself (acne), and the price of that measured:
//! shadows that come loose from their casters (Peter Panning, false lit).
//! The variants are the usual fixes: a constant bias (the seeds' magic
//! number, and a sweep of sizes), the rasteriser's slope-scaled depth bias,
//! a slope-scaled and a normal-offset bias in the shader, and drawing only
//! back faces into the map.
//!
//! Run: `cargo run --release --bin lesson_02 -- --headless`
//! Book: chapter "02 Bias" (`book/src/lesson_02.md`).

use std::collections::BTreeMap;

use common::app::{self, Lesson};
use common::gpu::Gpu;
use common::render::{FrameTargets, SceneGpu};
use common::scene::Scene;
use common::shadow_map::{self, ShadowBias, ShadowMap, ShadowPassState, SlopeScaledBias};
use common::timing::Frame;
use common::Result;

/// One map size for every variant: the variants differ only in the bias.
const MAP_SIZE: u32 = 1024;

// ANCHOR: variants
/// Where a variant fights acne.
#[derive(Clone, Copy, Debug)]
enum Fix {
    /// In the lit pass: compare a point moved off the surface (shadow_map.wgsl).
    Receiver(ShadowBias),
    /// In the shadow pass: the rasteriser adds `slope_scale · m + constant · r`
    /// to each stored depth (m: the triangle's depth slope per texel, r: one
    /// unit of the depth format), at most `clamp_texels` texels of depth.
    Hardware(SlopeScaledBias),
    /// In the shadow pass: store the back faces, not the lit front faces.
    CullFrontFaces,
}

/// Receiver moved `t` texels towards the light: a constant bias.
const fn toward(t: f32) -> ShadowBias {
    ShadowBias {
        toward_light: t,
        ..ShadowBias::NONE
    }
}

/// The sweep of constant biases, in texels: acne falls, Peter Panning rises.
const SWEEP: [(&str, f32); 6] = [
    ("bias_0.25tx", 0.25),
    ("bias_0.5tx", 0.5),
    ("bias_1tx", 1.0),
    ("bias_4tx", 4.0),
    ("bias_16tx", 16.0),
    ("bias_64tx", 64.0),
];

fn variant_list() -> Vec<(&'static str, Fix)> {
    let mut v = vec![
        ("none", Fix::Receiver(ShadowBias::NONE)),
        // lwjglgamedev's `projCoords.z - bias` with `bias = 0.05`: depth units.
        (
            "constant_seed",
            Fix::Receiver(ShadowBias {
                depth: 0.05,
                ..ShadowBias::NONE
            }),
        ),
    ];
    v.extend(
        SWEEP
            .iter()
            .map(|&(name, t)| (name, Fix::Receiver(toward(t)))),
    );
    v.extend([
        ("slope_hw", Fix::Hardware(SlopeScaledBias::RECOMMENDED)),
        (
            "slope_shader",
            Fix::Receiver(ShadowBias {
                toward_light: 0.1,
                slope: 1.0,
                slope_max: 4.0,
                ..ShadowBias::NONE
            }),
        ),
        (
            "slope_unclamped",
            Fix::Receiver(ShadowBias {
                toward_light: 0.1,
                slope: 1.0,
                slope_max: f32::MAX,
                ..ShadowBias::NONE
            }),
        ),
        (
            "normal_offset",
            Fix::Receiver(ShadowBias {
                toward_light: 0.3,
                normal: 2.0,
                ..ShadowBias::NONE
            }),
        ),
        ("front_cull", Fix::CullFrontFaces),
    ]);
    v
}
// ANCHOR_END: variants

struct Bias {
    variants: Vec<(&'static str, Fix, wgpu::BindGroup)>,
    map: ShadowMap,
    map_group: wgpu::BindGroup,
    lit_pipeline: wgpu::RenderPipeline,
    plain_shadow: wgpu::RenderPipeline,
    cull_shadow: wgpu::RenderPipeline,
    /// The hardware-bias shadow pipeline of each light (the clamp depends on it).
    slope_shadow: Vec<wgpu::RenderPipeline>,
    casters_drawn: u64,
}

impl Bias {
    fn fix(&self, variant: &str) -> Result<(Fix, &wgpu::BindGroup)> {
        self.variants
            .iter()
            .find(|(n, ..)| *n == variant)
            .map(|(_, f, g)| (*f, g))
            .ok_or_else(|| anyhow::anyhow!("unknown variant {variant}"))
    }
}

impl Lesson for Bias {
    const NAME: &'static str = "lesson_02";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_02.toml");

    fn variants() -> Vec<String> {
        variant_list()
            .into_iter()
            .map(|(n, _)| n.to_string())
            .collect()
    }

    fn check_scene(scene: &Scene) -> Result<()> {
        shadow_map::refuse_point_lights(scene, Self::NAME)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let module =
            shadow_map::shader_module(gpu, "lesson_02", include_str!("../shaders/lesson_02.wgsl"));
        let map_layout = shadow_map::shadow_map_layout(gpu);
        let bias_layout = shadow_map::uniform_layout(
            gpu,
            "shadow bias",
            std::mem::size_of::<ShadowBias>() as u64,
        );
        let lit_pipeline = scene.lit_pipeline(
            gpu,
            &module,
            "fs_lit",
            &[&map_layout, &bias_layout],
            Default::default(),
        );
        let map = ShadowMap::new(gpu, MAP_SIZE);
        let map_group =
            shadow_map::shadow_map_group(gpu, &map_layout, &map, wgpu::FilterMode::Nearest);

        let pass = |state| shadow_map::shadow_pipeline(gpu, scene, &module, state);
        let plain_shadow = pass(ShadowPassState::default());
        let cull_shadow = pass(ShadowPassState {
            cull: Some(wgpu::Face::Front),
            ..Default::default()
        });
        // One per light: the clamp is in texels, converted for each light.
        // (GL cannot clamp: there the slope-scaled bias is unclamped.)
        let slope = variant_list().into_iter().find_map(|(_, f)| {
            if let Fix::Hardware(b) = f {
                Some(b)
            } else {
                None
            }
        });
        let slope = slope.expect("a slope_hw variant");
        let slope_shadow = (0..scene.scene.lights.len())
            .map(|k| pass(slope.pass_state(gpu, &scene.scene, k, MAP_SIZE)))
            .collect();

        let variants = variant_list()
            .into_iter()
            .map(|(name, fix)| {
                let b = match fix {
                    Fix::Receiver(b) => b,
                    _ => ShadowBias::NONE,
                };
                (
                    name,
                    fix,
                    shadow_map::uniform_group(gpu, &bias_layout, name, bytemuck::bytes_of(&b)),
                )
            })
            .collect();
        Ok(Bias {
            variants,
            map,
            map_group,
            lit_pipeline,
            plain_shadow,
            cull_shadow,
            slope_shadow,
            casters_drawn: 0,
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
        let (fix, bias_group) = self.fix(variant)?;
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        let mut drawn = 0;
        for light in 0..scene.scene.lights.len() {
            let shadow = match fix {
                Fix::Receiver(_) => &self.plain_shadow,
                Fix::Hardware { .. } => &self.slope_shadow[light],
                Fix::CullFrontFaces => &self.cull_shadow,
            };
            drawn += frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, shadow, &self.map, light, ts.render())
            });
            let groups = [&self.map_group, bias_group];
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    light,
                    &self.lit_pipeline,
                    &groups,
                    0,
                    ts.render(),
                )
            });
        }
        self.casters_drawn = drawn as u64;
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, _variant: &str) -> BTreeMap<String, u64> {
        BTreeMap::from([
            ("shadow_map_size".into(), MAP_SIZE as u64),
            ("casters_drawn".into(), self.casters_drawn),
        ])
    }
}

fn main() -> std::process::ExitCode {
    app::main::<Bias>()
}
