//! The no-shadow baseline: the same frame as every lesson's, with the
//! visibility test removed. The base pass, then one lit pass per light whose
//! visibility is 1 everywhere. A variant's time minus the baseline's is what
//! its shadows cost.

use anyhow::Result;

use crate::gpu::lit::LitPass;
use crate::gpu::render::{shader_module, SceneGpu};
use crate::gpu::targets::FrameTargets;
use crate::gpu::Gpu;
use crate::measure::timing::Frame;

/// Every light lit everywhere: `lit_output` with visibility 1.
const UNSHADOWED_WGSL: &str = "
@fragment
fn fs_unshadowed(in: VertexOut) -> LitOut {
    return lit_output(in, 1.0);
}
";

/// The baseline's pipeline.
pub struct Baseline {
    lit_pipeline: wgpu::RenderPipeline,
}

impl Baseline {
    pub fn new(gpu: &Gpu, scene: &SceneGpu) -> Baseline {
        let module = shader_module(gpu, "no-shadow baseline", UNSHADOWED_WGSL);
        let lit_pipeline =
            scene.lit_pipeline(gpu, &module, "fs_unshadowed", &[], Default::default());
        Baseline { lit_pipeline }
    }

    /// Records the baseline frame with the passes named as the lessons
    /// name theirs (`base`, `lighting`).
    pub fn render(
        &self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
    ) -> Result<()> {
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for k in 0..scene.scene.lights.len() {
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    LitPass::new(k, &self.lit_pipeline, &[]),
                    ts.render(),
                )
            });
        }
        Ok(())
    }
}
