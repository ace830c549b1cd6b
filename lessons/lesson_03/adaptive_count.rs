//! Harness, not the technique: how many pixels the adaptive filter
//! (`pcf_adaptive` in `shaders/lesson_03/pcf.wgsl`) sent to the full disk.
//!
//! Its cost depends on the scene: 4 taps where the probes agree, 4 + 16
//! where they do not. A counting copy of its lit pass (`fs_adaptive_count`)
//! writes which path each pixel took as its visibility (1.0 the full disk,
//! 0.5 the probes alone); one untimed submit draws the base pass, each
//! light's shadow pass and that copy, and the images are summed. The same
//! fixed-function tests and the same probes decide as in the timed frame,
//! so the counts are the frame's, on any adapter.

use crate::lesson_01::shadow_map::{self, ShadowMap};
use common::gpu::lit::LitPass;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::Result;

/// The pixels the adaptive filter probed (inside the map) and those of
/// them that took the full disk, over every light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AdaptivePaths {
    pub probed: u64,
    pub full_disk: u64,
}

impl AdaptivePaths {
    /// Taps per probed pixel: 4 probes each, 16 more on the full disk.
    pub fn taps(self) -> u64 {
        4 * self.probed + 16 * self.full_disk
    }
}

/// What the counting submit draws with: the shadow pass and map of the
/// variant, the counting pipeline and the variant's bind groups.
pub struct CountPass<'a> {
    pub shadow_pipelines: &'a [wgpu::RenderPipeline],
    pub map: &'a ShadowMap,
    pub count_pipeline: &'a wgpu::RenderPipeline,
    pub groups: &'a [&'a wgpu::BindGroup],
}

/// Draws the frame once with the counting pipeline (its own submit, into
/// the frame's targets, which the timed frame then clears and draws again)
/// and sums which path each pixel took.
pub fn count_adaptive_paths(
    gpu: &Gpu,
    scene: &SceneGpu,
    targets: &FrameTargets,
    pass: CountPass<'_>,
) -> Result<AdaptivePaths> {
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    scene.base_pass(&mut enc, targets, None);
    for light in 0..scene.scene.lights.len() {
        let shadow = &pass.shadow_pipelines[light];
        shadow_map::shadow_pass(&mut enc, scene, shadow, pass.map, light, None);
        let lit = LitPass::new(light, pass.count_pipeline, pass.groups);
        scene.lit_pass(&mut enc, targets, lit, None);
    }
    gpu.queue.submit([enc.finish()]);
    let images = targets.read_measured(gpu)?;
    let mut paths = AdaptivePaths::default();
    for light in &images.visibility {
        for &v in light {
            paths.probed += u64::from(v > 0.25);
            paths.full_disk += u64::from(v > 0.75);
        }
    }
    Ok(paths)
}

#[cfg(test)]
mod tests {
    use super::AdaptivePaths;

    #[test]
    fn taps_count_the_probes_and_the_full_disk() {
        let p = AdaptivePaths {
            probed: 10,
            full_disk: 3,
        };
        assert_eq!(p.taps(), 40 + 48);
    }
}
