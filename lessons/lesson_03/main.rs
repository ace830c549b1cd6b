//! # Lesson 03: PCF
//!
//! Percentage-closer filtering: instead of one depth comparison per pixel,
//! several around it, averaged into a fractional visibility. The variants
//! are N×N grids (N = 1, 3, 5, 7) compared with the receiver's plane, the hardware's 2×2
//! (a comparison sampler with linear filtering), a rotated 16-tap Poisson
//! disk, a 7×7 grid without the receiver-plane depth bias that wide kernels
//! need, and the wrong way: averaging depths, then comparing once. The
//! shadow pass keeps lesson 02's slope-scaled bias. Then the defaults of
//! renderers people use, each with its own bias (LearnOpenGL, the wgpu
//! example, Bevy), on the same map.
//!
//! The filters are in [`pcf`] and `shaders/lesson_03/pcf.wgsl`; their
//! kernels' sizes are knobs ([`knobs`]).
//!
//! Run: `cargo run --release --bin lesson_03 -- --headless`
//! Book: chapter "03 PCF" (`book/src/lesson_03.md`).

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
use workbook::lesson_01::shadow_map::ShadowPassState;
use workbook::lesson_01::shadow_map::{self, PerSize, ShadowMap};
use workbook::lesson_01::tally::TallyShader;
use workbook::lesson_02::bias::{
    ShadowBias, SlopeScaledBias, BEVY_MAP_SIZE, WGPU_EXAMPLE_CULL, WGPU_EXAMPLE_MAP_SIZE,
};
use workbook::lesson_03::adaptive_count::AdaptivePaths;
use workbook::lesson_03::lit_pipelines::{LitKey, LitPipelines};
use workbook::lesson_03::pcf::{self, Filter, FilterUniform};

mod harness;

/// Lesson 02's map size: the lesson's filters differ, the map does not. A
/// renderer's default runs at its renderer's size ([`Variant::map_size`]).
const MAP_SIZE: u32 = 1024;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    #[value(name = "pcf_1x1")]
    Pcf1x1,
    /// The lesson's 3×3 grid: nine nearest comparisons, each with the
    /// receiver's plane, on lesson 02's slope-scaled bias (LearnOpenGL's
    /// own 3×3, with its bias: `learnopengl_pcf`).
    #[value(name = "pcf_3x3")]
    Pcf3x3,
    #[value(name = "pcf_5x5")]
    Pcf5x5,
    #[value(name = "pcf_7x7")]
    Pcf7x7,
    /// 7×7 without the receiver-plane depth bias.
    #[value(name = "pcf_7x7_flat")]
    Pcf7x7Flat,
    #[value(name = "hw_2x2")]
    Hw2x2,
    #[value(name = "poisson_16")]
    Poisson16,
    /// 4 probes decide lit or umbra; the full poisson_16 only between.
    #[value(name = "poisson_16_adaptive")]
    Poisson16Adaptive,
    /// Castaño's 5×5 from 9 bilinear comparisons on the lesson's map and bias.
    ///
    /// Castaño 2013, "Shadow Mapping Summary – Part 1" (The Witness): each
    /// bilinear tap, placed and weighted by the receiver's position in its
    /// texel, stands for a 2×2 block of a 5×5 tent-like Gaussian. Bevy runs
    /// it as its default filter (`sample_shadow_map_castano_thirteen`,
    /// `port_cards::BEVY_SHADOW_SAMPLING`); here it is `bevy`'s `MODE` 6
    /// without Bevy's offsets, map and shadow pass, beside `poisson_16`.
    /// Every tap compares with the centre's depth (`MODE` 6 takes no
    /// receiver plane), so lit slopes take a wide flat kernel's veil.
    #[value(name = "castano_5x5")]
    Castano5x5,
    #[value(name = "depth_avg_3x3")]
    DepthAvg3x3,
    /// LearnOpenGL "Shadow Mapping": no bias in the shadow pass, `max(0.05
    /// * (1.0 - dot(normal, lightDir)), 0.005)` of depth off the receiver,
    /// and a 3×3 average of nearest taps one `textureSize` texel apart, all
    /// compared with the centre's depth ([`pcf::LEARNOPENGL_3X3`]; its
    /// source lines and departures: `port_cards::LEARNOPENGL_PCF`).
    #[value(name = "learnopengl_pcf")]
    LearnOpenGlPcf,
    /// The wgpu shadow example: the shadow pass's `DepthBiasState {
    /// constant: 2, slope_scale: 2.0, clamp: 0.0 }` with back faces culled,
    /// its 512² map and its comparison sampler (`LessEqual`, `Linear`): the
    /// hardware's 2×2 (`port_cards::WGPU_EXAMPLE_HW2X2`).
    #[value(name = "wgpu_example_hw2x2")]
    WgpuExampleHw2x2,
    /// Bevy's `DirectionalLight` defaults (0.02 world units towards the
    /// light, 1.8 · √2 texels along the normal, no bias in the shadow pass)
    /// on its 2048² map as its one cascade, and its default filter,
    /// `ShadowFilteringMethod::Gaussian`: Castaño's 9-tap 5×5
    /// (`port_cards::BEVY`).
    #[value(name = "bevy")]
    Bevy,
    /// The chapter's exercises (`exercises.wgsl`), run only when named.
    #[value(name = "exercise_pcf_kernel")]
    ExercisePcfKernel,
    #[value(name = "exercise_world_disk")]
    ExerciseWorldDisk,
}

