//! # Lesson 02: bias
//!
//! Lesson 01's shadow map, with the comparison moved off the surface so that
//! a surface stops shadowing itself (acne), and the price of that measured:
//! shadows that come loose from their casters (Peter Panning, false lit).
//! The variants are the usual fixes: a constant bias (the lwjgl book's
//! magic number, and a sweep of sizes), the rasteriser's slope-scaled depth
//! bias, a slope-scaled and a normal-offset bias in the shader, and drawing
//! only back faces into the map; then the defaults of renderers people use
//! (LearnOpenGL, the wgpu example, Bevy), on the same map. Each variant's
//! bias sizes are knobs (`--knob`, the window's widgets): which ones, in
//! [`workbook::lesson_02::knobs`].
//!
//! Run: `cargo run --release --bin lesson_02 -- --headless`
//! Book: chapter "02 Bias" (`book/src/lesson_02.md`).

use clap::ValueEnum;
use common::gpu::bindings::{params_group, params_layout};
use common::gpu::lit::LitPass;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::run::lesson::{variant_name, Lesson};
use common::run::per_variant::PerVariant;
use common::scene::Scene;
use common::Result;
use workbook::lesson_01::shadow_map::{self, PerSize, ShadowMap, ShadowPassState};
use workbook::lesson_01::tally::TallyShader;
use workbook::lesson_02::bias::{
    ShadowBias, SlopeScaledBias, BEVY_MAP_SIZE, WGPU_EXAMPLE_CULL, WGPU_EXAMPLE_MAP_SIZE,
};
use workbook::lesson_02::exercise_pass::Exercise;

mod harness;

/// One map size for the lesson's variants: they differ only in the bias.
/// A renderer's default runs at its renderer's size ([`Variant::map_size`]).
const MAP_SIZE: u32 = 1024;

// ANCHOR: fixes
/// Where a variant fights acne.
#[derive(Clone, Copy, Debug)]
enum Fix {
    /// In the lit pass: compare a point moved off the surface (bias.wgsl).
    Receiver(ShadowBias),
    /// In the shadow pass: the rasteriser adds `slope_scale · m + constant · q`
    /// to each stored depth (m: the triangle's depth slope per texel, q: one
    /// unit of the depth format), at most `clamp_texels` texels of depth;
    /// and the faces the pass culls (the wgpu example culls back faces).
    Hardware(SlopeScaledBias, Option<wgpu::Face>),
    /// In the shadow pass: store the back faces, not the lit front faces.
    CullFrontFaces,
}

/// Receiver moved `t` texels towards the light: a constant bias. A texel is
/// measured along the receiver's depth gradient; a receiver at θ needs tan θ / 2.
const fn toward(t: f32) -> Fix {
    Fix::Receiver(ShadowBias {
        toward_light: t,
        ..ShadowBias::NONE
    })
}

/// Receiver moved 0.1 texel plus tan θ texels towards the light, at most
/// `max`: a slope-scaled bias in the shader.
const fn slope_scaled(max: f32) -> Fix {
    Fix::Receiver(ShadowBias {
        toward_light: 0.1,
        slope: 1.0,
        slope_max: max,
        ..ShadowBias::NONE
    })
}
// ANCHOR_END: fixes

/// The usual fixes, and a sweep of constant biases in texels: acne falls,
/// Peter Panning rises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    #[value(name = "none")]
    None,
    /// The lwjgl book's `bias = 0.05` (its legacy edition, chapter 18), in depth units.
    #[value(name = "constant_lwjgl")]
    ConstantLwjgl,
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
    /// LearnOpenGL "Shadow Mapping": `max(0.05 * (1.0 - dot(normal,
    /// lightDir)), 0.005)` of depth, verbatim in our depth units, one tap
    /// ([`ShadowBias::LEARNOPENGL`]; its source lines and departures:
    /// `port_cards::LEARNOPENGL`).
    #[value(name = "learnopengl")]
    LearnOpenGl,
    /// The wgpu shadow example: its shadow pass's `DepthBiasState {
    /// constant: 2, slope_scale: 2.0, clamp: 0.0 }` with back faces culled,
    /// on its 512² map; one nearest tap here (its 2×2 is lesson 03's
    /// `wgpu_example_hw2x2`) (`port_cards::WGPU_EXAMPLE`).
    #[value(name = "wgpu_example")]
    WgpuExample,
    /// Bevy's `DirectionalLight` defaults: 0.02 world units towards the
    /// light, 1.8 · √2 texels along the normal, on its 2048² map as its
    /// one cascade; one tap here (with Bevy's filter: lesson 03's `bevy`)
    /// (`port_cards::BEVY_BIAS`).
    #[value(name = "bevy_bias")]
    BevyBias,
    #[value(name = "exercise_slope_bias")]
    ExerciseSlopeBias,
    #[value(name = "exercise_grazing_bias")]
    ExerciseGrazingBias,
}

