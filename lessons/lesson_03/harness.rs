//! Lesson 03's harness: what the report counts around the frame that
//! `main.rs` draws, each in its own submits, once: the shadow pass's depth
//! writes (per shadow pass and map size) and the adaptive filter's paths.

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::Result;
use workbook::lesson_01::shadow_map;
use workbook::lesson_03::adaptive_count::{self, CountPass};
use workbook::lesson_03::pcf::Filter;

use super::{Pcf, Variant};

impl Pcf {
    /// The variant's shadow pass's depth writes and fragments, counted
    /// once per shadow pass and map size.
    pub(super) fn count_texels_once(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<()> {
        let (pass, size) = (variant.pass(), variant.map_size());
        let counted = self.texels_written.iter().any(|(k, _)| *k == (pass, size));
        if !counted {
            // In a web page the count comes back a frame or more later.
            let n = later(|| {
                shadow_map::count_shadow_texels(gpu, scene, size, |k| {
                    &self.tally_pipelines[pass][k]
                })
            })?;
            if let Some(n) = n {
                self.texels_written.push(((pass, size), n));
            }
        }
        Ok(())
    }

    /// The adaptive filter's paths ([`adaptive_count`]), counted once per
    /// variant and knob setting in its own submit: untimed.
    pub(super) fn count_adaptive_once(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        v: Variant,
    ) -> Result<()> {
        let adaptive = matches!(self.filters[v as usize], Filter::AdaptivePoisson { .. });
        if !adaptive || self.adaptive_paths[v as usize].is_some() {
            return Ok(());
        }
        let count = CountPass {
            shadow_pipelines: &self.shadow_pipelines[v.pass()],
            map: &self.map(v).map,
            count_pipeline: &self.adaptive_count,
            groups: &[self.map_group(v), &self.filter_groups[v as usize]],
        };
        let paths = later(|| adaptive_count::count_adaptive_paths(gpu, scene, targets, count))?;
        self.adaptive_paths[v as usize] = paths;
        Ok(())
    }
}
