//! # Lesson 09: cascaded shadow maps
//!
//! One shadow map over a large scene spends its texels evenly, while the
//! camera needs many near and few far (perspective aliasing). Cascades cut
//! the view frustum into K slices by depth and give each its own map, fitted
//! to that slice, all in one depth texture array. The lit pass picks the
//! cascade by the pixel's view depth. The variants keep the total texels
//! equal to one 2048² map and compare the split schemes, the two fits
//! (bounding sphere, tight box), texel snapping, the reach towards the
//! light, and blending across the splits. The cascades are fitted again on
//! every frame, from the camera as it is then (`[camera_path]`).
//!
//! The math is in [`cascades`], the GPU side in [`csm`] and
//! `shaders/lesson_09/csm.wgsl`; each cascade draws only the casters that
//! can shadow its receivers ([`caster_culling`]); the cascade count and
//! the split's λ are knobs ([`knobs`](workbook::lesson_09::knobs)). What
//! the runner measures and shows besides the image (draw calls, the shadow
//! passes' texels, texels per 100 m, the cascade each pixel samples) is in
//! `harness.rs`.
//!
//! Run: `cargo run --release --bin lesson_09 -- --headless`
//! Book: chapter "09 cascaded shadow maps" (`book/src/lesson_09.md`).

use clap::ValueEnum;
use common::gpu::lit::LitPass;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::run::lesson::{Capabilities, Lesson};
use common::run::per_variant::PerVariant;
use common::scene::Scene;
use common::Result;
use workbook::lesson_01::shadow_map::{self, ShadowPassState};
use workbook::lesson_01::tally::TallyShader;
use workbook::lesson_09::cascades::{self, Cascade, Fit, FitOptions, SplitScheme};
use workbook::lesson_09::caster_culling::{CasterCulling, Kept};
use workbook::lesson_09::csm::{self, CascadeLights, CascadeMaps};
use workbook::lesson_09::pipelines::{CsmPipelines, Shape};
use workbook::lesson_09::setup::{self, Exercise, Setup};

mod harness;

// ANCHOR: variants
/// Every variant spends about 2048² texels: K maps of 2048 / √K.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    /// Lesson 01's one map, fitted to the scene bounds: the baseline.
    #[value(name = "single_2048")]
    Single2048,
    /// Practical splits, sphere fit, snapped, reaching to the light.
    #[value(name = "k1")]
    K1,
    #[value(name = "k2")]
    K2,
    #[value(name = "k3")]
    K3,
    #[value(name = "k4")]
    K4,
    /// The other split schemes.
    #[value(name = "k4_uniform")]
    K4Uniform,
    #[value(name = "k4_log")]
    K4Log,
    /// The tight box, snapped (to its own, changing, texel size).
    #[value(name = "k4_aabb")]
    K4Aabb,
    /// The sphere, not snapped.
    #[value(name = "k4_nosnap")]
    K4NoSnap,
    /// The tight box, not snapped: the naive one.
    #[value(name = "k4_aabb_nosnap")]
    K4AabbNoSnap,
    /// The box only as deep as the sphere: casters outside it are lost.
    #[value(name = "k4_noextend")]
    K4NoExtend,
    /// k4, fading into the next cascade over the last 10 % of each.
    #[value(name = "k4_blend")]
    K4Blend,
    /// k4 drawing every caster into every cascade, over the whole map.
    #[value(name = "k4_nocull")]
    K4NoCull,
    // Then the chapter's exercises.
    // ANCHOR_END: variants
    /// Exercise 1: k4 with the student's `fitted_splits`.
    #[value(name = "exercise_practical_splits")]
    ExercisePracticalSplits,
    /// Exercise 2: k4_aabb with the student's `snap_tight_box`.
    #[value(name = "exercise_snap_tight_box")]
    ExerciseSnapTightBox,
}

// ANCHOR: setups
impl Variant {
    fn setup(self) -> Setup {
        let practical = SplitScheme::Practical {
            lambda: cascades::PRACTICAL_LAMBDA,
        };
        let best = FitOptions {
            fit: Fit::Sphere,
            snap: true,
            extend: true,
        };
        let k4 = Setup::cascaded(4, practical, best);
        match self {
            Variant::Single2048 => Setup::single(2048),
            Variant::K1 => Setup::cascaded(1, practical, best),
            Variant::K2 => Setup::cascaded(2, practical, best),
            Variant::K3 => Setup::cascaded(3, practical, best),
            Variant::K4 => k4,
            Variant::K4Uniform => Setup::cascaded(4, SplitScheme::Uniform, best),
            Variant::K4Log => Setup::cascaded(4, SplitScheme::Logarithmic, best),
            Variant::K4Aabb => k4.with_fit(Fit::Aabb, true, true),
            Variant::K4NoSnap => k4.with_fit(Fit::Sphere, false, true),
            Variant::K4AabbNoSnap => k4.with_fit(Fit::Aabb, false, true),
            Variant::K4NoExtend => k4.with_fit(Fit::Sphere, true, false),
            Variant::K4Blend => Setup { blend: 0.1, ..k4 },
            Variant::K4NoCull => Setup { cull: false, ..k4 },
            // The chapter's exercises (below).
            _ => self.exercise(),
        }
    }
}
// ANCHOR_END: setups

