//! One triangle that covers the target (`shaders/fullscreen.wgsl`): the
//! window's blit, depth- and stencil-texture readback, debug pictures, and
//! any pass that marks every pixel.

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
        self.build(gpu, None)
    }

    /// [`Fullscreen::pipeline`], its colour target blended with `blend`.
    pub fn pipeline_blended(&self, gpu: &Gpu, blend: wgpu::BlendState) -> wgpu::RenderPipeline {
        self.build(gpu, Some(blend))
    }

    fn build(&self, gpu: &Gpu, blend: Option<wgpu::BlendState>) -> wgpu::RenderPipeline {
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
        let targets = self.fragment.map(|(_, format)| {
            [Some(wgpu::ColorTargetState {
                format,
                blend,
                write_mask: wgpu::ColorWrites::ALL,
            })]
        });
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

/// The target [`read_stencil`] adds the stencil's bits into.
const STENCIL_BITS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// Reads the stencil of the depth-stencil texture `texture` back to the
/// CPU, one byte per pixel, row by row. Drawn, not copied (GL cannot copy
/// a stencil aspect to a buffer): eight full-screen draws, one per bit,
/// each passing the stencil test only where its bit is set (`Equal` on
/// that bit alone) and adding the bit's value into an R8 target. The
/// attachment is read-only: the stencil and depth are left as they were.
pub fn read_stencil(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<u8>> {
    let format = texture.format();
    if !format.has_stencil_aspect() {
        anyhow::bail!("read_stencil: {format:?} has no stencil");
    }
    let (w, h) = (texture.width(), texture.height());
    let usage = wgpu::TextureUsages::empty();
    let target = render_texture(gpu, "stencil bits", w, h, STENCIL_BITS_FORMAT, usage);
    let add = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    };
    let blend = wgpu::BlendState {
        color: add,
        alpha: add,
    };
    let pipelines: Vec<wgpu::RenderPipeline> = (0..8)
        .map(|bit| {
            let face = wgpu::StencilFaceState {
                compare: wgpu::CompareFunction::Equal,
                ..Default::default()
            };
            let stencil = wgpu::StencilState {
                front: face,
                back: face,
                read_mask: 1 << bit,
                write_mask: 0,
            };
            // The bit's value, exact in an 8-bit unorm target.
            let wgsl = format!(
                "@fragment fn fs() -> @location(0) vec4<f32> {{ return vec4<f32>({}.0 / 255.0); }}",
                1u32 << bit
            );
            Fullscreen {
                label: "stencil bit",
                wgsl: &wgsl,
                vs_entry: "vs_fullscreen",
                fragment: Some(("fs", STENCIL_BITS_FORMAT)),
                groups: &[],
                depth_stencil: Some(wgpu::DepthStencilState {
                    format,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(wgpu::CompareFunction::Always),
                    stencil,
                    bias: Default::default(),
                }),
            }
            .pipeline_blended(gpu, blend)
        })
        .collect();
    let view = target.create_view(&Default::default());
    let stencil_view = texture.create_view(&Default::default());
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("stencil readback"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            // Read-only: no depth or stencil operations at all.
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &stencil_view,
                depth_ops: None,
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        // Each draw passes where (stencil & its bit) == (0xff & its bit).
        pass.set_stencil_reference(0xff);
        for p in &pipelines {
            pass.set_pipeline(p);
            pass.draw(0..3, 0..1);
        }
    }
    gpu.queue.submit([enc.finish()]);
    read_texture(gpu, &target, 1)
}
