//! Lesson 09's harness: what the report counts around the frame that
//! `main.rs` draws: a frame's draw calls, and the shadow passes' depth
//! writes and fragments over every light and cascade (lesson 01's tally,
//! in submits of their own).

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::Result;
use workbook::lesson_01::tally::Tally;
use workbook::lesson_09::csm::CascadeMaps;

use super::{Csm, Variant};

impl Csm {
    /// Draw calls of a frame: the base pass, then per light K shadow passes
    /// (every caster) and the lit pass (every object).
    pub(super) fn draws(&self, variant: Variant) -> u64 {
        let k = self.setup(variant).count as u64;
        let lights = self.lights.len() as u64;
        self.objects + lights * (k * self.casters + self.objects)
    }

    /// The shadow passes' depth writes and rasterised fragments over every
    /// light and cascade, counted through lesson 01's tally. Untimed.
    pub(super) fn count_texels(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        size: u32,
        k: usize,
    ) -> Result<(u64, u64)> {
        let scratch = CascadeMaps::new(gpu, size, 1);
        let tally = Tally::new(gpu, size, size);
        let mut total = [0u64; 2];
        for (which, total) in total.iter_mut().enumerate() {
            for lights in &self.lights {
                for i in 0..k {
                    let depth = wgpu::RenderPassDepthStencilAttachment {
                        view: &scratch.layer_views[0],
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Discard,
                        }),
                        stencil_ops: None,
                    };
                    *total += tally.count(gpu, Some(depth), |pass| {
                        pass.set_pipeline(&self.tally_pipeline[which]);
                        lights.bind(pass, i);
                        scene.draw_objects(pass, |o| scene.casts_shadow(o));
                    })?;
                }
            }
        }
        Ok((total[0], total[1]))
    }
}