impl Variant {
    /// An exercise's setup: the lesson's variant it runs, with the
    /// student's function in place of the lesson's.
    fn exercise(self) -> Setup {
        let (base, exercise) = match self {
            Variant::ExercisePracticalSplits => (Variant::K4, Exercise::PracticalSplits),
            Variant::ExerciseSnapTightBox => (Variant::K4Aabb, Exercise::SnapTightBox),
            v => unreachable!("{v:?} is the lesson's own: Variant::setup has it"),
        };
        Setup {
            exercise: Some(exercise),
            ..base.setup()
        }
    }
}

struct Csm {
    shadow_pipeline: wgpu::RenderPipeline,
    tally_pipeline: [wgpu::RenderPipeline; 2],
    /// The lit pass and the cascade picture, per cascade count and blend.
    pipelines: CsmPipelines,
    layout: wgpu::BindGroupLayout,
    /// Per light: its cascades' matrices (shadow pass), its lit parameters.
    lights: Vec<CascadeLights>,
    /// Per light: its view of the objects, and per cascade of this frame,
    /// which objects the cascade draws.
    culling: Vec<CasterCulling>,
    kept: Vec<Vec<Kept>>,
    /// The scene's origin and bounds, found once ([`setup::SceneBox`]).
    scene_box: setup::SceneBox,
    params: Vec<wgpu::Buffer>,
    /// The arrays, one per (size, count), with one group per light.
    maps: Vec<(CascadeMaps, Vec<wgpu::BindGroup>)>,
    /// Each variant's cascades: its setup now, what its last frame fitted
    /// and what its shadow passes drew.
    variants: PerVariant<Variant, VariantCascades>,
    /// The scene's objects (for `draws`).
    objects: u64,
}

/// One variant's cascades: how it runs now, light 0's cascades of its
/// last frame, and what its shadow passes drew, counted once (first frame).
struct VariantCascades {
    /// [`Variant::setup`] with the knobs' values ([`Csm::setup`]).
    setup: Setup,
    /// Light 0's cascades of the variant's last frame, for the report.
    fitted: Option<Vec<Cascade>>,
    /// The shadow passes' depth writes and fragments.
    texels_written: Option<(u64, u64)>,
    /// The shadow passes' draws in the frame whose texels were counted
    /// (for `draws` and `casters_drawn`).
    caster_draws: Option<u64>,
}

impl VariantCascades {
    /// `variant` as named, not drawn nor counted yet.
    fn new(variant: Variant) -> VariantCascades {
        VariantCascades {
            setup: variant.setup(),
            fitted: None,
            texels_written: None,
            caster_draws: None,
        }
    }
}

impl Lesson for Csm {
    const NAME: &'static str = "lesson_09";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_09.toml");
    type Variant = Variant;
    // The cascades are fitted again every frame, to the view frustum made
    // from fov_y_deg and the aspect (no shift).
    const CAPABILITIES: Capabilities = Capabilities {
        camera_path: true,
        camera_shift: false,
        ..Capabilities::BASIC
    };

    fn check_scene(scene: &Scene) -> Result<()> {
        setup::refuse_non_directional(scene, Self::NAME)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let source = include_str!("../../shaders/lesson_09/csm.wgsl");
        let module = common::gpu::render::shader_module(gpu, "lesson_09", source);
        let state = ShadowPassState {
            cull: None,
            bias: setup::shadow_pass_bias(),
        };
        let layout = csm::csm_layout(gpu);
        let tally = TallyShader::new(gpu);
        let n = scene.scene.lights.len();
        let scene_box = setup::SceneBox::new(&scene.scene);
        Ok(Csm {
            shadow_pipeline: shadow_map::shadow_pipeline(gpu, scene, &module, state),
            tally_pipeline: shadow_map::shadow_tally_pipelines(gpu, scene, &module, state, &tally),
            pipelines: CsmPipelines::new(&module, &layout),
            lights: (0..n).map(|_| CascadeLights::new(gpu, scene)).collect(),
            culling: CasterCulling::for_lights(&scene.scene, scene_box.origin),
            kept: Vec::new(),
            scene_box,
            params: (0..n).map(|_| setup::params_buffer(gpu)).collect(),
            layout,
            maps: Vec::new(),
            variants: PerVariant::new(VariantCascades::new),
            objects: scene.scene.objects.len() as u64,
        })
    }

    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        let setup = self.setup(variant);
        let m = self.maps_for(frame.gpu, setup.resolution, setup.count);
        self.pipelines.make(frame.gpu, scene, Shape::of(&setup));
        let fits = self.fit_cascades(frame, scene, setup)?;
        self.choose_casters(frame, scene, setup, &fits);
        self.jitter_cascades(frame.gpu, scene, setup, &fits);
        // Light 0's cascades, for the report.
        self.variants[variant].fitted = fits.into_iter().next();
        self.count_once(frame, scene, setup, variant)?;
        self.cascade_passes(frame, scene, targets, setup, m);
        Ok(())
    }
}

