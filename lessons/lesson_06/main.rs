//! # Lesson 06: z-fail with caps (Carmack's reverse)
//!
//! Lesson 05 counted the volume faces *in front of* the visible surface,
//! which misses the "enter" of a volume the eye is already inside. Z-fail
//! counts the faces *behind* it instead (back faces +1, front faces −1),
//! out to infinity, where nothing starts inside a volume. That needs closed
//! volumes: a front cap (the light-facing triangles) and a back cap (the
//! same triangles at infinity, reversed).
//!
//! Variants: `zpass_quads` (lesson 05, for contrast), `zfail_cpu`,
//! `zfail_quads` and `zfail_compute` (lesson 05's three ways to build the
//! volumes), `zfail_no_front_cap`
//! and `zfail_no_back_cap` (what a missing cap does), and `zfail_selective`
//! (z-fail only for casters whose volume can reach the near plane, z-pass
//! for the rest, nothing for casters whose volume cannot reach the view:
//! the same pixels for less work).
//!
//! Under a finite far plane, volumes at infinity would be clipped; each
//! caster's volume then ends at a finite back cap that covers the light's
//! range (`reach`), or the lesson refuses the scene in one line (lesson 07).
//!
//! Run: `cargo run --release --bin lesson_06 -- --headless`
//! Book: chapter "06 z-fail with caps" (`book/src/lesson_06.md`).

use clap::ValueEnum;
use common::glam::DVec3;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::Counts;
use common::measure::timing::Frame;
use common::run::lesson::{Capabilities, Lesson};
use common::run::per_variant::PerVariant;
use common::scene::{Far, LightKind};
use common::Result;
use workbook::lesson_05::extrusion::{world_light, CpuParts, Extrusion};
use workbook::lesson_05::stencil::{self, Counting, Method};
use workbook::lesson_05::stencil_lesson::{StencilLesson, VariantFrame};
use workbook::lesson_05::volumes::{base_and_lit_draws, CasterDraw, ShadowVolumes, VolumeCaster};
use workbook::lesson_06::caps::{self, zfail_counting};
use workbook::lesson_06::plan::{near_rectangle, plan, plan_with};
use workbook::lesson_06::reach::volume_reach;

mod harness;

// ANCHOR: variants
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    /// Lesson 05's z-pass, for contrast.
    #[value(name = "zpass_quads")]
    ZpassQuads,
    #[value(name = "zfail_cpu")]
    ZfailCpu,
    #[value(name = "zfail_quads")]
    ZfailQuads,
    /// Sides and caps written by a compute shader, drawn indirectly.
    #[value(name = "zfail_compute")]
    ZfailCompute,
    /// What a missing cap does.
    #[value(name = "zfail_no_front_cap")]
    ZfailNoFrontCap,
    #[value(name = "zfail_no_back_cap")]
    ZfailNoBackCap,
    /// Z-fail only where the near plane can be in shadow, z-pass elsewhere,
    /// nothing where the volume cannot reach the view.
    #[value(name = "zfail_selective")]
    ZfailSelective,
    // ANCHOR_END: variants
    /// Exercise 1: `zfail_selective` with your `needs_zfail`.
    #[value(name = "exercise_choose_method")]
    ExerciseChooseMethod,
    /// Exercise 2: `zfail_cpu` with the caps of your `volume_caps`.
    #[value(name = "exercise_light_cap")]
    ExerciseLightCap,
}

// ANCHOR: variant_draws
impl Variant {
    /// The draws of one light: which casters, counted how.
    fn draws(self, volumes: &ShadowVolumes, scene: &SceneGpu, light: usize) -> Vec<CasterDraw> {
        let mut draws = volumes.all(caps::zfail);
        match self {
            Variant::ZpassQuads => return volumes.all(CasterDraw::zpass),
            Variant::ZfailSelective => return plan(volumes, scene, light),
            Variant::ZfailNoFrontCap => draws.iter_mut().for_each(|d| d.front_cap = false),
            Variant::ZfailNoBackCap => draws.iter_mut().for_each(|d| d.back_cap = false),
            // Z-fail everywhere, both caps.
            _ => {}
        }
        draws
    }
}
// ANCHOR_END: variant_draws

impl Variant {
    fn extrusion(self) -> Extrusion {
        match self {
            Variant::ZfailCpu | Variant::ExerciseLightCap => Extrusion::Cpu,
            Variant::ZfailCompute => Extrusion::Compute,
            _ => Extrusion::Quads,
        }
    }

    /// The parts of the CPU path that an exercise's code builds.
    fn cpu_parts(self) -> CpuParts {
        match self {
            Variant::ExerciseLightCap => CpuParts {
                sides: None,
                caps: Some(workbook::exercise!(lesson_06::volume_caps)),
            },
            _ => CpuParts::default(),
        }
    }

