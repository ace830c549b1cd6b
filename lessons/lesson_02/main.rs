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

use clap::ValueEnum;
use common::app;
use common::bindings::{params_group, params_layout};
use common::gpu::Gpu;
use common::lesson::{variant_name, Lesson};
use common::lit::LitPass;
use common::render::SceneGpu;
use common::scene::Scene;
use common::targets::FrameTargets;
use common::timing::Frame;
use common::Result;
use workbook::lesson_01::shadow_map::{self, ShadowMap, ShadowPassState};
use workbook::lesson_01::tally::TallyShader;
use workbook::lesson_02::bias::{ShadowBias, SlopeScaledBias};
use workbook::lesson_02::exercise_pass::{self, Exercise};

/// One map size for every variant: the variants differ only in the bias.
const MAP_SIZE: u32 = 1024;

// ANCHOR: variants
/// Where a variant fights acne.
#[derive(Clone, Copy, Debug)]
enum Fix {
    /// In the lit pass: compare a point moved off the surface (bias.wgsl).
    Receiver(ShadowBias),
    /// In the shadow pass: the rasteriser adds `slope_scale · m + constant · r`
    /// to each stored depth (m: the triangle's depth slope per texel, r: one
    /// unit of the depth format), at most `clamp_texels` texels of depth.
    Hardware(SlopeScaledBias),
    /// In the shadow pass: store the back faces, not the lit front faces.
    CullFrontFaces,
    /// The chapter's exercise: the student's WGSL in the lit pass
    /// (`shaders/lesson_02/exercises.wgsl`), the plain shadow pass.
    Exercise(Exercise),
}

/// The usual fixes, and a sweep of constant biases in texels: acne falls,
/// Peter Panning rises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    #[value(name = "none")]
    None,
    #[value(name = "constant_seed")]
    ConstantSeed,
    #[value(name = "bias_0.25tx")]
    Bias0_25,
    #[value(name = "bias_0.5tx")]
    Bias0_5,
    #[value(name = "bias_1tx")]
    Bias1,
    #[value(name = "bias_4tx")]
    Bias4,
    #[value(name = "bias_16tx")]
    Bias16,
    #[value(name = "bias_64tx")]
    Bias64,
    #[value(name = "slope_hw")]
    SlopeHw,
    #[value(name = "slope_shader")]
    SlopeShader,
    #[value(name = "slope_unclamped")]
    SlopeUnclamped,
    #[value(name = "normal_offset")]
    NormalOffset,
    #[value(name = "front_cull")]
    FrontCull,
    #[value(name = "exercise_slope_bias")]
    ExerciseSlopeBias,
    #[value(name = "exercise_grazing_bias")]
    ExerciseGrazingBias,
}

/// Receiver moved `t` texels towards the light: a constant bias. A texel is
/// measured along the receiver's depth gradient; a receiver at θ needs tan θ / 2.
const fn toward(t: f32) -> Fix {
    Fix::Receiver(ShadowBias {
        toward_light: t,
        ..ShadowBias::NONE
    })
}

impl Variant {
    fn fix(self) -> Fix {
        match self {
            Variant::None => Fix::Receiver(ShadowBias::NONE),
            // lwjglgamedev's `projCoords.z - bias` with `bias = 0.05`: depth units.
            Variant::ConstantSeed => Fix::Receiver(ShadowBias {
                depth: 0.05,
                ..ShadowBias::NONE
            }),
            Variant::Bias0_25 => toward(0.25),
            Variant::Bias0_5 => toward(0.5),
            Variant::Bias1 => toward(1.0),
            Variant::Bias4 => toward(4.0),
            Variant::Bias16 => toward(16.0),
            Variant::Bias64 => toward(64.0),
            Variant::SlopeHw => Fix::Hardware(SlopeScaledBias::RECOMMENDED),
            Variant::SlopeShader => Fix::Receiver(ShadowBias {
                toward_light: 0.1,
                slope: 1.0,
                slope_max: 4.0,
                ..ShadowBias::NONE
            }),
            Variant::SlopeUnclamped => Fix::Receiver(ShadowBias {
                toward_light: 0.1,
                slope: 1.0,
                slope_max: f32::MAX,
                ..ShadowBias::NONE
            }),
            Variant::NormalOffset => Fix::Receiver(ShadowBias {
                toward_light: 0.3,
                normal: 2.0,
                ..ShadowBias::NONE
            }),
            Variant::FrontCull => Fix::CullFrontFaces,
            Variant::ExerciseSlopeBias => Fix::Exercise(Exercise::SlopeBias),
            Variant::ExerciseGrazingBias => Fix::Exercise(Exercise::GrazingBias),
        }
    }
}
// ANCHOR_END: variants

struct Bias {
    /// Each variant's receiver bias, bound at group 3 (zeros for the
    /// shadow-pass fixes), in variant order.
    bias_groups: Vec<wgpu::BindGroup>,
    map: ShadowMap,
    map_group: wgpu::BindGroup,
    lit_pipeline: wgpu::RenderPipeline,
    /// The layouts of groups 2 and 3, for the exercises' lit pipelines.
    layouts: [wgpu::BindGroupLayout; 2],
    /// The exercises' lit pipelines, compiled when an exercise first runs.
    exercise_lit: Vec<(Exercise, wgpu::RenderPipeline)>,
    plain_shadow: wgpu::RenderPipeline,
    cull_shadow: wgpu::RenderPipeline,
    /// The hardware-bias shadow pipeline of each light (the clamp depends on it).
    slope_shadow: Vec<wgpu::RenderPipeline>,
    casters_drawn: u64,
    /// Counting copies of the shadow pipelines ([`shadow_map::shadow_tally_pipelines`]):
    /// plain, front-face culled, and hardware bias per light.
    tally_plain: [wgpu::RenderPipeline; 2],
    tally_cull: [wgpu::RenderPipeline; 2],
    tally_slope: Vec<[wgpu::RenderPipeline; 2]>,
    /// Per variant: the shadow pass's depth writes and fragments, counted once.
    texels_written: Vec<Option<(u64, u64)>>,
    draws: u64,
}

