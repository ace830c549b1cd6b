//! The shadow map, taught in lesson 01 and reused by lessons 02 and 03:
//! a depth texture rendered from the light, and the pass that fills it.

use std::path::Path;

use anyhow::Result;

use crate::gpu::Gpu;
use crate::render::{
    depth_texture, pipeline_layout_for, read_texture, render_texture, vertex_state, SceneGpu,
};

pub const SHADOW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A square depth texture seen from the light.
pub struct ShadowMap {
    pub size: u32,
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl ShadowMap {
    pub fn new(gpu: &Gpu, size: u32) -> ShadowMap {
        let texture = depth_texture(gpu, &format!("shadow map {size}"), size, 1, SHADOW_FORMAT);
        let view = texture.create_view(&Default::default());
        ShadowMap {
            size,
            texture,
            view,
        }
    }

    /// Reads the stored depths back to the CPU. Drawn through a shader into
    /// an RGBA8 target (the float's four bytes), because GL cannot copy
    /// depth textures to buffers.
    pub fn read_depths(&self, gpu: &Gpu) -> Result<Vec<f32>> {
        read_depth_texture(gpu, &self.view, self.size, wgpu::TextureViewDimension::D2)
    }

    /// Writes the depth map as a picture: near = dark, far = light, the
    /// range stretched over what the map holds so the casters stand out.
    pub fn write_png(&self, gpu: &Gpu, path: &Path) -> Result<()> {
        let d = self.read_depths(gpu)?;
        let lo = d.iter().copied().fold(f32::INFINITY, f32::min);
        let hi = d.iter().copied().filter(|&x| x < 1.0).fold(lo, f32::max);
        let span = (hi - lo).max(1e-12);
        let img = image::GrayImage::from_fn(self.size, self.size, |x, y| {
            let v = d[(y * self.size + x) as usize];
            image::Luma([if v >= 1.0 {
                255
            } else {
                (((v - lo) / span) * 235.0).round() as u8
            }])
        });
        crate::app::save(&img, path)
    }
}

/// How the shadow pass rasterises: which faces it culls and what depth bias
/// the hardware adds (lesson 02). Lesson 01 uses the default: none of either.
#[derive(Clone, Copy, Debug, Default)]
pub struct ShadowPassState {
    pub cull: Option<wgpu::Face>,
    pub bias: wgpu::DepthBiasState,
}

// ANCHOR: shadow_pipeline
/// The depth-only pipeline of the shadow pass: the scene's vertex buffers,
/// `vs_light_depth` (object → light clip space), no fragment shader at all.
pub fn shadow_pipeline(
    gpu: &Gpu,
    scene: &SceneGpu,
    module: &wgpu::ShaderModule,
    state: ShadowPassState,
) -> wgpu::RenderPipeline {
    let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
    gpu.device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("shadow pass"),
            layout: Some(&layout),
            vertex: vertex_state(module, "vs_light_depth"),
            primitive: wgpu::PrimitiveState {
                cull_mode: state.cull,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: SHADOW_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: state.bias,
            }),
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        })
}
// ANCHOR_END: shadow_pipeline

// ANCHOR: shadow_pass
/// Renders every shadow caster's depth from light `light` into `map`.
pub fn shadow_pass(
    encoder: &mut wgpu::CommandEncoder,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    map: &ShadowMap,
    light: usize,
    ts: Option<wgpu::RenderPassTimestampWrites>,
) -> u32 {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("shadow pass"),
        color_attachments: &[],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &map.view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: ts,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    scene.bind_frame(&mut pass, light);
    scene.draw_objects(&mut pass, |i| scene.casts_shadow(i))
}
// ANCHOR_END: shadow_pass

/// Bind group layout for sampling a shadow map in the lit pass (group 2):
/// binding 0 the depth texture, binding 1 a comparison sampler.
pub fn shadow_map_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow map"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
            ],
        })
}

/// The matching bind group. `filter` Linear gives the hardware's 2×2 PCF.
pub fn shadow_map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &ShadowMap,
    filter: wgpu::FilterMode,
) -> wgpu::BindGroup {
    let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("shadow comparison"),
        address_mode_u: wgpu::AddressMode::ClampToEdge,
        address_mode_v: wgpu::AddressMode::ClampToEdge,
        mag_filter: filter,
        min_filter: filter,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    });
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("shadow map"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&map.view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(&sampler),
            },
        ],
    })
}

const DEPTH_TO_BYTES_WGSL: &str = r#"
// The depth texture bound as unfilterable float: GLSL has no textureLoad on
// shadow samplers.
@group(0) @binding(0) var depth: texture_2d<f32>;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let d = textureLoad(depth, vec2<i32>(p.xy), 0).r;
    // The float's bits, one byte per channel: exact on the way back.
    return unpack4x8unorm(bitcast<u32>(d));
}
"#;

/// Reads a 2D depth texture view as `f32`s through a render pass.
pub fn read_depth_texture(
    gpu: &Gpu,
    view: &wgpu::TextureView,
    size: u32,
    dim: wgpu::TextureViewDimension,
) -> Result<Vec<f32>> {
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("depth to bytes"),
        source: wgpu::ShaderSource::Wgsl(DEPTH_TO_BYTES_WGSL.into()),
    });
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("depth to bytes"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: dim,
                multisampled: false,
            },
            count: None,
        }],
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::TextureView(view),
        }],
    });
    let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let target_format = wgpu::TextureFormat::Rgba8Unorm;
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("depth to bytes"),
        layout: Some(&pl),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(target_format.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let target = render_texture(
        gpu,
        "depth bytes",
        size,
        size,
        target_format,
        wgpu::TextureUsages::empty(),
    );
    let tv = target.create_view(&Default::default());
    let mut enc = device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("depth to bytes"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &tv,
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
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }
    gpu.queue.submit([enc.finish()]);
    let bytes = read_texture(gpu, &target, 4)?;
    Ok(bytes
        .chunks_exact(4)
        .map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        .collect())
}