// ANCHOR: variants
impl Variant {
    /// How the variant turns the shadow map into a visibility.
    fn filter(self) -> Filter {
        let grid = |n| Filter::Grid {
            n,
            receiver_plane: true,
        };
        match self {
            Variant::Pcf1x1 => grid(1),
            Variant::Pcf3x3 => grid(3),
            Variant::Pcf5x5 => grid(5),
            Variant::Pcf7x7 => grid(7),
            Variant::Pcf7x7Flat => Filter::Grid {
                n: 7,
                receiver_plane: false,
            },
            Variant::Hw2x2 => Filter::Hardware2x2,
            Variant::Poisson16 => Filter::Poisson {
                taps: 16,
                radius: 2.5,
            },
            Variant::Poisson16Adaptive => Filter::AdaptivePoisson {
                taps: 16,
                radius: 2.5,
            },
            Variant::Castano5x5 => Filter::Castano13,
            Variant::DepthAvg3x3 => Filter::DepthAverage { n: 3 },
            Variant::LearnOpenGlPcf => pcf::LEARNOPENGL_3X3,
            Variant::WgpuExampleHw2x2 => pcf::WGPU_EXAMPLE_HW2X2,
            Variant::Bevy => pcf::BEVY_GAUSSIAN,
            // ... then the two exercises' filters (the chapter's end).
            // ANCHOR_END: variants
            // Graded against pcf_5x5 and poisson_16 (exercises.toml).
            Variant::ExercisePcfKernel => Filter::ExerciseGrid { n: 5 },
            // 2.5 cm: about poisson_16's 2.5 texels on the default scene.
            Variant::ExerciseWorldDisk => Filter::ExerciseDisk { radius_m: 0.025 },
        }
    }

    /// The shadow map's size: the lesson's, or a renderer's default.
    fn map_size(self) -> u32 {
        match self {
            Variant::WgpuExampleHw2x2 => WGPU_EXAMPLE_MAP_SIZE,
            Variant::Bevy => BEVY_MAP_SIZE,
            _ => MAP_SIZE,
        }
    }

    /// The shadow pass: lesson 02's recommended bias, none, or the wgpu
    /// example's (index into [`PASSES`]).
    fn pass(self) -> usize {
        match self {
            Variant::LearnOpenGlPcf | Variant::Bevy => 1,
            Variant::WgpuExampleHw2x2 => 2,
            _ => 0,
        }
    }

