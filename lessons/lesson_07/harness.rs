//! Lesson 07's harness: what the runner measures and shows besides the
//! image. Each variant's depth precision (the smallest depth gap its
//! mapping resolves), the casters drawn and the volumes' costs (counted on
//! a variant's second frame, against the first one's depth), the second
//! exercise's vertices before its near plane, as counters; the variants an
//! adapter cannot draw; the z-fail count in the stencil as the window's
//! buffer view; and the depth-precision study's tables and plots as extra
//! files.

use std::path::Path;

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, CASTERS_DRAWN, DEPTH_GAP_PPB_AT_HALF_FAR, DEPTH_GAP_PPB_AT_SQRT_NEAR_FAR,
    FRAGMENT_SHADER_INVOCATIONS, VERTICES_BEFORE_NEAR,
};
use common::run::files::save;
use common::run::instruments::{BufferView, Instruments};
use common::run::lesson::is_exercise;
use common::run::per_variant::PerVariant;
use common::scene::Far;
use common::{anyhow, Result};
use workbook::lesson_05::count_view::count_view;
use workbook::lesson_05::extrusion::Extrusion;
use workbook::lesson_05::volumes::{base_and_lit_draws, CasterDraw, ShadowVolumes};
use workbook::lesson_07::exercise_cameras as cameras;
use workbook::lesson_07::precision_study::{self as study, DepthFormat};
use workbook::lesson_07::precision_table;

use super::{DepthClamp, Variant};

/// What lesson 07 counts of one variant.
#[derive(Clone, Debug, Default)]
pub(super) struct VariantCounts {
    /// Counted once and kept: the depth precision of the variant's
    /// mapping (when the lesson starts), and `exercise_adaptive_near`'s
    /// vertices before its near plane (when its camera is made).
    once: Counts,
    /// The casters drawn and the fragment-shader invocations, counted on
    /// the variant's first frame (from [`Instruments::count_again`]), with
    /// the volumes' costs added on its second; `None` until the first.
    frame: Option<Counts>,
    /// The volumes' costs are still to count, on the next frame.
    costs_pending: bool,
}

impl VariantCounts {
    /// `reversed_z`'s frame (drawn by [`ReversedZ`](workbook::lesson_07::reversed_z::ReversedZ),
    /// not counted by a tally): the casters drawn.
    pub(super) fn reversed_frame(&mut self, casters: u64) {
        (self.frame.get_or_insert_with(Counts::new)).set(CASTERS_DRAWN, casters);
    }

    /// An exercise's camera is made: for `exercise_adaptive_near`, the
    /// vertices its near plane clips.
    pub(super) fn camera_made(&mut self, variant: Variant, scene: &SceneGpu) {
        if variant == Variant::ExerciseAdaptiveNear {
            let near = cameras::adapted_near(scene);
            let clipped = cameras::vertices_before_near(scene, near);
            self.once.set(VERTICES_BEFORE_NEAR, clipped);
        }
    }

    /// After a frame of `draws`, seen through `sg`'s camera: on the
    /// variant's first, the casters drawn and the fragment-shader
    /// invocations; on its second, the volumes' exact costs against the
    /// first frame's depth in `targets` (untimed, their own submits).
    pub(super) fn after_frame(
        &mut self,
        gpu: &Gpu,
        sg: &SceneGpu,
        targets: &FrameTargets,
        volumes: &ShadowVolumes,
        draws: &[Vec<CasterDraw>],
    ) -> Result<()> {
        let ext = Extrusion::Quads;
        match &mut self.frame {
            None => {
                let drawn = draws.iter().map(|d| d.len() as u64).sum();
                let mut c = Counts::from([(CASTERS_DRAWN, drawn)]);
                if let Some(f) = volumes.count_fragments(gpu, sg, ext, draws) {
                    // llvmpipe counts 16 per 4×4 block: not the fragment count.
                    c.set(FRAGMENT_SHADER_INVOCATIONS, f);
                }
                self.frame = Some(c);
                // The depth is this frame's, not yet drawn: the costs wait
                // for the second call.
                self.costs_pending = true;
            }
            Some(c) if self.costs_pending => {
                // In a web page the costs come back a frame or more later.
                let costs = later(|| volumes.count_costs(gpu, sg, targets, ext, draws))?;
                if let Some(costs) = costs {
                    self.costs_pending = false;
                    costs.insert_into(c, base_and_lit_draws(sg));
                }
            }
            Some(_) => {}
        }
        Ok(())
    }
}

