//! A frame of stencil shadows, as lessons 05, 06 and 07 draw it: the base
//! pass, then for each light a volume pass that counts the light's volumes
//! into the cleared stencil and a lit pass where the count is 0.

use anyhow::Result;
use common::gpu::lit::LitPass;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::measure::timing::Frame;

use super::{CasterDraw, DrawRole, LightVolumes, ShadowVolumes};
use crate::lesson_05::extrusion::Extrusion;

impl ShadowVolumes {
    // ANCHOR: volume_pass
    /// One light's volume pass: clears the stencil (depth is loaded from the
    /// base pass) and counts the volumes of `draws` into it.
    pub fn volume_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &SceneGpu,
        targets: &FrameTargets,
        volumes: LightVolumes<'_>,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) -> u32 {
        let mut pass = targets.stencil_pass(encoder, "volume pass", ts, None);
        self.draw_casters(&mut pass, scene, volumes, DrawRole::Stencil)
    }
    // ANCHOR_END: volume_pass

    // ANCHOR: light_passes
    /// One light's two passes: clear the stencil and count the light's
    /// volumes into it ("volume"), then add the light where the count is 0
    /// ("lighting", through `lit_pipeline`). Returns the casters drawn.
    pub fn light_passes(
        &self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        volumes: LightVolumes<'_>,
        lit_pipeline: &wgpu::RenderPipeline,
    ) -> u32 {
        let drawn = frame.pass("volume", |enc, ts| {
            self.volume_pass(enc, scene, targets, volumes, ts.render())
        });
        frame.pass("lighting", |enc, ts| {
            let lit = LitPass::new(volumes.light, lit_pipeline, &[]);
            scene.lit_pass(enc, targets, lit, ts.render())
        });
        drawn
    }
    // ANCHOR_END: light_passes

    // ANCHOR: shadow_frame
    /// A frame of stencil shadows: build this frame's volumes (the CPU and
    /// compute routes), draw the base pass, then for each light clear the
    /// stencil, count its volumes (`draws[light]`) and add the light where
    /// the count is 0. Returns the casters drawn.
    pub fn shadow_frame(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        extrusion: Extrusion,
        draws: &[Vec<CasterDraw>],
        lit_pipeline: &wgpu::RenderPipeline,
    ) -> Result<u32> {
        match extrusion {
            // Doom 3's way: find every silhouette on the CPU, every frame.
            Extrusion::Cpu => self.prepare_cpu(frame, scene, draws),
            // The same silhouettes, found by a compute shader on the GPU.
            Extrusion::Compute => self.prepare_compute(frame, scene, draws)?,
            // Built once: the vertex shader extrudes them.
            Extrusion::Quads => {}
        }
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        let mut drawn = 0;
        for (light, draws) in draws.iter().enumerate() {
            let volumes = LightVolumes {
                light,
                extrusion,
                draws,
            };
            drawn += self.light_passes(frame, scene, targets, volumes, lit_pipeline);
        }
        Ok(drawn)
    }
    // ANCHOR_END: shadow_frame
}
