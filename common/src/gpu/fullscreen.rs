//! One triangle that covers the target (`shaders/fullscreen.wgsl`): the
//! window's blit, depth-texture readback, debug pictures, and any pass
//! that marks every pixel.

use anyhow::Result;

use crate::gpu::readback::read_texture;
use crate::gpu::targets::render_texture;
use crate::gpu::Gpu;

/// `vs_fullscreen`, `fullscreen_position(i, z)` and `FullscreenOut`.
pub const FULLSCREEN_WGSL: &str = include_str!("../../../shaders/fullscreen.wgsl");

/// A full-screen pipeline: `FULLSCREEN_WGSL` followed by `wgsl`.
pub struct Fullscreen<'a> {
    pub label: &'a str,
    /// The pass's own WGSL (its fragment shader, or its own vertex entry).
    pub wgsl: &'a str,
    /// `"vs_fullscreen"`, or an entry of `wgsl` that calls `fullscreen_position`.
    pub vs_entry: &'a str,
    /// The fragment entry and its one colour target; `None` for a
    /// depth-stencil-only pass.
    pub fragment: Option<(&'a str, wgpu::TextureFormat)>,
    /// The bind groups, from group 0 on.
    pub groups: &'a [&'a wgpu::BindGroupLayout],
    pub depth_stencil: Option<wgpu::DepthStencilState>,
}

impl Fullscreen<'_> {
    /// The common case: `fs_entry` of `wgsl` into one colour target of
    /// `format`, reading bind group 0 from `layout`, no depth.
    pub fn image<'a>(
        label: &'a str,
        wgsl: &'a str,
        fs_entry: &'a str,
        layout: &'a [&'a wgpu::BindGroupLayout],
        format: wgpu::TextureFormat,
    ) -> Fullscreen<'a> {
        Fullscreen {
            label,
            wgsl,
            vs_entry: "vs_fullscreen",
            fragment: Some((fs_entry, format)),
            groups: layout,
            depth_stencil: None,
        }
    }

    pub fn pipeline(&self, gpu: &Gpu) -> wgpu::RenderPipeline {
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(self.label),
                source: wgpu::ShaderSource::Wgsl(
                    format!("{FULLSCREEN_WGSL}\n{}", self.wgsl).into(),
                ),
            });
        let groups: Vec<Option<&wgpu::BindGroupLayout>> =
            self.groups.iter().map(|g| Some(*g)).collect();
        let layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(self.label),
                bind_group_layouts: &groups,
                immediate_size: 0,
            });
        let targets = self.fragment.map(|(_, format)| [Some(format.into())]);
        gpu.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(self.label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(self.vs_entry),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: Default::default(),
                depth_stencil: self.depth_stencil.clone(),
                multisample: Default::default(),
                fragment: self
                    .fragment
                    .zip(targets.as_ref())
                    .map(|((entry, _), targets)| wgpu::FragmentState {
                        module: &module,
                        entry_point: Some(entry),
                        compilation_options: Default::default(),
                        targets,
                    }),
                multiview_mask: None,
                cache: None,
            })
    }
}

/// Records one full-screen draw of `pipeline` into `view` (cleared first).
pub fn draw_fullscreen(
    encoder: &mut wgpu::CommandEncoder,
    view: &wgpu::TextureView,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("full-screen pass"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, group, &[]);
    pass.draw(0..3, 0..1);
}

/// Draws `pipeline` (a [`Fullscreen`] pipeline whose
/// fragment shader writes each float's bits with `unpack4x8unorm(bitcast<u32>(x))`)
/// into a `w × h` RGBA8 target and reads the floats back, exactly. GL
/// cannot copy depth textures to buffers, so depth is read this way.
pub fn read_floats(
    gpu: &Gpu,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
    (w, h): (u32, u32),
) -> Result<Vec<f32>> {
    let target = render_texture(
        gpu,
        "float bytes",
        w,
        h,
        FLOAT_BYTES_FORMAT,
        wgpu::TextureUsages::empty(),
    );
    let view = target.create_view(&Default::default());
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    draw_fullscreen(&mut enc, &view, pipeline, group);
    gpu.queue.submit([enc.finish()]);
    let bytes = read_texture(gpu, &target, 4)?;
    Ok(bytes
        .chunks_exact(4)
        .map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        .collect())
}

/// The target format [`read_floats`] draws into: give it to the pipeline.
pub const FLOAT_BYTES_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
