//! The shadow map, taught in lesson 01 and reused by lessons 02 and 03:
//! a depth texture rendered from the light, and the pass that fills it.

use std::path::Path;

use anyhow::Result;

use crate::gpu::Gpu;
use crate::render::{
    depth_texture, draw_fullscreen, fullscreen_pipeline, pipeline_layout_for, read_texture,
    render_texture, vertex_state, SceneGpu,
};
use crate::scene::{LightKind, Scene};

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

/// Refuses point lights: lessons 01–03 render one 2D map per light, which a
/// point light (lesson 04's cube map) cannot use.
pub fn refuse_point_lights(scene: &Scene, lesson: &str) -> Result<()> {
    match scene
        .lights
        .iter()
        .position(|l| matches!(l.kind, LightKind::Point { .. }))
    {
        Some(k) => anyhow::bail!(
            "lights[{k}]: {lesson} shadows directional and spot lights; point lights are lesson_04"
        ),
        None => Ok(()),
    }
}

/// Bind group layout for sampling a shadow map in the lit pass (group 2):
/// binding 0 the depth texture, binding 1 a comparison sampler.
pub fn shadow_map_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    shadow_map_layout_with(gpu, false)
}

/// The same, and with `raw` a binding 2: the same texture read as plain
/// floats (GLSL cannot `textureLoad` a depth texture), for lesson 03's
/// depth averaging.
pub fn shadow_map_layout_with(gpu: &Gpu, raw: bool) -> wgpu::BindGroupLayout {
    let texture = |binding, sample_type| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    };
    let mut entries = vec![
        texture(0, wgpu::TextureSampleType::Depth),
        wgpu::BindGroupLayoutEntry {
            binding: 1,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
            count: None,
        },
    ];
    if raw {
        entries.push(texture(
            2,
            wgpu::TextureSampleType::Float { filterable: false },
        ));
    }
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow map"),
            entries: &entries,
        })
}

/// The matching bind group. `filter` Linear gives the hardware's 2×2 PCF.
pub fn shadow_map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &ShadowMap,
    filter: wgpu::FilterMode,
) -> wgpu::BindGroup {
    shadow_map_group_with(gpu, layout, map, filter, false)
}

/// The bind group for [`shadow_map_layout_with`].
pub fn shadow_map_group_with(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &ShadowMap,
    filter: wgpu::FilterMode,
    raw: bool,
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
    let view = wgpu::BindingResource::TextureView(&map.view);
    let mut entries = vec![
        wgpu::BindGroupEntry {
            binding: 0,
            resource: view.clone(),
        },
        wgpu::BindGroupEntry {
            binding: 1,
            resource: wgpu::BindingResource::Sampler(&sampler),
        },
    ];
    if raw {
        entries.push(wgpu::BindGroupEntry {
            binding: 2,
            resource: view,
        });
    }
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("shadow map"),
        layout,
        entries: &entries,
    })
}

const DEPTH_TO_BYTES_WGSL: &str = r#"
// The depth texture bound as unfilterable float: GLSL has no textureLoad on
// shadow samplers.
@group(0) @binding(0) var depth: texture_2d<f32>;
@fragment fn fs(in: FullscreenOut) -> @location(0) vec4<f32> {
    let d = textureLoad(depth, vec2<i32>(in.pos.xy), 0).r;
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
    let target_format = wgpu::TextureFormat::Rgba8Unorm;
    let pipeline = fullscreen_pipeline(
        gpu,
        "depth to bytes",
        DEPTH_TO_BYTES_WGSL,
        "fs",
        &layout,
        target_format,
    );
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
    draw_fullscreen(&mut enc, &tv, &pipeline, &group);
    gpu.queue.submit([enc.finish()]);
    let bytes = read_texture(gpu, &target, 4)?;
    Ok(bytes
        .chunks_exact(4)
        .map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        .collect())
}

// ---- the shader side, shared by lessons 01, 02 and 03 ---------------------

/// The WGSL that lessons 01, 02 and 03 share (`shaders/shadow_map.wgsl`): the
/// shadow map's bindings (group 2), the light-space transform, the texel
/// size, and the receiver-side bias of lesson 02.
pub const SHADOW_MAP_WGSL: &str = include_str!("../../shaders/shadow_map.wgsl");

/// Compiles `common.wgsl`, then `shadow_map.wgsl`, then a lesson's own WGSL.
pub fn shader_module(gpu: &Gpu, label: &str, lesson_wgsl: &str) -> wgpu::ShaderModule {
    crate::render::shader_module(
        gpu,
        label,
        &format!("{SHADOW_MAP_WGSL}\n// ---- {label} ----\n{lesson_wgsl}"),
    )
}