impl Csm {
    // ANCHOR: fit_cascades
    /// Every light's cascades, fitted to the camera as it is now (it may
    /// have moved since the last frame) and uploaded: the shadow passes'
    /// matrices, and the lit pass's splits and matrices.
    fn fit_cascades(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        setup: Setup,
    ) -> Result<Vec<Vec<Cascade>>> {
        let (b, size, gpu) = (&self.scene_box, (scene.width, scene.height), frame.gpu);
        let mut fits = Vec::new();
        let lights = self.lights.iter_mut().zip(&self.params).enumerate();
        for (light, (lights, params)) in lights {
            let fit = frame.cpu("fit", || {
                let single = lights.light_view_proj(&scene.scene, light);
                let fit = setup.fit(&scene.scene, b, single, size, light)?;
                lights.write(gpu, scene, light, &fit);
                let p = setup.params(&scene.scene, b, size, &fit);
                gpu.queue.write_buffer(params, 0, bytemuck::bytes_of(&p));
                Ok::<_, anyhow::Error>(fit)
            })?;
            fits.push(fit);
        }
        Ok(fits)
    }
    // ANCHOR_END: fit_cascades

    /// Per light and cascade of `fits`, the casters the cascade draws
    /// ([`CasterCulling::casters`]): those that can shadow a surface the
    /// lit pass reads the cascade for, seen by the camera as the scene's
    /// uniforms hold it now; every caster where the variant does not cull.
    fn choose_casters(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        setup: Setup,
        fits: &[Vec<Cascade>],
    ) {
        let view = setup::lit_view(scene, self.scene_box.origin);
        let (res, band) = (setup.resolution, setup.blend as f64);
        self.kept = frame.cpu("cull", || {
            let culling = self.culling.iter().zip(fits);
            let kept = |(c, fit): (&CasterCulling, &Vec<Cascade>)| match setup.cull {
                true => c.casters(&view, fit, res, band),
                false => c.every_caster(fit.len(), res),
            };
            culling.map(kept).collect()
        });
    }

    // ANCHOR: cascade_passes
    /// A frame: per light, K shadow passes, one per layer of the array
    /// `m`, each drawing the casters its cascade keeps; then one lit pass
    /// that picks a layer per pixel.
    fn cascade_passes(
        &self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        setup: Setup,
        m: usize,
    ) {
        let (maps, groups) = &self.maps[m];
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for (light, (lights, group)) in self.lights.iter().zip(groups).enumerate() {
            for i in 0..setup.count {
                frame.pass("shadow", |enc, ts| {
                    let (p, kept) = (&self.shadow_pipeline, &self.kept[light][i]);
                    csm::cascade_pass(enc, scene, p, maps, lights, i, kept, ts.render())
                });
            }
            frame.pass("lighting", |enc, ts| {
                let group = [group];
                let made = self.pipelines.get(Shape::of(&setup));
                let pipeline = &made.expect("made by render").lit;
                let lit = LitPass::new(light, pipeline, &group);
                scene.lit_pass(enc, targets, lit, ts.render())
            });
        }
    }
    // ANCHOR_END: cascade_passes

    /// `variant`'s cascades as it runs now: [`Variant::setup`] with the
    /// knobs' values.
    fn setup(&self, variant: Variant) -> Setup {
        self.variants[variant].setup
    }

    /// The index of the array for `count` cascades of `size`², if made.
    fn find_maps(&self, size: u32, count: usize) -> Option<usize> {
        self.maps
            .iter()
            .position(|(m, _)| m.size == size && m.count == count)
    }

    /// The array for `count` cascades of `size`², made when first needed
    /// and shared by the variants of the same shape.
    fn maps_for(&mut self, gpu: &Gpu, size: u32, count: usize) -> usize {
        if let Some(m) = self.find_maps(size, count) {
            return m;
        }
        let maps = CascadeMaps::new(gpu, size, count);
        let groups = self
            .params
            .iter()
            .map(|p| csm::csm_group(gpu, &self.layout, &maps, p))
            .collect();
        self.maps.push((maps, groups));
        self.maps.len() - 1
    }
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<Csm>()
}
