//! # Lesson 01: the depth map
//!
//! A directional light renders the scene's depth into a shadow map (the
//! shadow pass); the lit pass then asks, for each pixel, whether the surface
//! is farther from the light than what the map stored. No bias yet: the
//! report measures the acne that lesson 02 fixes.
//!
//! The technique is in [`shadow_map`] (the map, the shadow pass, how the lit
//! pass samples it) and `shaders/lesson_01/`. The map's size is a knob of
//! the `res_*` variants (`map_size_log2`).
//!
//! Run: `cargo run --release --bin lesson_01 -- --headless`
//! Book: chapter "01 depth map" (`book/src/lesson_01.md`).

use clap::ValueEnum;
use common::gpu::lit::LitPass;
use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::run::lesson::{Capabilities, Lesson};
use common::run::per_variant::PerVariant;
use common::scene::Scene;
use common::Result;
use workbook::lesson_01::exercise_pass;
use workbook::lesson_01::shadow_map::{self, ShadowMap, ShadowPassState};
use workbook::lesson_01::tally::TallyShader;

mod harness;

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
    // ... then the two exercises' variants, at 1024² (the chapter's end).
    // ANCHOR_END: variants
    /// Exercise 1: the student's light box (`exercises::fit_light_box`), 1024².
    #[value(name = "exercise_tight_frustum")]
    ExerciseTightFrustum,
    /// Exercise 2: the student's shadow test (`depth_compare`), 1024².
    #[value(name = "exercise_depth_compare")]
    ExerciseDepthCompare,
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
            Variant::ExerciseTightFrustum | Variant::ExerciseDepthCompare => 1024,
        }
    }
}

struct DepthMap {
    shadow_pipeline: wgpu::RenderPipeline,
    /// The shadow pipeline that counts its depth writes (`shadow_texels_written`).
    tally_pipeline: [wgpu::RenderPipeline; 2],
    draws: u64,
    lit_pipeline: wgpu::RenderPipeline,
    /// Each variant's shadow map, and what its shadow pass wrote.
    maps: PerVariant<Variant, VariantMap>,
    /// Light 0's texel at the scene's centre for a 1-texel map, in world
    /// units along the map's u and v: a map of N texels divides it by N.
    texel_at_1: Option<(f64, f64)>,
    /// The shadow map's layout, for the exercise's lit pipeline.
    map_layout: wgpu::BindGroupLayout,
    /// `exercise_depth_compare`'s lit pipeline, compiled when it first runs.
    exercise_lit: Option<wgpu::RenderPipeline>,
    /// Its group 3: the map it reads as plain floats.
    exercise_depths: Option<wgpu::BindGroup>,
    /// Per light, `exercise_tight_frustum`'s view-projection, and whether
    /// the light buffer holds it now (the other variants restore the lesson's).
    tight: Vec<Option<common::glam::Mat4>>,
    tight_written: bool,
    /// [`DepthMap::texel_at_1`] with `exercise_tight_frustum`'s matrix.
    tight_texel_at_1: Option<(f64, f64)>,
}

/// A variant's shadow map, its bind group, and the shadow pass's depth
/// writes and fragments into it, counted once.
struct VariantMap {
    map: ShadowMap,
    group: wgpu::BindGroup,
    texels_written: Option<(u64, u64)>,
}

impl VariantMap {
    /// A map of `size`² texels, sampled nearest, not counted yet.
    fn new(gpu: &Gpu, layout: &wgpu::BindGroupLayout, size: u32) -> VariantMap {
        let map = ShadowMap::new(gpu, size);
        let group = shadow_map::shadow_map_group(gpu, layout, &map, wgpu::FilterMode::Nearest);
        VariantMap {
            map,
            group,
            texels_written: None,
        }
    }
}

