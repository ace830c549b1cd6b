//! # Lesson 07: depth clamp and infinite extrusion
//!
//! Z-fail (lesson 06) counts volume faces *behind* the visible surface, out
//! to the back cap, which lies at infinity (w = 0). A finite far plane clips
//! it away, and the counts come out wrong. Two cures, compared here:
//!
//! - `clamp`: keep the finite projection but clamp depth instead of
//!   clipping it (`unclipped_depth`, wgpu's `DEPTH_CLIP_CONTROL`, the
//!   GL_DEPTH_CLAMP of the original technique). Where the adapter lacks
//!   it, the variant fails with one line naming it.
//! - `infinite`: move the far plane to infinity (Everitt & Kilgard), with an
//!   ε that keeps points at infinity strictly inside depth 1
//!   ([`infinite_far`](workbook::lesson_07::infinite_far)).
//!
//! `neither` shows the failure. The lesson also measures what each choice
//! costs in depth precision ([`precision_study`](workbook::lesson_07::precision_study):
//! `depth_precision.md/.csv/.png/.svg`), and `reversed_z` keeps the far
//! plane at infinity with reversed depth in Depth32Float
//! ([`reversed_z`](workbook::lesson_07::reversed_z)), exact on deep ranges.
//!
//! Run: `cargo run --release --bin lesson_07 -- --headless`
//! Book: chapter "07 depth clamp and infinite extrusion" (`book/src/lesson_07.md`).

use std::cell::Cell;

use clap::ValueEnum;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::Counts;
use common::measure::timing::Frame;
use common::run::lesson::{Capabilities, Lesson};
use common::run::per_variant::PerVariant;
use common::scene::{Far, Scene};
use common::{anyhow, Result};
use workbook::lesson_05::extrusion::Extrusion;
use workbook::lesson_05::stencil::{self, Counting};
use workbook::lesson_05::volumes::{CasterDraw, ShadowVolumes};
use workbook::lesson_06::caps::{self, zfail_counting};
use workbook::lesson_07::exercise_cameras as cameras;
use workbook::lesson_07::infinite_far::{infinite_scene, DepthMapping};
use workbook::lesson_07::reversed_z::ReversedZ;

mod harness;
use harness::VariantCounts;

// ANCHOR: variants
/// The three ways to treat the back cap at infinity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    /// A finite far plane clips the back cap.
    #[value(name = "neither")]
    Neither,
    /// Depth clamped instead of clipped.
    #[value(name = "clamp")]
    Clamp,
    /// The far plane at infinity.
    #[value(name = "infinite")]
    Infinite,
    /// Reversed-Z in Depth32Float, far plane at infinity.
    #[value(name = "reversed_z")]
    ReversedZ,
    // ANCHOR_END: variants
    /// Exercise 1: your off-centre infinite projection (`exercises::infinite_frustum`).
    #[value(name = "exercise_infinite_projection")]
    ExerciseInfiniteProjection,
    /// Exercise 2: the infinite far plane, near fitted to the scene
    /// (`exercises::adaptive_near`).
    #[value(name = "exercise_adaptive_near")]
    ExerciseAdaptiveNear,
}

impl Variant {
    /// The depth mapping of the variant's camera.
    fn mapping(self) -> DepthMapping {
        match self {
            Variant::Infinite => DepthMapping::Infinite,
            Variant::ReversedZ => DepthMapping::InfiniteReversed,
            Variant::Neither | Variant::Clamp => DepthMapping::Standard,
            Variant::ExerciseInfiniteProjection | Variant::ExerciseAdaptiveNear => {
                DepthMapping::Infinite
            }
        }
    }

    /// An exercise's camera (`None`: not an exercise).
    fn exercise(self) -> Option<ExerciseCamera> {
        match self {
            Variant::ExerciseInfiniteProjection => Some(cameras::infinite_projection_scene),
            Variant::ExerciseAdaptiveNear => Some(cameras::adaptive_near_scene),
            _ => None,
        }
    }
}

/// Makes an exercise's camera: a second `SceneGpu` with its projection.
type ExerciseCamera = fn(&Gpu, &SceneGpu) -> Result<SceneGpu>;

/// One way of drawing: the scene (camera), its volumes and lit pipeline.
struct Route {
    volumes: ShadowVolumes,
    lit: wgpu::RenderPipeline,
}

// ANCHOR: render
/// One frame of lesson 06's z-fail with pre-built quads, both caps for
/// every caster, seen through `sg`'s camera and drawn with `route`'s
/// volumes: lesson 05's frame. Returns the draws, per light.
fn zfail_frame(
    frame: &mut Frame,
    sg: &SceneGpu,
    targets: &FrameTargets,
    route: &mut Route,
) -> Result<Vec<Vec<CasterDraw>>> {
    // Z-fail everywhere, both caps: the back cap is the one at infinity.
    let draws: Vec<Vec<CasterDraw>> = (0..sg.scene.lights.len())
        .map(|_| route.volumes.all(caps::zfail))
        .collect();
    let (ext, lit) = (Extrusion::Quads, &route.lit);
    (route.volumes).shadow_frame(frame, sg, targets, ext, &draws, lit)?;
    Ok(draws)
}
// ANCHOR_END: render

