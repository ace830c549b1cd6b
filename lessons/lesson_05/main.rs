//! # Lesson 05: z-pass stencil shadow volumes
//!
//! Each caster's silhouette, seen from the light, is extruded to infinity
//! (w = 0) into a closed *shadow volume*. Counting, along the view ray, the
//! volume faces in front of the visible surface (front faces +1, back
//! faces −1) gives the number of volumes the surface is inside: 0 is lit.
//! Exact while the eye is outside every volume; the report measures what
//! happens when it is not (`--scene scenes/volume_eye_in_umbra.toml`).
//!
//! Three ways to build the volumes, timed against each other: silhouettes
//! on the CPU every frame (`zpass_cpu`), degenerate quads built once and
//! extruded in the vertex shader (`zpass_quads`), and the CPU route's
//! triangles written by a compute shader and drawn indirectly
//! (`zpass_compute`).
//!
//! Run: `cargo run --release --bin lesson_05 -- --headless`
//! Book: chapter "05 z-pass stencil shadow volumes" (`book/src/lesson_05.md`).

use clap::ValueEnum;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::Counts;
use common::measure::timing::Frame;
use common::run::lesson::{Capabilities, Lesson};
use common::Result;
use workbook::lesson_05::cull::kept_draws;
use workbook::lesson_05::extrusion::{CpuParts, Extrusion};
use workbook::lesson_05::stencil::{self, Counting};
use workbook::lesson_05::stencil_lesson::{StencilLesson, VariantFrame};
use workbook::lesson_05::volumes::{base_and_lit_draws, CasterDraw, ShadowVolumes};

mod harness;

// ANCHOR: variants
/// The variants differ in how the volume geometry is built, not in what
/// it is: all count with z-pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    /// Silhouettes found on the CPU every frame.
    #[value(name = "zpass_cpu")]
    ZpassCpu,
    /// Degenerate quads built once, extruded in the vertex shader.
    #[value(name = "zpass_quads")]
    ZpassQuads,
    /// Silhouettes and sides written by a compute shader, drawn indirectly.
    #[value(name = "zpass_compute")]
    ZpassCompute,
    // ANCHOR_END: variants
    /// Exercise 1: `zpass_cpu` with your `silhouette_edges_in_view`.
    #[value(name = "exercise_edges_in_view")]
    ExerciseEdgesInView,
    /// Exercise 2: `zpass_cpu` drawing only the casters your
    /// `volume_can_matter` keeps.
    #[value(name = "exercise_skip_casters")]
    ExerciseSkipCasters,
}

impl Variant {
    fn extrusion(self) -> Extrusion {
        match self {
            Variant::ZpassQuads => Extrusion::Quads,
            Variant::ZpassCompute => Extrusion::Compute,
            _ => Extrusion::Cpu,
        }
    }

    /// The parts of the CPU path that an exercise's code builds.
    fn cpu_parts(self) -> CpuParts {
        match self {
            Variant::ExerciseEdgesInView => CpuParts {
                sides: Some(workbook::exercise!(lesson_05::silhouette_edges_in_view)),
                caps: None,
            },
            _ => CpuParts::default(),
        }
    }
}

struct ZPass {
    /// The volumes, the lit pipeline, the counts and the buffer view.
    shadow: StencilLesson<Variant>,
    /// `draws[light]`: every caster, z-pass, sides only.
    draws: Vec<Vec<CasterDraw>>,
    /// The same, of the casters `exercise_skip_casters` keeps (per frame).
    kept: Vec<Vec<CasterDraw>>,
    /// Computed once: mesh validation and the largest stencil count.
    scene_counters: Counts,
    /// The casters the last frame drew volumes for, over every light.
    casters_drawn: u64,
    /// Draw calls of the base and lit passes.
    base_draws: u64,
}

impl Lesson for ZPass {
    const NAME: &'static str = "lesson_05";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_05.toml");
    type Variant = Variant;
    /// Costs are counted on a variant's second frame (`harness.rs`).
    const CAPABILITIES: Capabilities = Capabilities {
        counted_on_frame: 2,
        ..Capabilities::BASIC
    };

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let volumes = ShadowVolumes::new(gpu, scene, &Counting::zpass())?;
        let draws = vec![volumes.all(CasterDraw::zpass); scene.scene.lights.len()];
        let lit = stencil::stencil_lit_pipeline(gpu, scene);
        Ok(ZPass {
            shadow: StencilLesson::new(volumes, lit),
            scene_counters: stencil::scene_counters(scene),
            draws,
            kept: Vec::new(),
            casters_drawn: 0,
            base_draws: base_and_lit_draws(scene),
        })
    }

    /// The frame is [`ShadowVolumes::shadow_frame`] (in
    /// [`StencilLesson::frame`]); around it, the exercises' code and the
    /// counts.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        let draws = match variant {
            Variant::ExerciseSkipCasters => {
                let can_matter = workbook::exercise!(lesson_05::volume_can_matter);
                self.kept = kept_draws(&self.shadow.volumes, scene, can_matter);
                &self.kept
            }
            _ => &self.draws,
        };
        let v = VariantFrame {
            variant,
            extrusion: variant.extrusion(),
            parts: variant.cpu_parts(),
        };
        let drawn = self.shadow.frame(frame, scene, targets, v, draws)?;
        self.casters_drawn = drawn as u64;
        Ok(())
    }
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<ZPass>()
}
