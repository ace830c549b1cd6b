//! # Lesson 08: depth bounds and scissor
//!
//! A point light of range r lights nothing outside its range sphere, yet
//! its shadow volumes run to infinity and cover much of the screen. Two
//! limits, both computed from the sphere ([`range_sphere`](workbook::lesson_08::range_sphere)), cut the volume
//! pass's work:
//!
//! - a scissor rectangle: the sphere's image on screen (`set_scissor_rect`);
//! - depth bounds: the sphere's window-depth interval [zmin, zmax]. Where the
//!   depth *stored* at a pixel is outside it, the surface there is out of
//!   range and its count cannot matter. wgpu has no depth-bounds test, so
//!   it is emulated with stencil bit 7 ([`bounds_test`](workbook::lesson_08::bounds_test)).
//!
//! A third limit works on objects, not pixels: a caster whose bounding
//! sphere misses the range sphere cannot shadow anything in range, so its
//! volume is left out ([`caster_reaches`](workbook::lesson_08::range_sphere::caster_reaches)).
//!
//! Variants: `unbounded`, `scissor`, `depth_bounds`, `bounds_scissor`,
//! `cull`, `cull_bounds_scissor`. The pixels are the same in all six; the
//! counters say how many volume triangles each one draws, and how many
//! fragments it rasterises and lets through to the stencil. The scissor
//! cuts the lit pass as well. Each of the six takes the three limits as
//! toggles (knobs `scissor`, `depth_bounds`, `cull`): it starts as its name
//! says.
//!
//! A finite far plane is clamped, not clipped, as in lesson 07's `clamp`
//! (needs DEPTH_CLIP_CONTROL). Bit 7 holds the bounds mark, so the count
//! wraps at 128 ([`count_bits`]).
//!
//! Run: `cargo run --release --bin lesson_08 -- --headless`
//! Book: chapter "08 depth bounds" (`book/src/lesson_08.md`).

use clap::ValueEnum;
use common::glam::DVec3;
use common::gpu::lit::LitPass;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::Counts;
use common::measure::timing::Frame;
use common::run::lesson::{Capabilities, Lesson};
use common::run::per_variant::PerVariant;
use common::scene::Far;
use common::Result;
use workbook::lesson_05::extrusion::{volume_shader_module, Extrusion};
use workbook::lesson_05::volumes::ShadowVolumes;
use workbook::lesson_06::caps::zfail_counting;
use workbook::lesson_08::bounds_test::{bounded_lit_stencil, BoundedLight, BoundedVolumes, Limits};
use workbook::lesson_08::costs::VolumeTally;
use workbook::lesson_08::count_bits;
use workbook::lesson_08::exercise_bounds::{exercise_bounds, Student};
use workbook::lesson_08::range_sphere::{all_bounds, range_spheres, LightBounds, RangeSphere};

mod harness;
use harness::VariantCounts;

// ANCHOR: variants
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    #[value(name = "unbounded")]
    Unbounded,
    #[value(name = "scissor")]
    Scissor,
    #[value(name = "depth_bounds")]
    DepthBounds,
    #[value(name = "bounds_scissor")]
    BoundsScissor,
    /// Only the casters that reach into the light's range cast volumes.
    #[value(name = "cull")]
    Cull,
    /// The cull, the depth bounds and the scissor together.
    #[value(name = "cull_bounds_scissor")]
    CullBoundsScissor,
    // ANCHOR_END: variants
    /// Exercise 1: spot lights scissored to `exercises::cone_sphere`.
    #[value(name = "exercise_scissor_rect")]
    ExerciseScissorRect,
    /// Exercise 2: spot lights depth-bounded by `exercises::cone_depth_bounds`.
    #[value(name = "exercise_depth_bounds")]
    ExerciseDepthBounds,
}

// ANCHOR: variant_limits
impl Variant {
    /// Which of the three limits the variant's volume pass uses.
    fn limits(self) -> Limits {
        use Variant::*;
        Limits {
            scissor: matches!(self, Scissor | BoundsScissor | CullBoundsScissor),
            depth_bounds: matches!(self, DepthBounds | BoundsScissor | CullBoundsScissor),
            cull: matches!(self, Cull | CullBoundsScissor),
        }
    }
}
// ANCHOR_END: variant_limits

impl Variant {
    /// [`Variant::limits`]; an exercise's are those its code bounds.
    fn limits_or_exercise(self) -> Limits {
        match self {
            Variant::ExerciseScissorRect => Limits {
                scissor: true,
                ..Limits::default()
            },
            Variant::ExerciseDepthBounds => Limits {
                depth_bounds: true,
                ..Limits::default()
            },
            _ => self.limits(),
        }
    }

    /// Every light's bounds: its range sphere's, or for an exercise, with
    /// one of them from the student's code.
    fn bounds(self, scene: &SceneGpu, spheres: &[RangeSphere]) -> Vec<Option<Option<LightBounds>>> {
        match self {
            Variant::ExerciseScissorRect => exercise_bounds(scene, spheres, Student::Scissor),
            Variant::ExerciseDepthBounds => exercise_bounds(scene, spheres, Student::DepthBounds),
            _ => all_bounds(scene, spheres),
        }
    }
}

