//! Lesson 09's harness: what the report counts around the frame that
//! `main.rs` draws: a frame's draw calls, and the shadow passes' depth
//! writes and fragments over every light and cascade (lesson 01's tally,
//! in submits of their own), each cascade drawing the casters it keeps.

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::Result;
use workbook::lesson_01::tally::Tally;
use workbook::lesson_09::cascades::Cascade;
use workbook::lesson_09::csm::{self, CascadeMaps};
use workbook::lesson_09::setup::Setup;

use super::{Csm, Variant};

impl Csm {
    /// The runner's sub-texel move of every cascade's map (`--fragile`):
    /// each light's cascades `fits`, as `fit_cascades` uploaded them, are
    /// uploaded again moved, for the shadow passes and the lit pass alike
    /// (the later writes land last). Nothing unless the runner moves them.
    pub(super) fn jitter_cascades(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        setup: Setup,
        fits: &[Vec<Cascade>],
    ) {
        let jitter = scene.light_jitter.matrix(setup.resolution).as_dmat4();
        if jitter == common::glam::DMat4::IDENTITY {
            return;
        }
        let (b, size) = (&self.scene_box, (scene.width, scene.height));
        let lights = self.lights.iter_mut().zip(&self.params).enumerate();
        for ((light, (lights, params)), fit) in lights.zip(fits) {
            let mut moved = fit.clone();
            for c in &mut moved {
                c.view_proj = jitter * c.view_proj;
            }
            lights.write(gpu, scene, light, &moved);
            let p = setup.params(&scene.scene, b, size, &moved);
            gpu.queue.write_buffer(params, 0, bytemuck::bytes_of(&p));
        }
    }

    /// Draw calls of a frame whose shadow passes drew `casters` times: the
    /// base pass and each light's lit pass draw every object.
    pub(super) fn draws(&self, casters: u64) -> u64 {
        let lights = self.lights.len() as u64;
        self.objects * (1 + lights) + casters
    }

    /// Once per variant (and again after the runner or a knob moved
    /// something): this frame's caster draws, and, where the GPU can be
    /// waited on, its shadow passes' texels, in submits of their own that
    /// are left out of the frame's times.
    pub(super) fn count_once(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        setup: Setup,
        variant: Variant,
    ) -> Result<()> {
        let v = variant as usize;
        if self.caster_draws[v].is_none() {
            let rects = self.kept.iter().flatten().flatten();
            self.caster_draws[v] = Some(rects.map(|r| r.len() as u64).sum());
        }
        if self.texels_written[v].is_none() {
            let (size, k) = (setup.resolution, setup.count);
            // In a web page the count comes back a frame or more later.
            let n = frame.untimed(|gpu| later(|| self.count_texels(gpu, scene, size, k)))?;
            self.texels_written[v] = n;
        }
        Ok(())
    }

    /// The shadow passes' depth writes and rasterised fragments over every
    /// light and cascade, counted through lesson 01's tally. Untimed.
    fn count_texels(&self, gpu: &Gpu, scene: &SceneGpu, size: u32, k: usize) -> Result<(u64, u64)> {
        let scratch = CascadeMaps::new(gpu, size, 1);
        let tally = Tally::new(gpu, size, size);
        let mut total = [0u64; 2];
        for (which, total) in total.iter_mut().enumerate() {
            for (lights, kept) in self.lights.iter().zip(&self.kept) {
                for (i, kept) in kept.iter().enumerate().take(k) {
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
                        csm::draw_kept(pass, scene, kept);
                    })?;
                }
            }
        }
        Ok((total[0], total[1]))
    }
}