impl Route {
    /// Z-fail volumes; `unclipped_depth` clamps depth instead of clipping.
    fn new(gpu: &Gpu, scene: &SceneGpu, unclipped_depth: bool) -> Result<Route> {
        let counting = Counting {
            unclipped_depth,
            ..zfail_counting()
        };
        let volumes = ShadowVolumes::new(gpu, scene, &counting)?;
        if let Some(why) = volumes.unfit(Extrusion::Quads) {
            // Every variant here draws the quads.
            anyhow::bail!("{why}: lesson_05's zpass_cpu builds volumes this size");
        }
        Ok(Route {
            volumes,
            lit: stencil::stencil_lit_pipeline(gpu, scene),
        })
    }
}

struct DepthClamp {
    finite: Route,
    /// `Err` (one line) where the adapter lacks DEPTH_CLIP_CONTROL.
    clamp: std::result::Result<Route, String>,
    infinite_scene: SceneGpu,
    infinite: Route,
    /// `Err` (one line) where the adapter lacks Depth32FloatStencil8.
    reversed: std::result::Result<ReversedZ, String>,
    /// Computed once: mesh validation and the largest stencil count.
    scene_counters: Counts,
    /// What each variant counted: depth precision, casters drawn, the
    /// volumes' costs ([`VariantCounts`]).
    counts: PerVariant<Variant, VariantCounts>,
    /// Whether the depth-precision study's files are written (once a run).
    study_written: Cell<bool>,
    /// Each exercise's camera and volumes, made when first drawn (`None`
    /// for the lesson's own variants).
    exercises: PerVariant<Variant, Option<(SceneGpu, Route)>>,
    /// The last frame's depth-stencil texture (the runner's), for the
    /// window's buffer view; `reversed_z` draws into its own.
    depth_stencil: Option<wgpu::Texture>,
}

impl Lesson for DepthClamp {
    const NAME: &'static str = "lesson_07";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_07.toml");
    type Variant = Variant;
    /// Costs are counted on a variant's second frame (`harness.rs`).
    const CAPABILITIES: Capabilities = Capabilities {
        counted_on_frame: 2,
        ..Capabilities::BASIC
    };

    fn check_scene(scene: &Scene) -> Result<()> {
        if scene.camera.far == Far::Infinite {
            anyhow::bail!("camera.far: lesson_07 compares a finite far plane with clamping and an infinite one; give a finite far");
        }
        Ok(())
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let infinite_scene = infinite_scene(gpu, scene)?;
        let clamp = Route::new(gpu, scene, true).map_err(|e| {
            format!("variant \"clamp\": {e}; run --variant neither --variant infinite")
        });
        // Depth precision for this scene's near/far, each variant's mapping.
        let counts = harness::precision_counts(gpu, scene)?;
        let reversed = ReversedZ::new(gpu, scene).map_err(|e| {
            format!("variant \"reversed_z\": {e}; or run --variant clamp --variant infinite")
        });
        Ok(DepthClamp {
            reversed,
            finite: Route::new(gpu, scene, false)?,
            clamp,
            infinite: Route::new(gpu, &infinite_scene, false)?,
            infinite_scene,
            scene_counters: stencil::scene_counters(scene),
            counts,
            study_written: Cell::new(false),
            exercises: PerVariant::new(|_| None),
            depth_stencil: None,
        })
    }

    /// The variant's camera and volumes drawn by [`zfail_frame`]; around
    /// it, the exercises' cameras and the counts.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        // What the "buffer" view reads: this frame's stencil.
        self.depth_stencil = Some(targets.depth.clone());
        if variant == Variant::ReversedZ {
            let r = self.reversed.as_mut().map_err(|e| anyhow::anyhow!("{e}"))?;
            r.render(frame, scene, targets, &self.infinite.volumes);
            let casters = self.infinite.volumes.casters.len() * r.scene.scene.lights.len();
            self.counts[variant].reversed_frame(casters as u64);
            return Ok(());
        }
        if let Some(camera) = variant.exercise() {
            if self.exercises[variant].is_none() {
                let sg = camera(frame.gpu, scene)?;
                let route = Route::new(frame.gpu, &sg, false)?;
                self.counts[variant].camera_made(variant, scene);
                self.exercises[variant] = Some((sg, route));
            }
        }
        // The runner's sub-pixel move (`--fragile`) reaches the cameras
        // this lesson makes for itself.
        self.infinite_scene.set_jitter(frame.gpu, scene.jitter);
        for (sg, _) in self.exercises.values_mut().flatten() {
            sg.set_jitter(frame.gpu, scene.jitter);
        }
        let (sg, route): (&SceneGpu, &mut Route) = match variant {
            Variant::ReversedZ => unreachable!("drawn above"),
            Variant::ExerciseInfiniteProjection | Variant::ExerciseAdaptiveNear => {
                let (sg, route) = self.exercises[variant].as_mut().expect("made above");
                (sg, route)
            }
            Variant::Neither => (scene, &mut self.finite),
            Variant::Clamp => (
                scene,
                self.clamp.as_mut().map_err(|e| anyhow::anyhow!("{e}"))?,
            ),
            Variant::Infinite => (&self.infinite_scene, &mut self.infinite),
        };
        let draws = zfail_frame(frame, sg, targets, route)?;
        (self.counts[variant]).after_frame(frame.gpu, sg, targets, &route.volumes, &draws)
    }
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<DepthClamp>()
}
