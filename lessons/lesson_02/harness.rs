//! Lesson 02's harness: around the frame that `main.rs` draws, the shadow
//! pass's depth writes counted once per variant (their own submits), and
//! the exercises' lit pipelines, compiled when an exercise first runs.

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::Result;
use workbook::lesson_01::shadow_map;
use workbook::lesson_02::exercise_pass;

use super::{Bias, Fix, Variant};

impl Bias {
    /// The variant's shadow pass's depth writes and fragments, counted on
    /// its first frame through the counting copy of its pipeline.
    pub(super) fn count_texels_once(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<()> {
        if self.texels_written[variant as usize].is_some() {
            return Ok(());
        }
        let tally_slope = &self.tally_slope[variant as usize];
        let size = variant.map_size();
        // In a web page the count comes back a frame or more later.
        let n = later(|| {
            shadow_map::count_shadow_texels(gpu, scene, size, |k| {
                match (variant.fix(), tally_slope) {
                    (Fix::CullFrontFaces, _) => &self.tally_cull,
                    (_, Some(hw)) => &hw[k],
                    _ => &self.tally_plain,
                }
            })
        })?;
        self.texels_written[variant as usize] = n;
        Ok(())
    }

    /// An exercise's lit pipeline, compiled on its first frame.
    pub(super) fn compile_exercise(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<()> {
        if let Some(e) = variant.exercise() {
            if !self.exercise_lit.iter().any(|(x, _)| *x == e) {
                let [map, bias] = &self.layouts;
                let p = exercise_pass::lit_pipeline(gpu, scene, e, &[map, bias])?;
                self.exercise_lit.push((e, p));
            }
        }
        Ok(())
    }

    /// The variant's lit pipeline: the lesson's, or its exercise's.
    pub(super) fn lit_for(&self, variant: Variant) -> &wgpu::RenderPipeline {
        let exercise = variant.exercise();
        (self.exercise_lit.iter())
            .find(|(x, _)| Some(*x) == exercise)
            .map_or(&self.lit_pipeline, |(_, p)| p)
    }
}
