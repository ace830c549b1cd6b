//! # Lesson 03: PCF
//!
//! Percentage-closer filtering: instead of one depth comparison per pixel,
//! several around it, averaged into a fractional visibility. The variants
//! are N×N grids (N = 1, 3, 5, 7; 3×3 is the seed's), the hardware's 2×2
//! (a comparison sampler with linear filtering), a rotated 16-tap Poisson
//! disk, a 7×7 grid without the receiver-plane depth bias that wide kernels
//! need, and the wrong way: averaging depths, then comparing once. The
//! shadow pass keeps lesson 02's slope-scaled bias.
//!
//! The filters are in [`pcf`] and `shaders/lesson_03/pcf.wgsl`.
//!
//! Run: `cargo run --release --bin lesson_03 -- --headless`
//! Book: chapter "03 PCF" (`book/src/lesson_03.md`).

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
use workbook::lesson_01::shadow_map::{self, ShadowMap};
use workbook::lesson_01::tally::TallyShader;
use workbook::lesson_02::bias::SlopeScaledBias;
use workbook::lesson_03::exercises;
use workbook::lesson_03::pcf::{self, Filter, FilterUniform};

/// Lesson 02's map size: the filters differ, the map does not.
const MAP_SIZE: u32 = 1024;

// ANCHOR: variants
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    #[value(name = "pcf_1x1")]
    Pcf1x1,
    /// The seed's 3×3 average.
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
    #[value(name = "depth_avg_3x3")]
    DepthAvg3x3,
    /// The chapter's exercises (`exercises.wgsl`), run only when named.
    #[value(name = "exercise_pcf_kernel")]
    ExercisePcfKernel,
    #[value(name = "exercise_rotated_poisson")]
    ExerciseRotatedPoisson,
}

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
            Variant::DepthAvg3x3 => Filter::DepthAverage { n: 3 },
            // Graded against pcf_5x5 and poisson_16 (exercises.toml).
            Variant::ExercisePcfKernel => Filter::ExerciseGrid { n: 5 },
            Variant::ExerciseRotatedPoisson => Filter::ExerciseDisk { radius: 2.5 },
        }
    }
}
// ANCHOR_END: variants

struct Pcf {
    /// Each variant's filter parameters (group 3), in variant order.
    filter_groups: Vec<wgpu::BindGroup>,
    map: ShadowMap,
    nearest: wgpu::BindGroup,
    linear: wgpu::BindGroup,
    lit_pipeline: wgpu::RenderPipeline,
    /// Lesson 02's slope-scaled bias, one pipeline per light.
    shadow_pipelines: Vec<wgpu::RenderPipeline>,
    /// Their counting copies ([`shadow_map::shadow_tally_pipelines`]).
    tally_pipelines: Vec<[wgpu::RenderPipeline; 2]>,
    /// The shadow pass's depth writes and fragments (the same for every
    /// variant: the filters differ, the map does not), counted once.
    texels_written: Option<(u64, u64)>,
    draws: u64,
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
        let source = format!(
            "{}\n{}",
            include_str!("../../shaders/lesson_03/pcf.wgsl"),
            exercises::EXERCISES_WGSL
        );
        let module = shadow_map::shader_module(gpu, "lesson_03", &source);
        let layout = pcf::pcf_map_layout(gpu);
        let filter_layout =
            params_layout(gpu, "filter", std::mem::size_of::<FilterUniform>() as u64);
        let lit_pipeline = scene.lit_pipeline(
            gpu,
            &module,
            "fs_lit",
            &[&layout, &filter_layout],
            Default::default(),
        );
        let map = ShadowMap::new(gpu, MAP_SIZE);
        let nearest = pcf::pcf_map_group(gpu, &layout, &map, wgpu::FilterMode::Nearest);
        let linear = pcf::pcf_map_group(gpu, &layout, &map, wgpu::FilterMode::Linear);
        let bias = SlopeScaledBias::RECOMMENDED;
        let states: Vec<_> = (0..scene.scene.lights.len())
            .map(|k| bias.pass_state(gpu, &scene.scene, k, MAP_SIZE))
            .collect();
        let shadow_pipelines = states
            .iter()
            .map(|&state| shadow_map::shadow_pipeline(gpu, scene, &module, state))
            .collect();
        let tally = TallyShader::new(gpu);
        let tally_pipelines = states
            .iter()
            .map(|&state| shadow_map::shadow_tally_pipelines(gpu, scene, &module, state, &tally))
            .collect();
        let filter_groups = Variant::value_variants()
            .iter()
            .map(|&v| {
                let params = FilterUniform::from(v.filter());
                params_group(
                    gpu,
                    &filter_layout,
                    &variant_name(v),
                    bytemuck::bytes_of(&params),
                )
            })
            .collect();
        Ok(Pcf {
            filter_groups,
            map,
            nearest,
            linear,
            lit_pipeline,
            shadow_pipelines,
            tally_pipelines,
            texels_written: None,
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
        if self.texels_written.is_none() {
            // Once, its own submit: untimed.
            let n = shadow_map::count_shadow_texels(frame.gpu, scene, MAP_SIZE, |k| {
                &self.tally_pipelines[k]
            })?;
            self.texels_written = Some(n);
        }
        let filter_group = &self.filter_groups[variant as usize];
        let map_group = match variant.filter().sampler() {
            wgpu::FilterMode::Linear => &self.linear,
            _ => &self.nearest,
        };
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for light in 0..scene.scene.lights.len() {
            let shadow = &self.shadow_pipelines[light];
            frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, shadow, &self.map, light, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    LitPass::new(light, &self.lit_pipeline, &[map_group, filter_group]),
                    ts.render(),
                )
            });
        }
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, variant: Variant) -> BTreeMap<String, u64> {
        let (taps, texels) = variant.filter().taps();
        let mut c = BTreeMap::from([
            ("taps".into(), taps),
            ("filter_taps_per_pixel".into(), taps),
            ("texels_read".into(), texels),
            ("shadow_map_size".into(), MAP_SIZE as u64),
            ("draws".into(), self.draws),
        ]);
        if let Some((written, fragments)) = self.texels_written {
            c.insert("shadow_texels_written".into(), written);
            c.insert("shadow_fragments".into(), fragments);
        }
        c
    }
}

fn main() -> std::process::ExitCode {
    app::main::<Pcf>()
}