impl Lesson for Bias {
    const NAME: &'static str = "lesson_02";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_02.toml");
    type Variant = Variant;

    fn check_scene(scene: &Scene) -> Result<()> {
        shadow_map::refuse_point_lights(scene, Self::NAME)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let module = shadow_map::shader_module(
            gpu,
            "lesson_02",
            include_str!("../../shaders/lesson_02/bias.wgsl"),
        );
        let map_layout = shadow_map::shadow_map_layout(gpu);
        let bias_layout =
            params_layout(gpu, "shadow bias", std::mem::size_of::<ShadowBias>() as u64);
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
        let tally = TallyShader::new(gpu);
        let count = |state| shadow_map::shadow_tally_pipelines(gpu, scene, &module, state, &tally);
        let cull = ShadowPassState {
            cull: Some(wgpu::Face::Front),
            ..Default::default()
        };
        let plain_shadow = pass(ShadowPassState::default());
        let cull_shadow = pass(cull);
        // One per light: the clamp is in texels, converted for each light.
        // (GL cannot clamp: there the slope-scaled bias is unclamped.)
        let Fix::Hardware(slope) = Variant::SlopeHw.fix() else {
            unreachable!("slope_hw is the rasteriser's bias")
        };
        let slope_states: Vec<_> = (0..scene.scene.lights.len())
            .map(|k| slope.pass_state(gpu, &scene.scene, k, MAP_SIZE))
            .collect();
        let slope_shadow = slope_states.iter().map(|&s| pass(s)).collect();

        let bias_groups = Variant::value_variants()
            .iter()
            .map(|&v| {
                let b = match v.fix() {
                    Fix::Receiver(b) => b,
                    _ => ShadowBias::NONE,
                };
                let name = variant_name(v);
                params_group(gpu, &bias_layout, &name, bytemuck::bytes_of(&b))
            })
            .collect();
        Ok(Bias {
            bias_groups,
            map,
            map_group,
            lit_pipeline,
            layouts: [map_layout, bias_layout],
            exercise_lit: Vec::new(),
            plain_shadow,
            cull_shadow,
            slope_shadow,
            casters_drawn: 0,
            tally_plain: count(ShadowPassState::default()),
            tally_cull: count(cull),
            tally_slope: slope_states.iter().map(|&s| count(s)).collect(),
            texels_written: vec![None; Variant::value_variants().len()],
            draws: shadow_map::shadow_map_draws(scene),
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
        let (fix, bias_group) = (variant.fix(), &self.bias_groups[variant as usize]);
        if self.texels_written[variant as usize].is_none() {
            // Once per variant, its own submit: untimed.
            let n = shadow_map::count_shadow_texels(frame.gpu, scene, MAP_SIZE, |k| match fix {
                Fix::Receiver(_) | Fix::Exercise(_) => &self.tally_plain,
                Fix::Hardware(_) => &self.tally_slope[k],
                Fix::CullFrontFaces => &self.tally_cull,
            })?;
            self.texels_written[variant as usize] = Some(n);
        }
        if let Fix::Exercise(e) = fix {
            if !self.exercise_lit.iter().any(|(x, _)| *x == e) {
                let [map, bias] = &self.layouts;
                let p = exercise_pass::lit_pipeline(frame.gpu, scene, e, &[map, bias]);
                self.exercise_lit.push((e, p));
            }
        }
        let lit = match fix {
            Fix::Exercise(e) => self
                .exercise_lit
                .iter()
                .find(|(x, _)| *x == e)
                .map(|(_, p)| p),
            _ => None,
        }
        .unwrap_or(&self.lit_pipeline);
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        let mut drawn = 0;
        for light in 0..scene.scene.lights.len() {
            let shadow = match fix {
                Fix::Receiver(_) | Fix::Exercise(_) => &self.plain_shadow,
                Fix::Hardware(_) => &self.slope_shadow[light],
                Fix::CullFrontFaces => &self.cull_shadow,
            };
            drawn += frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, shadow, &self.map, light, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    LitPass::new(light, lit, &[&self.map_group, bias_group]),
                    ts.render(),
                )
            });
        }
        self.casters_drawn = drawn as u64;
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, variant: Variant) -> BTreeMap<String, u64> {
        let mut c = BTreeMap::from([
            ("shadow_map_size".into(), MAP_SIZE as u64),
            ("casters_drawn".into(), self.casters_drawn),
            ("filter_taps_per_pixel".into(), 1),
            ("draws".into(), self.draws),
        ]);
        if let Some((written, fragments)) = self.texels_written[variant as usize] {
            c.insert("shadow_texels_written".into(), written);
            c.insert("shadow_fragments".into(), fragments);
        }
        c
    }
}

fn main() -> std::process::ExitCode {
    app::main::<Bias>()
}
