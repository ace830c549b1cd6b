//! The lit pass: one light added on top of the base pass, where the depth
//! equals the base pass's, with the technique's visibility written out.

use crate::gpu::render::{pipeline_layout_for, vertex_state, SceneGpu};
use crate::gpu::targets::FrameTargets;
use crate::gpu::targets::{COLOR_FORMAT, VISIBILITY_FORMAT};
use crate::gpu::Gpu;

/// What one light's lit pass draws with: the lesson's pipeline (made by
/// [`SceneGpu::lit_pipeline`]) and its bind groups from group 2 on (the
/// shadow map, a variant's parameters, ...).
#[derive(Clone, Copy)]
pub struct LitPass<'a> {
    pub light: usize,
    pub pipeline: &'a wgpu::RenderPipeline,
    pub groups: &'a [&'a wgpu::BindGroup],
    /// Draw only inside `[x, y, width, height]` (pixels): where the light
    /// can reach, when the lesson knows it. Empty: draw nothing. The
    /// light's visibility image is cleared whole either way.
    pub scissor: Option<[u32; 4]>,
    /// A second pipeline drawn after the first in the same pass, and the
    /// stencil reference of both (lesson 10's `pcss_min_max`: the first
    /// answers where it can and marks those pixels, the second takes the
    /// taps where it could not). Else none, and the reference 0.
    pub then: Option<&'a wgpu::RenderPipeline>,
    pub stencil_reference: u32,
}

impl<'a> LitPass<'a> {
    pub fn new(
        light: usize,
        pipeline: &'a wgpu::RenderPipeline,
        groups: &'a [&'a wgpu::BindGroup],
    ) -> LitPass<'a> {
        LitPass {
            light,
            pipeline,
            groups,
            scissor: None,
            then: None,
            stencil_reference: 0,
        }
    }

    /// The same pass, then `then` over the same objects, with the stencil
    /// reference `reference`.
    pub fn then(self, then: &'a wgpu::RenderPipeline, reference: u32) -> LitPass<'a> {
        LitPass {
            then: Some(then),
            stencil_reference: reference,
            ..self
        }
    }

    /// The same pass, drawn only inside `rect` (`[x, y, width, height]`).
    pub fn scissored(self, rect: [u32; 4]) -> LitPass<'a> {
        LitPass {
            scissor: Some(rect),
            ..self
        }
    }
}

impl SceneGpu {
    /// A lit-pass pipeline: the lesson's `fs_entry` adds one light where the
    /// depth equals the base pass's, and writes its visibility. Extra bind
    /// groups (the shadow map, ...) start at group 2.
    pub fn lit_pipeline(
        &self,
        gpu: &Gpu,
        module: &wgpu::ShaderModule,
        fs_entry: &str,
        extra: &[&wgpu::BindGroupLayout],
        stencil: wgpu::StencilState,
    ) -> wgpu::RenderPipeline {
        let depth_stencil = self.lit_depth_state(stencil);
        self.lit_pipeline_with_depth(gpu, module, fs_entry, extra, depth_stencil, &[])
    }

    /// The lit pass's depth test: where the depth equals the base pass's
    /// (no depth writes), with `stencil`.
    pub fn lit_depth_state(&self, stencil: wgpu::StencilState) -> wgpu::DepthStencilState {
        wgpu::DepthStencilState {
            format: self.depth_format,
            depth_write_enabled: Some(false),
            // Same vertices, same matrices, @invariant: the depths are equal.
            depth_compare: Some(wgpu::CompareFunction::LessEqual),
            stencil,
            bias: Default::default(),
        }
    }

    /// [`SceneGpu::lit_pipeline`] with another depth test (lesson 07's
    /// reversed-Z tests `GreaterEqual` on its own depth format; else
    /// [`SceneGpu::lit_depth_state`]) and the fragment shader's `override`
    /// constants set: a variant's choices fixed when the pipeline is
    /// compiled, so the compiler drops the branches the variant does not
    /// take (a software rasteriser runs every branch of a switch it cannot
    /// prove dead, masked, texture reads included).
    pub fn lit_pipeline_with_depth(
        &self,
        gpu: &Gpu,
        module: &wgpu::ShaderModule,
        fs_entry: &str,
        extra: &[&wgpu::BindGroupLayout],
        depth_stencil: wgpu::DepthStencilState,
        constants: &[(&str, f64)],
    ) -> wgpu::RenderPipeline {
        let layout = pipeline_layout_for(gpu, &self.frame_layout, &self.object_layout, extra);
        let add = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent::OVER,
        };
        gpu.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(fs_entry),
                layout: Some(&layout),
                vertex: vertex_state(module, "vs_scene"),
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(depth_stencil),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(fs_entry),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants,
                        ..Default::default()
                    },
                    targets: &[
                        Some(wgpu::ColorTargetState {
                            format: COLOR_FORMAT,
                            blend: Some(add),
                            write_mask: wgpu::ColorWrites::ALL,
                        }),
                        Some(VISIBILITY_FORMAT.into()),
                    ],
                }),
                multiview_mask: None,
                cache: None,
            })
    }

    /// Adds `lit.light` to the frame through `lit.pipeline`, writing its
    /// visibility. The stencil reference is 0 unless [`LitPass::then`] set
    /// it: stencil techniques light where the count is 0.
    pub fn lit_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        t: &FrameTargets,
        lit: LitPass<'_>,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) {
        let LitPass {
            light,
            pipeline,
            groups,
            scissor,
            then,
            stencil_reference,
        } = lit;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("lit pass"),
            color_attachments: &[
                Some(t.color_attachment(wgpu::LoadOp::Load)),
                Some(wgpu::RenderPassColorAttachment {
                    view: &t.visibility_views[light],
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                }),
            ],
            depth_stencil_attachment: Some(t.depth_attachment_loaded()),
            timestamp_writes: ts,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some([x, y, w, h]) = scissor {
            if w == 0 || h == 0 {
                return;
            }
            pass.set_scissor_rect(x, y, w, h);
        }
        pass.set_pipeline(pipeline);
        pass.set_stencil_reference(stencil_reference);
        self.bind_frame(&mut pass, light);
        for (i, g) in groups.iter().enumerate() {
            pass.set_bind_group(2 + i as u32, *g, &[]);
        }
        self.draw_objects(&mut pass, |_| true);
        if let Some(then) = then {
            pass.set_pipeline(then);
            self.draw_objects(&mut pass, |_| true);
        }
    }
}
