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
//! Run: `cargo run --release --bin lesson_03 -- --headless`
//! Book: chapter "03 PCF" (`book/src/lesson_03.md`).

use std::collections::BTreeMap;

use common::app::{self, Lesson};
use common::gpu::Gpu;
use common::render::{FrameTargets, SceneGpu};
use common::scene::Scene;
use common::shadow_map::{self, ShadowMap, SlopeScaledBias};
use common::timing::Frame;
use common::Result;

/// Lesson 02's map size: the filters differ, the map does not.
const MAP_SIZE: u32 = 1024;

// ANCHOR: variants
/// How a variant turns the shadow map into a visibility.
#[derive(Clone, Copy, Debug)]
enum Filter {
    /// N×N nearest comparisons, averaged. `receiver_plane`: each tap
    /// compares with the receiver's plane there (receiver-plane depth bias).
    Grid { n: u32, receiver_plane: bool },
    /// One comparison through a linear-filtering comparison sampler: the
    /// hardware compares the 4 nearest texels and blends the answers.
    Hardware2x2,
    /// `taps` bilinear comparisons on a Poisson disk of `radius` texels,
    /// rotated per pixel.
    Poisson { taps: u32, radius: f32 },
    /// Average N×N stored depths, then compare once: filtering depth.
    DepthAverage { n: u32 },
}

fn variant_list() -> Vec<(&'static str, Filter)> {
    let grid = |n| Filter::Grid {
        n,
        receiver_plane: true,
    };
    vec![
        ("pcf_1x1", grid(1)),
        ("pcf_3x3", grid(3)), // the seed's 3×3 average
        ("pcf_5x5", grid(5)),
        ("pcf_7x7", grid(7)),
        (
            "pcf_7x7_flat",
            Filter::Grid {
                n: 7,
                receiver_plane: false,
            },
        ),
        ("hw_2x2", Filter::Hardware2x2),
        (
            "poisson_16",
            Filter::Poisson {
                taps: 16,
                radius: 2.5,
            },
        ),
        ("depth_avg_3x3", Filter::DepthAverage { n: 3 }),
    ]
}

impl Filter {
    /// Depth comparisons per pixel and light, and texels they read.
    fn taps(self) -> (u64, u64) {
        match self {
            Filter::Grid { n, .. } => ((n * n) as u64, (n * n) as u64),
            Filter::Hardware2x2 => (1, 4),
            Filter::Poisson { taps, .. } => (taps as u64, 4 * taps as u64),
            Filter::DepthAverage { n } => (1, (n * n) as u64),
        }
    }

    /// Linear filtering for the taps that blend 2×2 texels.
    fn sampler(self) -> wgpu::FilterMode {
        match self {
            Filter::Hardware2x2 | Filter::Poisson { .. } => wgpu::FilterMode::Linear,
            _ => wgpu::FilterMode::Nearest,
        }
    }
}
// ANCHOR_END: variants

/// `Filter` in lesson_03.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FilterUniform {
    mode: u32,
    n: u32,
    receiver_plane: u32,
    taps: u32,
    radius: f32,
    _pad: [f32; 3],
}

impl From<Filter> for FilterUniform {
    fn from(f: Filter) -> Self {
        let u = FilterUniform {
            mode: 0,
            n: 1,
            receiver_plane: 0,
            taps: 0,
            radius: 0.0,
            _pad: [0.0; 3],
        };
        match f {
            Filter::Grid { n, receiver_plane } => FilterUniform {
                n,
                receiver_plane: receiver_plane as u32,
                ..u
            },
            Filter::Hardware2x2 => FilterUniform { mode: 1, ..u },
            Filter::Poisson { taps, radius } => FilterUniform {
                mode: 2,
                taps,
                radius,
                receiver_plane: 1,
                ..u
            },
            Filter::DepthAverage { n } => FilterUniform { mode: 3, n, ..u },
        }
    }
}

struct Pcf {
    variants: Vec<(&'static str, Filter, wgpu::BindGroup)>,
    map: ShadowMap,
    nearest: wgpu::BindGroup,
    linear: wgpu::BindGroup,
    lit_pipeline: wgpu::RenderPipeline,
    /// Lesson 02's slope-scaled bias, one pipeline per light.
    shadow_pipelines: Vec<wgpu::RenderPipeline>,
}

impl Lesson for Pcf {
    const NAME: &'static str = "lesson_03";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_03.toml");

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
            shadow_map::shader_module(gpu, "lesson_03", include_str!("../shaders/lesson_03.wgsl"));
        let layout = shadow_map::shadow_map_layout_with(gpu, true);
        let filter_layout =
            shadow_map::uniform_layout(gpu, "filter", std::mem::size_of::<FilterUniform>() as u64);
        let lit_pipeline = scene.lit_pipeline(
            gpu,
            &module,
            "fs_lit",
            &[&layout, &filter_layout],
            Default::default(),
        );
        let map = ShadowMap::new(gpu, MAP_SIZE);
        let nearest =
            shadow_map::shadow_map_group_with(gpu, &layout, &map, wgpu::FilterMode::Nearest, true);
        let linear =
            shadow_map::shadow_map_group_with(gpu, &layout, &map, wgpu::FilterMode::Linear, true);
        let bias = SlopeScaledBias::RECOMMENDED;
        let shadow_pipelines = (0..scene.scene.lights.len())
            .map(|k| {
                shadow_map::shadow_pipeline(
                    gpu,
                    scene,
                    &module,
                    bias.pass_state(gpu, &scene.scene, k, MAP_SIZE),
                )
            })
            .collect();
        let variants = variant_list()
            .into_iter()
            .map(|(name, f)| {
                (
                    name,
                    f,
                    shadow_map::uniform_group(
                        gpu,
                        &filter_layout,
                        name,
                        bytemuck::bytes_of(&FilterUniform::from(f)),
                    ),
                )
            })
            .collect();
        Ok(Pcf {
            variants,
            map,
            nearest,
            linear,
            lit_pipeline,
            shadow_pipelines,
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
        let (_, filter, filter_group) = self
            .variants
            .iter()
            .find(|(n, ..)| *n == variant)
            .ok_or_else(|| anyhow::anyhow!("unknown variant {variant}"))?;
        let map_group = match filter.sampler() {
            wgpu::FilterMode::Linear => &self.linear,
            _ => &self.nearest,
        };
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for light in 0..scene.scene.lights.len() {
            let shadow = &self.shadow_pipelines[light];
            frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, shadow, &self.map, light, ts.render())
            });
            let groups = [map_group, filter_group];
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
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, variant: &str) -> BTreeMap<String, u64> {
        let filter = self
            .variants
            .iter()
            .find(|(n, ..)| *n == variant)
            .map(|(_, f, _)| *f);
        let (taps, texels) = filter.map_or((0, 0), Filter::taps);
        BTreeMap::from([
            ("taps".into(), taps),
            ("texels_read".into(), texels),
            ("shadow_map_size".into(), MAP_SIZE as u64),
        ])
    }
}

fn main() -> std::process::ExitCode {
    app::main::<Pcf>()
}