    /// Whether the lit pipeline takes a renderer's receiver bias
    /// (`RENDERER_BIAS`).
    fn renderer_bias(self) -> bool {
        self.receiver_bias() != ShadowBias::NONE
    }

    /// The receiver-side bias: none for ours (the shadow pass has it).
    fn receiver_bias(self) -> ShadowBias {
        match self {
            Variant::LearnOpenGlPcf => ShadowBias::LEARNOPENGL,
            Variant::Bevy => ShadowBias::BEVY,
            _ => ShadowBias::NONE,
        }
    }
}

/// The shadow passes' hardware bias and culling: lesson 02's recommended
/// bias (ours), none (LearnOpenGL, Bevy), the wgpu example's.
const PASSES: [(Option<SlopeScaledBias>, Option<wgpu::Face>); 3] = [
    (Some(SlopeScaledBias::RECOMMENDED), None),
    (None, None),
    (Some(SlopeScaledBias::WGPU_EXAMPLE), Some(WGPU_EXAMPLE_CULL)),
];

struct Pcf {
    /// Each variant's filter, as its knobs set it, and its uniform.
    variants: PerVariant<Variant, VariantFilter>,
    /// One map per size the variants use, with its nearest and linear groups.
    maps: PerSize<SizedMap>,
    /// The lit pipelines, one per filter's constants.
    lit_pipelines: LitPipelines,
    /// Per shadow pass of [`PASSES`], one pipeline per light.
    shadow_pipelines: Vec<Vec<wgpu::RenderPipeline>>,
    /// Their counting copies ([`shadow_map::shadow_tally_pipelines`]).
    tally_pipelines: Vec<Vec<[wgpu::RenderPipeline; 2]>>,
    /// Per shadow pass and map size, its depth writes and fragments, counted once.
    texels_written: Vec<((usize, u32), (u64, u64))>,
    draws: u64,
    /// The layout of a variant's filter uniform, to make it again.
    filter_layout: wgpu::BindGroupLayout,
    /// The adaptive filter's counting copy (`fs_adaptive_count`).
    adaptive_count: wgpu::RenderPipeline,
}

/// A variant's filter as its knobs set it, its uniform, and the adaptive
/// filter's paths with it, counted once.
struct VariantFilter {
    /// The filter with the knobs' values (`Variant::filter` when no knob
    /// was set).
    filter: Filter,
    /// Its parameters and the variant's receiver bias, bound at group 3.
    filter_group: wgpu::BindGroup,
    /// The adaptive filter's paths ([`adaptive_count`]); `None` for the
    /// other filters, and until counted.
    adaptive_paths: Option<AdaptivePaths>,
}

impl VariantFilter {
    /// Variant `v` with `filter`, not counted yet.
    fn new(gpu: &Gpu, layout: &wgpu::BindGroupLayout, v: Variant, filter: Filter) -> Self {
        let params = FilterUniform::new(filter, v.receiver_bias());
        let bytes = bytemuck::bytes_of(&params);
        VariantFilter {
            filter,
            filter_group: params_group(gpu, layout, &variant_name(v), bytes),
            adaptive_paths: None,
        }
    }
}

/// A shadow map and its bind groups, sampled nearest and linear.
struct SizedMap {
    map: ShadowMap,
    nearest: wgpu::BindGroup,
    linear: wgpu::BindGroup,
}

impl Pcf {
    /// The variant's shadow map.
    fn map(&self, v: Variant) -> &SizedMap {
        self.maps.get(v.map_size())
    }

    /// The variant's map, bound for its filter's sampler.
    fn map_group(&self, v: Variant) -> &wgpu::BindGroup {
        match v.filter().sampler() {
            wgpu::FilterMode::Linear => &self.map(v).linear,
            _ => &self.map(v).nearest,
        }
    }
}

impl Lesson for Pcf {
    const NAME: &'static str = "lesson_03";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_03.toml");
    type Variant = Variant;