    /// [`Variant::draws`], with the first exercise's `needs_zfail` in
    /// `zfail_selective`'s plan.
    fn draws_or_exercise(
        self,
        volumes: &ShadowVolumes,
        scene: &SceneGpu,
        light: usize,
    ) -> Vec<CasterDraw> {
        if self != Variant::ExerciseChooseMethod {
            return self.draws(volumes, scene, light);
        }
        let near_rect = near_rectangle(scene.camera.view_proj.as_dmat4());
        let l = world_light(scene, light);
        let models = scene.scene.relative_models();
        // The caster's vertices in world space (origin-relative).
        let needs_zfail = |c: &VolumeCaster| {
            let m = models[c.object].as_dmat4();
            let p = c.adjacency.positions.iter();
            let world: Vec<DVec3> = p.map(|p| m.transform_point3(p.as_dvec3())).collect();
            workbook::exercise!(lesson_06::needs_zfail(&world, l, &near_rect))
        };
        plan_with(volumes, scene, light, needs_zfail)
    }
}

struct ZFail {
    /// The volumes, the lit pipeline, the counts and the buffer view
    /// (lesson 05's [`StencilLesson`]).
    shadow: StencilLesson<Variant>,
    /// Computed once: mesh validation and the largest stencil count.
    scene_counters: Counts,
    /// Each variant's plan: `draws[light]`, which casters, counted how.
    plans: PerVariant<Variant, Vec<Vec<CasterDraw>>>,
    /// Draw calls of the base and lit passes.
    base_draws: u64,
    /// The camera and lights the reach and plans were made for.
    view: Vec<f64>,
}

/// Every variant's draws for every light.
fn plans(volumes: &ShadowVolumes, scene: &SceneGpu) -> PerVariant<Variant, Vec<Vec<CasterDraw>>> {
    // A finite reach puts the back cap where a view ray can cross it in
    // front of the surface: z-pass must then count it too.
    let finite = matches!(scene.scene.camera.far, Far::Finite(_));
    PerVariant::new(|v: Variant| {
        (0..scene.scene.lights.len())
            .map(|light| {
                let mut d = v.draws_or_exercise(volumes, scene, light);
                for d in d.iter_mut().filter(|d| d.method == Method::ZPass) {
                    d.back_cap |= finite;
                }
                d
            })
            .collect()
    })
}

/// What the reach and the plans depend on: the camera (far plane, frustum)
/// and the lights (their distance to each caster). In the window both move.
fn view_key(scene: &SceneGpu) -> Vec<f64> {
    let mut key: Vec<f64> = scene
        .camera
        .view_proj
        .to_cols_array()
        .map(f64::from)
        .to_vec();
    for l in &scene.scene.lights {
        key.extend(match l.kind {
            LightKind::Directional { direction } => direction.to_array(),
            LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
                position.to_array()
            }
        });
    }
    key
}

impl Lesson for ZFail {
    const NAME: &'static str = "lesson_06";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_06.toml");
    type Variant = Variant;
    /// Costs are counted on a variant's second frame (`harness.rs`).
    const CAPABILITIES: Capabilities = Capabilities {
        counted_on_frame: 2,
        ..Capabilities::BASIC
    };

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        // ANCHOR: reach
        // Each caster's volume gets a reach: infinity under far = "infinite",
        // the light's range under a finite far plane (or a one-line error).
        let counting = Counting {
            finite_reach: true,
            ..zfail_counting()
        };
        let mut volumes = ShadowVolumes::new(gpu, scene, &counting)?;
        let reach = volume_reach(scene, &volumes.casters)?;
        volumes.set_reach(gpu, reach);
        // ANCHOR_END: reach
        let lit = stencil::stencil_lit_pipeline(gpu, scene);
        Ok(ZFail {
            scene_counters: stencil::scene_counters(scene),
            plans: plans(&volumes, scene),
            shadow: StencilLesson::new(volumes, lit),
            base_draws: base_and_lit_draws(scene),
            view: view_key(scene),
        })
    }

    /// The frame is lesson 05's [`ShadowVolumes::shadow_frame`] (in
    /// [`StencilLesson::frame`]), each caster with its own method; around
    /// it, the plans and the counts.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        let key = view_key(scene);
        let volumes = &mut self.shadow.volumes;
        if key != self.view {
            // The window moved the camera or a light: redo reach and plans
            // (a reach that no longer fits the far plane ends the run).
            volumes.set_reach(frame.gpu, volume_reach(scene, &volumes.casters)?);
            self.plans = plans(volumes, scene);
            self.view = key;
        }
        let draws = &self.plans[variant];
        let v = VariantFrame {
            variant,
            extrusion: variant.extrusion(),
            parts: variant.cpu_parts(),
        };
        self.shadow.frame(frame, scene, targets, v, draws)?;
        Ok(())
    }
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<ZFail>()
}