/// Relative gap in parts per billion; 10⁹ means "not even Δd = d resolves".
fn ppb(g: Option<f64>) -> u64 {
    g.map_or(1_000_000_000, |g| (g * 1e9).round() as u64)
}

/// Every variant's counts, nothing drawn yet, with the depth precision of
/// its mapping for this scene's near and far planes and depth format. The
/// study reads the GPU back: not for the exercises, nor in a web page (no
/// counters there).
pub(super) fn precision_counts(
    gpu: &Gpu,
    scene: &SceneGpu,
) -> Result<PerVariant<Variant, VariantCounts>> {
    let Far::Finite(far) = scene.scene.camera.far else {
        unreachable!("checked")
    };
    let near = scene.scene.camera.near;
    let format = if scene.depth_format == DepthFormat::D32F.wgpu() {
        DepthFormat::D32F
    } else {
        DepthFormat::D24
    };
    // The model follows what the format stores here (24-bit or float).
    let format = (format, study::storage_of(gpu, format)?);
    PerVariant::try_new(|v: Variant| {
        let mut counts = VariantCounts::default();
        if is_exercise(v) || !gpu.can_wait() {
            return Ok(counts);
        }
        let row = study::study_one(gpu, format, v.mapping(), near, far)?;
        let n = row.distances.len();
        counts.once = Counts::from([
            (DEPTH_GAP_PPB_AT_SQRT_NEAR_FAR, ppb(row.best(n - 2))),
            (DEPTH_GAP_PPB_AT_HALF_FAR, ppb(row.best(n - 1))),
        ]);
        Ok(counts)
    })
}

impl Instruments for DepthClamp {
    /// `clamp` without DEPTH_CLIP_CONTROL, `reversed_z` without
    /// Depth32FloatStencil8: the one line that says so.
    fn unavailable(&self, variant: Variant) -> Option<String> {
        match variant {
            Variant::Clamp => self.clamp.as_ref().err().cloned(),
            Variant::ReversedZ => self.reversed.as_ref().err().cloned(),
            _ => None,
        }
    }

    /// The costs are counted once, on the frame after the casters drawn
    /// are: forget both and they are counted again.
    fn count_again(&mut self, variant: Variant) {
        let c = &mut self.counts[variant];
        c.frame = None;
        c.costs_pending = false;
    }

    /// The scene's checks (mesh validation, the largest overlap), the
    /// variant's depth precision, and what its frames counted.
    fn counters(&self, variant: Variant) -> Counts {
        let mut c = self.scene_counters.clone();
        let v = &self.counts[variant];
        c.extend(&v.once);
        if let Some(f) = &v.frame {
            c.extend(f);
        }
        c
    }

    /// The stencil: light N's z-fail count, N the last light.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        let ds = match (v, &self.reversed) {
            (Variant::ReversedZ, Ok(r)) => Some(r.depth_stencil()),
            _ => self.depth_stencil.as_ref(),
        };
        let (Some(ds), Some(last)) = (ds, scene.scene.lights.len().checked_sub(1)) else {
            return Ok(None);
        };
        count_view(gpu, ds, last, 0xff, "z-fail count").map(Some)
    }

    /// The depth-precision study, once per run: both formats, four
    /// mappings, far/near from 1e2 to 1e8 (near = 1e-3).
    fn write_extras(&self, gpu: &Gpu, _: &SceneGpu, _: Variant, out: &Path) -> Result<()> {
        if self.study_written.replace(true) {
            return Ok(());
        }
        let rows = study::study(gpu, 1e-3, &[1e2, 1e4, 1e6, 1e8])?;
        let write = |name: &str, text: String| {
            std::fs::write(out.join(name), text)
                .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", out.join(name).display()))
        };
        write("depth_precision.csv", precision_table::csv(&rows))?;
        write("depth_precision.md", precision_table::markdown(&rows))?;
        write("depth_precision.svg", precision_table::svg_plot(&rows))?;
        save(
            &precision_table::grid_image(&rows, 3),
            &out.join("depth_precision.png"),
        )
    }
}