impl Lesson for DepthMap {
    const NAME: &'static str = "lesson_01";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_01.toml");
    type Variant = Variant;
    // The light's box fits the scene bounds, not the camera: a camera
    // path (chapter 09's shimmer) needs nothing re-fitted (but
    // exercise_tight_frustum, fitted to the camera, is each frame).
    const CAPABILITIES: Capabilities = Capabilities {
        camera_path: true,
        ..Capabilities::BASIC
    };

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
        let tally = TallyShader::new(gpu);
        let tally_pipeline = shadow_map::shadow_tally_pipelines(
            gpu,
            scene,
            &module,
            ShadowPassState::default(),
            &tally,
        );
        let lit_pipeline =
            scene.lit_pipeline(gpu, &module, "fs_lit", &[&layout], Default::default());
        let maps = PerVariant::new(|v: Variant| VariantMap::new(gpu, &layout, v.resolution()));
        let tight: Vec<_> = (0..scene.scene.lights.len())
            .map(|k| {
                exercise_pass::tight_light_view_proj(&scene.scene, k, scene.width, scene.height)
            })
            .collect();
        Ok(DepthMap {
            shadow_pipeline,
            tally_pipeline,
            draws: shadow_map::shadow_map_draws(scene),
            lit_pipeline,
            maps,
            texel_at_1: texel_at_1(
                &scene.scene,
                common::scene::camera::light_view_proj(&scene.scene, 0),
            ),
            map_layout: layout,
            exercise_lit: None,
            exercise_depths: None,
            tight_texel_at_1: texel_at_1(&scene.scene, tight.first().copied().flatten()),
            tight,
            tight_written: false,
        })
    }

    /// The harness around [`DepthMap::draw`]: the exercises' setup, the
    /// shadow pass's depth writes counted once per variant (their own
    /// submits, before the frame), and the lit pipeline the variant uses.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        self.exercise_setup(frame.gpu, scene, variant)?;
        if self.maps[variant].texels_written.is_none() {
            // In a web page the count comes back a frame or more later.
            let n = later(|| {
                shadow_map::count_shadow_texels(frame.gpu, scene, self.resolution(variant), |_| {
                    &self.tally_pipeline
                })
            })?;
            self.maps[variant].texels_written = n;
        }
        let VariantMap { map, group, .. } = &self.maps[variant];
        let (lit, groups) = match (variant, &self.exercise_lit, &self.exercise_depths) {
            (Variant::ExerciseDepthCompare, Some(lit), Some(depths)) => (lit, vec![group, depths]),
            _ => (&self.lit_pipeline, vec![group]),
        };
        self.draw(frame, scene, targets, map, lit, &groups);
        Ok(())
    }
}

impl DepthMap {
    // ANCHOR: render
    /// One frame: the base pass, then per light the shadow pass into `map`
    /// and the lit pass, whose `groups` start with the map's (group 2).
    fn draw(
        &self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        map: &ShadowMap,
        lit: &wgpu::RenderPipeline,
        groups: &[&wgpu::BindGroup],
    ) {
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for light in 0..scene.scene.lights.len() {
            // Pass 1: depth from the light. Pass 2: compare and add the light.
            frame.pass("shadow", |enc, ts| {
                shadow_map::shadow_pass(enc, scene, &self.shadow_pipeline, map, light, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(enc, targets, LitPass::new(light, lit, groups), ts.render())
            });
        }
    }
    // ANCHOR_END: render

    /// The side of `variant`'s map now: [`Variant::resolution`], or the
    /// `map_size_log2` knob's.
    fn resolution(&self, variant: Variant) -> u32 {
        self.maps[variant].map.size
    }

    /// Before an exercise runs: its light matrix into the light buffer
    /// (`exercise_tight_frustum`; the others put the lesson's back), moved
    /// as the runner moves the map (`--fragile`), and its lit pipeline
    /// (`exercise_depth_compare`).
    fn exercise_setup(&mut self, gpu: &Gpu, scene: &SceneGpu, variant: Variant) -> Result<()> {
        let tight = variant == Variant::ExerciseTightFrustum;
        if tight {
            // Fitted to the camera: re-fit to where it is now (a camera path).
            self.tight = (0..scene.scene.lights.len())
                .map(|k| {
                    exercise_pass::tight_light_view_proj(&scene.scene, k, scene.width, scene.height)
                })
                .collect();
            self.tight_texel_at_1 = texel_at_1(&scene.scene, self.tight.first().copied().flatten());
        }
        // The runner's sub-texel move of the map (`--fragile`), drawn and read.
        let jitter = scene.light_jitter.matrix(self.resolution(variant));
        let jittered = jitter != common::glam::Mat4::IDENTITY;
        if tight || self.tight_written || jittered {
            for (k, m) in self.tight.iter().enumerate() {
                let lesson = common::scene::camera::light_view_proj(&scene.scene, k);
                let m = if tight { *m } else { lesson };
                scene.write_light_view_proj(gpu, k, jitter * m.unwrap_or_default());
            }
            self.tight_written = tight || jittered;
        }
        if variant == Variant::ExerciseDepthCompare && self.exercise_lit.is_none() {
            let depths = exercise_pass::depths_layout(gpu);
            let p = exercise_pass::depth_compare_pipeline(gpu, scene, &self.map_layout, &depths)?;
            self.exercise_lit = Some(p);
            let map = &self.maps[variant].map;
            self.exercise_depths = Some(exercise_pass::depths_group(gpu, &depths, map));
        }
        Ok(())
    }
}

/// Light 0's texel sides for a 1-texel map at the scene's centre, with
/// light matrix `m`: a texel is 2/N of NDC, and x_ndc = (row 0 · p) / w,
/// so it is 2w / (N |row 0|).
fn texel_at_1(scene: &Scene, m: Option<common::glam::Mat4>) -> Option<(f64, f64)> {
    if scene.lights.is_empty() {
        return None;
    }
    let m = m?.as_dmat4();
    let row = |i: usize| m.row(i).truncate().length();
    let w = m.w_axis.w; // at the origin-relative centre, p = 0
    Some((2.0 * w / row(0), 2.0 * w / row(1)))
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<DepthMap>()
}
