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

use std::collections::BTreeMap;

use clap::ValueEnum;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::run::lesson::{variant_name, BufferView, Lesson};
use common::Result;
use workbook::lesson_05::count_view::count_view;
use workbook::lesson_05::cull::kept_draws;
use workbook::lesson_05::extrusion::{CpuParts, Extrusion};
use workbook::lesson_05::stencil::{self, Counting};
use workbook::lesson_05::volumes::{
    base_and_lit_draws, CasterDraw, LightVolumes, ShadowVolumes, VolumeCosts,
};

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
// ANCHOR_END: variants

/// How many variants (exercises included): the per-variant arrays.
const VARIANTS: usize = 5;

struct ZPass {
    volumes: ShadowVolumes,
    lit_pipeline: wgpu::RenderPipeline,
    /// `draws[light]`: every caster, z-pass, sides only.
    draws: Vec<Vec<CasterDraw>>,
    /// The same, of the casters `exercise_skip_casters` keeps (per frame).
    kept: Vec<Vec<CasterDraw>>,
    /// Computed once: mesh validation and the largest stencil count.
    scene_counters: BTreeMap<String, u64>,
    /// Per variant: fragment-shader invocations (pipeline statistics,
    /// Vulkan only), the exact volume costs, and frames rendered.
    invocations: [Option<u64>; VARIANTS],
    costs: [Option<VolumeCosts>; VARIANTS],
    frames: [u32; VARIANTS],
    casters_drawn: u64,
    base_draws: u64,
    /// The last frame's depth-stencil texture, for [`Lesson::buffer_view`].
    depth_stencil: Option<wgpu::Texture>,
}

impl Lesson for ZPass {
    const NAME: &'static str = "lesson_05";
    /// Costs are counted on a variant's second frame ([`Lesson::count_again`]).
    const COUNTED_ON_FRAME: u32 = 2;
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_05.toml");
    type Variant = Variant;

    /// The stencil: light N's z-pass count, N the last light.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, _: Variant) -> Result<Option<BufferView>> {
        let (Some(ds), Some(last)) = (&self.depth_stencil, scene.scene.lights.len().checked_sub(1))
        else {
            return Ok(None);
        };
        count_view(gpu, ds, last, 0xff, "z-pass count").map(Some)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let volumes = ShadowVolumes::new(gpu, scene, &Counting::zpass())?;
        let draws = vec![volumes.all(CasterDraw::zpass); scene.scene.lights.len()];
        Ok(ZPass {
            lit_pipeline: stencil::stencil_lit_pipeline(gpu, scene),
            scene_counters: stencil::scene_counters(scene),
            volumes,
            draws,
            kept: Vec::new(),
            invocations: [None; VARIANTS],
            costs: [None; VARIANTS],
            frames: [0; VARIANTS],
            casters_drawn: 0,
            base_draws: base_and_lit_draws(scene),
            depth_stencil: None,
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
        let ext = variant.extrusion();
        if variant == Variant::ExerciseSkipCasters {
            self.kept = kept_draws(
                &self.volumes,
                scene,
                workbook::exercise!(lesson_05::volume_can_matter),
            );
        }
        let all = match variant {
            Variant::ExerciseSkipCasters => &self.kept,
            _ => &self.draws,
        };
        if ext == Extrusion::Cpu {
            // Doom 3's way: find every silhouette on the CPU, every frame.
            (self.volumes).prepare_cpu_with(frame, scene, all, variant.cpu_parts());
        }
        if ext == Extrusion::Compute {
            // The same silhouettes, found by a compute shader on the GPU.
            self.volumes.prepare_compute(frame, scene, all)?;
        }
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        let mut drawn = 0;
        for (light, draws) in all.iter().enumerate() {
            let volumes = LightVolumes {
                light,
                extrusion: ext,
                draws,
            };
            // Clear the stencil, count the volumes into it, and add the
            // light where the count is 0.
            drawn += self
                .volumes
                .light_passes(frame, scene, targets, volumes, &self.lit_pipeline);
        }
        self.casters_drawn = drawn as u64;
        // What the "buffer" view reads: this frame's stencil.
        self.depth_stencil = Some(targets.depth.clone());
        // The second call finds the first frame's depth in place: count
        // then, once, in submits of their own, left out of the frame's times.
        let n = &mut self.frames[variant as usize];
        *n += 1;
        if *n == 2 {
            let (v, volumes) = (variant as usize, &self.volumes);
            let (invocations, costs) = frame.untimed(|gpu| {
                let invocations = volumes.count_fragments(gpu, scene, ext, all);
                (
                    invocations,
                    volumes.count_costs(gpu, scene, targets, ext, all),
                )
            });
            self.invocations[v] = invocations;
            self.costs[v] = Some(costs?);
        }
        Ok(())
    }
    // ANCHOR_END: render

    /// A route whose buffers would pass the adapter's limits
    /// ([`fit`](workbook::lesson_05::fit)) is left out; the others run.
    fn unavailable(&self, variant: Variant) -> Option<String> {
        let why = self.volumes.unfit(variant.extrusion())?;
        Some(format!("{}: {why}", variant_name(variant)))
    }

    fn count_again(&mut self, variant: Variant) {
        self.frames[variant as usize] = 0;
    }

    fn counters(&self, variant: Variant) -> BTreeMap<String, u64> {
        let mut c = self.scene_counters.clone();
        c.insert("casters_drawn".into(), self.casters_drawn);
        if let Some(f) = self.invocations[variant as usize] {
            // llvmpipe counts 16 per 4×4 block: not the fragment count.
            c.insert("fragment_shader_invocations".into(), f);
        }
        if let Some(costs) = self.costs[variant as usize] {
            costs.insert_into(&mut c, self.base_draws);
        }
        c
    }
}

fn main() -> std::process::ExitCode {
    workbook::lesson_main::<ZPass>()
}