// ANCHOR: variants
impl Variant {
    /// What the variant changes: where it fights acne, and by how much.
    fn fix(self) -> Fix {
        match self {
            Variant::None => Fix::Receiver(ShadowBias::NONE),
            // The lwjgl book's `projCoords.z - bias` with `bias = 0.05`: depth units.
            Variant::ConstantLwjgl => Fix::Receiver(ShadowBias {
                depth: 0.05,
                ..ShadowBias::NONE
            }),
            Variant::Bias0_25 => toward(0.25),
            Variant::Bias0_5 => toward(0.5),
            Variant::Bias1 => toward(1.0),
            Variant::Bias4 => toward(4.0),
            Variant::Bias16 => toward(16.0),
            Variant::Bias64 => toward(64.0),
            Variant::SlopeHw => Fix::Hardware(SlopeScaledBias::RECOMMENDED, None),
            Variant::SlopeShader => slope_scaled(4.0),
            Variant::SlopeUnclamped => slope_scaled(f32::MAX),
            Variant::NormalOffset => Fix::Receiver(ShadowBias {
                toward_light: 0.3,
                normal: 2.0,
                ..ShadowBias::NONE
            }),
            Variant::FrontCull => Fix::CullFrontFaces,
            Variant::LearnOpenGl => Fix::Receiver(ShadowBias::LEARNOPENGL),
            Variant::WgpuExample => {
                Fix::Hardware(SlopeScaledBias::WGPU_EXAMPLE, Some(WGPU_EXAMPLE_CULL))
            }
            Variant::BevyBias => Fix::Receiver(ShadowBias::BEVY),
            // The exercises: lesson 01's map, no bias here (their WGSL biases).
            _ => Fix::Receiver(ShadowBias::NONE),
        }
    }
}
// ANCHOR_END: variants

impl Variant {
    /// The shadow map's size: the lesson's, or a renderer's default.
    fn map_size(self) -> u32 {
        match self {
            Variant::WgpuExample => WGPU_EXAMPLE_MAP_SIZE,
            Variant::BevyBias => BEVY_MAP_SIZE,
            _ => MAP_SIZE,
        }
    }

    /// The exercise whose WGSL the variant's lit pass runs, if it is one.
    fn exercise(self) -> Option<Exercise> {
        match self {
            Variant::ExerciseSlopeBias => Some(Exercise::SlopeBias),
            Variant::ExerciseGrazingBias => Some(Exercise::GrazingBias),
            _ => None,
        }
    }
}

struct Bias {
    /// Each variant's bias, as its knobs set it, bound for its passes.
    variants: PerVariant<Variant, VariantBias>,
    /// One map per size the variants use, and its bind group.
    maps: PerSize<(ShadowMap, wgpu::BindGroup)>,
    lit_pipeline: wgpu::RenderPipeline,
    /// The layouts of groups 2 and 3, for the exercises' lit pipelines.
    layouts: [wgpu::BindGroupLayout; 2],
    /// The exercises' lit pipelines, compiled when an exercise first runs.
    exercise_lit: Vec<(Exercise, wgpu::RenderPipeline)>,
    plain_shadow: wgpu::RenderPipeline,
    cull_shadow: wgpu::RenderPipeline,
    casters_drawn: u64,
    /// Counting copies of the shadow pipelines ([`shadow_map::shadow_tally_pipelines`]):
    /// plain and front-face culled.
    tally_plain: [wgpu::RenderPipeline; 2],
    tally_cull: [wgpu::RenderPipeline; 2],
    draws: u64,
    /// The shadow pipelines' shader and the counting one, to rebuild a
    /// hardware bias's pipelines when a knob changes it.
    module: wgpu::ShaderModule,
    tally: TallyShader,
}

/// A variant's fix as its knobs set it, what draws it (its receiver bias's
/// uniform, its hardware bias's shadow pipelines), and the shadow pass's
/// depth writes and fragments with it, counted once.
struct VariantBias {
    /// The fix with the knobs' values (`Variant::fix` when no knob was set).
    fix: Fix,
    /// Its receiver bias, bound at group 3 (zeros for the shadow-pass fixes).
    bias_group: wgpu::BindGroup,
    /// With a hardware bias: its shadow pipeline for each light (the clamp
    /// depends on it), and their counting copies.
    slope_shadow: Option<Vec<wgpu::RenderPipeline>>,
    tally_slope: Option<Vec<[wgpu::RenderPipeline; 2]>>,
    texels_written: Option<(u64, u64)>,
}

impl VariantBias {
    /// Variant `v`'s own fix ([`Variant::fix`]), not counted yet.
    fn new(
        gpu: &Gpu,
        scene: &SceneGpu,
        shaders: (&wgpu::ShaderModule, &TallyShader),
        bias_layout: &wgpu::BindGroupLayout,
        v: Variant,
    ) -> VariantBias {
        let fix = v.fix();
        let receiver = match fix {
            Fix::Receiver(b) => b,
            _ => ShadowBias::NONE,
        };
        let (slope_shadow, tally_slope) = match fix {
            Fix::Hardware(slope, cull) => {
                let (p, t) = hardware_pipelines(gpu, scene, shaders, (slope, cull), v.map_size());
                (Some(p), Some(t))
            }
            _ => (None, None),
        };
        VariantBias {
            fix,
            bias_group: bias_group(gpu, bias_layout, v, &receiver),
            slope_shadow,
            tally_slope,
            texels_written: None,
        }
    }
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
        let sizes = Variant::value_variants().iter().map(|v| v.map_size());
        let maps = PerSize::new(sizes, |size| {
            let map = ShadowMap::new(gpu, size);
            let nearest = wgpu::FilterMode::Nearest;
            let group = shadow_map::shadow_map_group(gpu, &map_layout, &map, nearest);
            (map, group)
        });