/// Each light's bounded volume pass for a variant.
fn bounded_lights(
    spheres: &[RangeSphere],
    bounds: &[Option<Option<LightBounds>>],
    limits: Limits,
) -> Vec<BoundedLight> {
    (spheres.iter().zip(bounds).enumerate())
        .map(|(light, (&sphere, &bounds))| BoundedLight {
            light,
            sphere,
            bounds,
            limits,
        })
        .collect()
}

struct DepthBounds {
    bounded: BoundedVolumes,
    /// The counting copies of the volume pass ([`VolumeTally::count`]).
    tally: VolumeTally,
    volumes: ShadowVolumes,
    lit_pipeline: wgpu::RenderPipeline,
    /// The scene's origin, found once (a pass over every vertex; objects
    /// do not move), and the last frame's range spheres and bounds.
    origin: DVec3,
    spheres: Vec<RangeSphere>,
    bounds: Vec<Option<Option<LightBounds>>>,
    /// Computed once: mesh validation and the largest stencil count.
    scene_counters: Counts,
    /// What each variant counted, on its second frame ([`VariantCounts`]).
    counted: PerVariant<Variant, VariantCounts>,
    /// The last frame's depth-stencil texture, for the window's buffer view.
    depth_stencil: Option<wgpu::Texture>,
    /// Each variant's limits, with the knobs' values ([`Variant::limits`]
    /// when no knob was set).
    limits: PerVariant<Variant, Limits>,
}

impl Lesson for DepthBounds {
    const NAME: &'static str = "lesson_08";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_08.toml");
    type Variant = Variant;
    /// Costs are counted on a variant's second frame (`harness.rs`). The
    /// scissor rectangles read only the projection's diagonal: no shifted
    /// camera.
    const CAPABILITIES: Capabilities = Capabilities {
        counted_on_frame: 2,
        camera_shift: false,
        ..Capabilities::BASIC
    };

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let volumes = ShadowVolumes::new(gpu, scene, &zfail_counting())?;
        if let Some(why) = volumes.unfit(Extrusion::Quads) {
            // Every variant here draws the quads.
            anyhow::bail!("{why}: lesson_05's zpass_cpu builds volumes this size");
        }
        // A finite far plane would clip the volumes' ends at infinity: clamp
        // depth instead, as lesson 07's `clamp` variant does.
        let unclipped_depth = scene.scene.camera.far != Far::Infinite;
        let origin = scene.scene.origin();
        let spheres = range_spheres(&scene.scene, origin);
        let module = volume_shader_module(
            gpu,
            "lesson_08",
            include_str!("../../shaders/lesson_08/range.wgsl"),
        );
        Ok(DepthBounds {
            bounded: BoundedVolumes::new(gpu, scene, &volumes, unclipped_depth)?,
            tally: VolumeTally::new(gpu, scene, unclipped_depth),
            lit_pipeline: scene.lit_pipeline(
                gpu,
                &module,
                "fs_lit_range",
                &[],
                bounded_lit_stencil(),
            ),
            bounds: all_bounds(scene, &spheres),
            origin,
            spheres,
            scene_counters: count_bits::scene_counters(scene),
            volumes,
            counted: PerVariant::new(|_| VariantCounts::default()),
            depth_stencil: None,
            limits: PerVariant::new(Variant::limits_or_exercise),
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
        // Per frame (the lights may move): each light's range sphere →
        // its bounds and scissor, uploaded.
        let (gpu, bounded) = (frame.gpu, &self.bounded);
        let (spheres, bounds) = frame.cpu("bounds", || {
            let spheres = range_spheres(&scene.scene, self.origin);
            let bounds = variant.bounds(scene, &spheres);
            bounded.write_bounds(gpu, &bounds);
            (spheres, bounds)
        });
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for b in bounded_lights(&spheres, &bounds, self.limits[variant]) {
            frame.pass("volume", |enc, ts| {
                self.bounded
                    .volume_pass(enc, scene, targets, b, ts.render())
            });
            // The scissor cuts the lit pass too: outside the sphere's
            // rectangle the light adds nothing (fs_lit_range discards).
            let mut lit = LitPass::new(b.light, &self.lit_pipeline, &[]);
            if b.limits.scissor {
                match b.bounds {
                    Some(Some(lb)) => {
                        let s = lb.scissor;
                        lit = lit.scissored([s.x, s.y, s.width, s.height]);
                    }
                    Some(None) => lit = lit.scissored([0; 4]), // off screen
                    None => {}                                 // directional: everywhere
                }
            }
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(enc, targets, lit, ts.render())
            });
        }
        (self.spheres, self.bounds) = (spheres, bounds);
        // What the "buffer" view reads: this frame's stencil.
        self.depth_stencil = Some(targets.depth.clone());
        // Counted on the variant's second frame (`harness.rs`).
        self.after_frame(frame, scene, targets, variant)
    }
    // ANCHOR_END: render
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<DepthBounds>()
}