    fn check_scene(scene: &Scene) -> Result<()> {
        shadow_map::refuse_point_lights(scene, Self::NAME)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        // The lesson's filters, then the exercises' functions.
        let exercises_path = workbook::exercises_wgsl_path("lesson_03");
        let files = [
            (
                "shaders/lesson_03/pcf.wgsl",
                include_str!("../../shaders/lesson_03/pcf.wgsl"),
            ),
            (
                exercises_path.as_str(),
                workbook::exercise!(lesson_03::EXERCISES_WGSL),
            ),
        ];
        let module = shadow_map::shader_module_from_files(gpu, "lesson_03", &files)?;
        let layout = pcf::pcf_map_layout(gpu);
        let filter_layout =
            params_layout(gpu, "filter", std::mem::size_of::<FilterUniform>() as u64);
        let adaptive_count = scene.lit_pipeline_with_depth(
            gpu,
            &module,
            "fs_adaptive_count",
            &[&layout, &filter_layout],
            scene.lit_depth_state(Default::default()),
            &[("RECEIVER_PLANE", 1.0)],
        );
        let sizes = Variant::value_variants().iter().map(|v| v.map_size());
        let maps = PerSize::new(sizes, |size| {
            let map = ShadowMap::new(gpu, size);
            let nearest = pcf::pcf_map_group(gpu, &layout, &map, wgpu::FilterMode::Nearest);
            let linear = pcf::pcf_map_group(gpu, &layout, &map, wgpu::FilterMode::Linear);
            SizedMap {
                map,
                nearest,
                linear,
            }
        });
        // The clamp of a pass's bias is converted for the lesson's map: only
        // the lesson's own pass (0) has one.
        let states: Vec<Vec<_>> = PASSES
            .iter()
            .map(|&(bias, cull)| {
                (0..scene.scene.lights.len())
                    .map(|k| ShadowPassState {
                        cull,
                        ..bias.map_or(ShadowPassState::default(), |b| {
                            b.pass_state(gpu, &scene.scene, k, MAP_SIZE)
                        })
                    })
                    .collect()
            })
            .collect();
        let tally = TallyShader::new(gpu);
        let (shadow_pipelines, tally_pipelines) = states
            .iter()
            .map(|per_light| {
                let pass = |&s| shadow_map::shadow_pipeline(gpu, scene, &module, s);
                let count = |&s| shadow_map::shadow_tally_pipelines(gpu, scene, &module, s, &tally);
                (
                    per_light.iter().map(pass).collect(),
                    per_light.iter().map(count).collect(),
                )
            })
            .unzip();
        let variants =
            PerVariant::new(|v: Variant| VariantFilter::new(gpu, &filter_layout, v, v.filter()));
        Ok(Pcf {
            variants,
            maps,
            lit_pipelines: LitPipelines::new(module, [layout, filter_layout.clone()]),
            shadow_pipelines,
            tally_pipelines,
            texels_written: Vec::new(),
            draws: shadow_map::shadow_map_draws(scene),
            filter_layout,
            adaptive_count,
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
        shadow_map::jitter_light_maps(frame.gpu, scene, variant.map_size());
        self.count_texels_once(frame.gpu, scene, variant)?;
        self.count_adaptive_once(frame.gpu, scene, targets, variant)?;
        let pass = variant.pass();
        let VariantFilter {
            filter,
            filter_group,
            ..
        } = &self.variants[variant];
        let key = LitKey::new(*filter, variant.renderer_bias());
        self.lit_pipelines.build(frame.gpu, scene, key);
        let lit_pipeline = self.lit_pipelines.get(key);
        let (map, map_group) = (self.map(variant), self.map_group(variant));
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for light in 0..scene.scene.lights.len() {
            let shadow = &self.shadow_pipelines[pass][light];
            frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, shadow, &map.map, light, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    LitPass::new(light, lit_pipeline, &[map_group, filter_group]),
                    ts.render(),
                )
            });
        }
        Ok(())
    }
    // ANCHOR_END: render
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<Pcf>()
}