        let pass = |state| shadow_map::shadow_pipeline(gpu, scene, &module, state);
        let tally = TallyShader::new(gpu);
        let count = |state| shadow_map::shadow_tally_pipelines(gpu, scene, &module, state, &tally);
        let cull = ShadowPassState {
            cull: Some(wgpu::Face::Front),
            ..Default::default()
        };
        let plain_shadow = pass(ShadowPassState::default());
        let cull_shadow = pass(cull);
        let variants = PerVariant::new(|v: Variant| {
            VariantBias::new(gpu, scene, (&module, &tally), &bias_layout, v)
        });
        Ok(Bias {
            variants,
            maps,
            lit_pipeline,
            layouts: [map_layout, bias_layout],
            exercise_lit: Vec::new(),
            plain_shadow,
            cull_shadow,
            casters_drawn: 0,
            tally_plain: count(ShadowPassState::default()),
            tally_cull: count(cull),
            draws: shadow_map::shadow_map_draws(scene),
            module: module.clone(),
            tally,
        })
    }

    /// The harness around [`Bias::draw`]: the shadow pass's depth writes
    /// counted once per variant (their own submits, before the frame), an
    /// exercise's lit pipeline, and the casters the frame drew.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        // The runner's sub-texel move of the map (`--fragile`), drawn and read.
        shadow_map::jitter_light_maps(frame.gpu, scene, variant.map_size());
        self.count_texels_once(frame.gpu, scene, variant)?;
        self.compile_exercise(frame.gpu, scene, variant)?;
        let lit = self.lit_for(variant);
        let drawn = self.draw(frame, scene, targets, variant, lit);
        self.casters_drawn = drawn as u64;
        Ok(())
    }
}

impl Bias {
    // ANCHOR: render
    /// One frame: per light, the shadow pass with the variant's pipeline
    /// (front faces culled, its hardware bias for that light, or lesson
    /// 01's plain one), then the lit pass with its bias at group 3.
    /// Returns the casters drawn.
    fn draw(
        &self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
        lit: &wgpu::RenderPipeline,
    ) -> u32 {
        let VariantBias {
            slope_shadow,
            bias_group,
            ..
        } = &self.variants[variant];
        let (map, map_group) = self.map(variant);
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        let mut drawn = 0;
        for light in 0..scene.scene.lights.len() {
            let shadow = match (variant.fix(), slope_shadow) {
                (Fix::CullFrontFaces, _) => &self.cull_shadow,
                (_, Some(hw)) => &hw[light],
                _ => &self.plain_shadow,
            };
            drawn += frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, shadow, map, light, ts.render())
            });
            let groups = [map_group, bias_group];
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(enc, targets, LitPass::new(light, lit, &groups), ts.render())
            });
        }
        drawn
    }
    // ANCHOR_END: render

    /// The variant's shadow map and its bind group.
    fn map(&self, v: Variant) -> &(ShadowMap, wgpu::BindGroup) {
        self.maps.get(v.map_size())
    }
}

/// A hardware bias's shadow pipeline for each light, and their counting
/// copies, for a map of `size`: the clamp is in texels, converted for each
/// light (GL cannot clamp: there the slope-scaled bias is unclamped).
fn hardware_pipelines(
    gpu: &Gpu,
    scene: &SceneGpu,
    (module, tally): (&wgpu::ShaderModule, &TallyShader),
    (slope, cull): (SlopeScaledBias, Option<wgpu::Face>),
    size: u32,
) -> (Vec<wgpu::RenderPipeline>, Vec<[wgpu::RenderPipeline; 2]>) {
    let states: Vec<ShadowPassState> = (0..scene.scene.lights.len())
        .map(|k| ShadowPassState {
            cull,
            ..slope.pass_state(gpu, &scene.scene, k, size)
        })
        .collect();
    let pass = |&s| shadow_map::shadow_pipeline(gpu, scene, module, s);
    let count = |&s| shadow_map::shadow_tally_pipelines(gpu, scene, module, s, tally);
    (
        states.iter().map(pass).collect(),
        states.iter().map(count).collect(),
    )
}

/// Variant `v`'s receiver bias `b` as its group 3 uniform.
fn bias_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    v: Variant,
    b: &ShadowBias,
) -> wgpu::BindGroup {
    params_group(gpu, layout, &variant_name(v), bytemuck::bytes_of(b))
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<Bias>()
}