/// The receiver-side bias of `shadow_map.wgsl` (its `ShadowBias`), taught in
/// lesson 02. Lengths are in shadow-map texels at the receiver, so a setting
/// fits any scene size, map resolution and light type.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ShadowBias {
    /// Subtracted from the receiver's depth, in depth units (the seeds' constant).
    pub depth: f32,
    /// The receiver moves this many texels towards the light.
    pub toward_light: f32,
    /// ... plus `slope · tan θ` texels, at most `slope_max`.
    pub slope: f32,
    pub slope_max: f32,
    /// The receiver moves `normal · (1 − N·L)` texels along its normal.
    pub normal: f32,
    pub _pad: [f32; 3],
}

impl ShadowBias {
    /// No bias at all: lesson 01's comparison.
    pub const NONE: ShadowBias = ShadowBias {
        depth: 0.0,
        toward_light: 0.0,
        slope: 0.0,
        slope_max: 0.0,
        normal: 0.0,
        _pad: [0.0; 3],
    };
}

/// A bind group layout with one uniform buffer of `size` bytes at binding 0,
/// read by the fragment stage (a lesson's per-variant parameters, group 3).
pub fn uniform_layout(gpu: &Gpu, label: &str, size: u64) -> wgpu::BindGroupLayout {
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(size),
                },
                count: None,
            }],
        })
}

/// A uniform buffer holding `bytes`, bound through [`uniform_layout`].
pub fn uniform_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    bytes: &[u8],
) -> wgpu::BindGroup {
    use wgpu::util::DeviceExt;
    let buffer = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage: wgpu::BufferUsages::UNIFORM,
        });
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: buffer.as_entire_binding(),
        }],
    })
}

/// Whether the adapter can clamp the hardware depth bias
/// (`DepthBiasState::clamp`); GL cannot, and a non-zero clamp fails there.
pub fn can_clamp_depth_bias(gpu: &Gpu) -> bool {
    gpu.adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::DEPTH_BIAS_CLAMP)
}

// ANCHOR: slope_scaled_bias
/// The rasteriser's slope-scaled depth bias (`wgpu::DepthBiasState`), with
/// its clamp given in texels: taught in lesson 02, reused in lesson 03.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlopeScaledBias {
    /// Units of the depth format (for `Depth32Float`, 2^(e − 23) with e the
    /// exponent of the triangle's largest depth).
    pub constant: i32,
    /// Times the triangle's depth slope: its largest depth change per texel.
    pub slope_scale: f32,
    /// At most this many texel widths of depth, along the light.
    pub clamp_texels: f32,
}

impl SlopeScaledBias {
    /// What lesson 02 measured best, and what lesson 03 filters with.
    pub const RECOMMENDED: SlopeScaledBias = SlopeScaledBias {
        constant: 8,
        slope_scale: 1.5,
        clamp_texels: 16.0,
    };

    /// The shadow pass's state for `light` and a `map_size` map: the clamp
    /// converted to depth units at the scene's centre, and left out where
    /// the adapter cannot clamp (GL), so there the bias is unclamped.
    pub fn pass_state(
        &self,
        gpu: &Gpu,
        scene: &crate::scene::Scene,
        light: usize,
        map_size: u32,
    ) -> ShadowPassState {
        let clamp = if can_clamp_depth_bias(gpu) {
            (self.clamp_texels as f64 * depth_per_texel(scene, light, map_size)) as f32
        } else {
            0.0
        };
        ShadowPassState {
            cull: None,
            bias: wgpu::DepthBiasState {
                constant: self.constant,
                slope_scale: self.slope_scale,
                clamp,
            },
        }
    }
}
// ANCHOR_END: slope_scaled_bias

/// How much depth one texel-width step along the light's ray is, at the
/// scene's centre (the depth is not linear for a spot light, so only there).
pub fn depth_per_texel(scene: &crate::scene::Scene, light: usize, map_size: u32) -> f64 {
    use crate::scene::LightKind;
    use glam::DVec3;
    let Some(m) = crate::camera::light_view_proj(scene, light) else {
        return 0.0;
    };
    let m = m.as_dmat4();
    let centre = DVec3::ZERO; // everything is relative to the scene-bounds centre
    let along = match scene.lights[light].kind {
        LightKind::Directional { direction } => direction.normalize(),
        LightKind::Spot { position, .. } => {
            (centre - (position - scene.origin())).normalize_or(DVec3::NEG_Y)
        }
        LightKind::Point { .. } => return 0.0,
    };
    let row = |i: usize| DVec3::new(m.x_axis[i], m.y_axis[i], m.z_axis[i]).length();
    let w = (m * centre.extend(1.0)).w;
    let texel = 2.0 * w / (map_size as f64 * row(0).min(row(1)));
    (m.project_point3(centre + along * texel).z - m.project_point3(centre).z).abs()
}
