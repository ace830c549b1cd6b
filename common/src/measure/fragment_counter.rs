//! Deterministic cost counters: fragments rasterised, counted by the GPU's
//! pipeline statistics (where the adapter has them).

use anyhow::Result;

use crate::gpu::readback::QueryReadback;
use crate::gpu::targets::render_texture;
use crate::gpu::Gpu;

/// Counts the fragments a set of draws rasterises, with a pipeline
/// statistics query (FRAGMENT_SHADER_INVOCATIONS) around a pass that has no
/// depth test and a throw-away R8 target. `None` from [`FragmentCounter::new`]
/// when the adapter lacks PIPELINE_STATISTICS_QUERY (GL): omit the key then.
pub struct FragmentCounter {
    set: wgpu::QuerySet,
    readback: QueryReadback,
    target: wgpu::TextureView,
}

impl FragmentCounter {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Option<FragmentCounter> {
        if !gpu.has(wgpu::Features::PIPELINE_STATISTICS_QUERY) {
            return None;
        }
        let set = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("volume fragments"),
            ty: wgpu::QueryType::PipelineStatistics(
                wgpu::PipelineStatisticsTypes::FRAGMENT_SHADER_INVOCATIONS,
            ),
            count: 1,
        });
        let tex = render_texture(
            gpu,
            "fragment count target",
            width,
            height,
            wgpu::TextureFormat::R8Unorm,
            wgpu::TextureUsages::empty(),
        );
        Some(FragmentCounter {
            set,
            readback: QueryReadback::new(gpu, 1, "fragment count"),
            target: tex.create_view(&Default::default()),
        })
    }

    /// Records `draw` (which must set counting pipelines: no depth-stencil,
    /// one R8Unorm target) in its own pass and submit; returns the count.
    pub fn count(&self, gpu: &Gpu, draw: impl FnOnce(&mut wgpu::RenderPass<'_>)) -> Result<u64> {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("count volume fragments"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Discard,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.begin_pipeline_statistics_query(&self.set, 0);
            draw(&mut pass);
            pass.end_pipeline_statistics_query();
        }
        self.readback.resolve(&mut enc, &self.set, 1);
        gpu.queue.submit([enc.finish()]);
        Ok(self.readback.read(gpu, 1)?[0])
    }
}
