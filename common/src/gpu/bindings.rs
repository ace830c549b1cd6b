//! Bind group layouts and groups, written once: fragment-stage textures,
//! samplers and uniform buffers, and a uniform buffer's layout and group
//! (a variant's parameters).

use wgpu::util::DeviceExt;

use crate::gpu::Gpu;

/// A texture at `binding`, read by the fragment stage.
pub fn texture_entry(
    binding: u32,
    sample_type: wgpu::TextureSampleType,
    view_dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension,
            multisampled: false,
        },
        count: None,
    }
}

/// A 2D texture of unfilterable floats at `binding`: what `textureLoad`
/// reads (a depth texture read back, the window's blit).
pub fn float_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    texture_entry(
        binding,
        wgpu::TextureSampleType::Float { filterable: false },
        wgpu::TextureViewDimension::D2,
    )
}

/// A sampler at `binding`, used by the fragment stage.
pub fn sampler_entry(binding: u32, ty: wgpu::SamplerBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(ty),
        count: None,
    }
}

/// A buffer entry of type `ty`, at least `size` bytes (any size with
/// `None`), at `binding`, read by `visibility`.
fn buffer_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    ty: wgpu::BufferBindingType,
    dynamic: bool,
    size: Option<u64>,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: dynamic,
            min_binding_size: size.and_then(wgpu::BufferSize::new),
        },
        count: None,
    }
}

/// A uniform buffer entry (`var<uniform>` in WGSL).
pub fn uniform_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    dynamic: bool,
    size: Option<u64>,
) -> wgpu::BindGroupLayoutEntry {
    let ty = wgpu::BufferBindingType::Uniform;
    buffer_entry(binding, visibility, ty, dynamic, size)
}

/// A read-only storage buffer entry (`var<storage, read>` in WGSL).
pub fn storage_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    dynamic: bool,
    size: Option<u64>,
) -> wgpu::BindGroupLayoutEntry {
    let ty = wgpu::BufferBindingType::Storage { read_only: true };
    buffer_entry(binding, visibility, ty, dynamic, size)
}

/// A layout of `entries`.
pub fn layout(
    gpu: &Gpu,
    label: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
) -> wgpu::BindGroupLayout {
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries,
        })
}

/// A group binding `resources` at bindings 0, 1, 2, ... in order.
pub fn group(
    gpu: &Gpu,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: r.clone(),
        })
        .collect();
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A uniform buffer holding `bytes`.
pub fn uniform_buffer(gpu: &Gpu, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage: wgpu::BufferUsages::UNIFORM,
        })
}

/// A read-only storage buffer holding `bytes`: a variant's parameters.
///
/// Parameters live in storage, not uniform, buffers because lavapipe
/// (Mesa 22.3) recompiles, and leaks, a large fragment shader on every draw
/// when its branches test values from a uniform buffer; see
/// `common::gpu::render::SCENE_BUFFER_USAGE`. In WGSL: `var<storage, read>`.
pub fn params_buffer(gpu: &Gpu, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage: wgpu::BufferUsages::STORAGE,
        })
}

/// A bind group layout with one parameter buffer ([`params_buffer`]) of
/// `size` bytes at binding 0, read by the fragment stage: a variant's
/// parameters for the lit pass.
pub fn params_layout(gpu: &Gpu, label: &str, size: u64) -> wgpu::BindGroupLayout {
    let entry = storage_entry(0, wgpu::ShaderStages::FRAGMENT, false, Some(size));
    layout(gpu, label, &[entry])
}

/// A parameter buffer holding `bytes`, bound through [`params_layout`].
pub fn params_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    bytes: &[u8],
) -> wgpu::BindGroup {
    let buffer = params_buffer(gpu, label, bytes);
    group(gpu, label, layout, &[buffer.as_entire_binding()])
}

/// A compute pass over a depth map (lesson 10's variance map and min/max
/// chain): its group's layout (binding 0 the map, read as floats, then
/// `inputs` read-only storage buffers, then one read-write buffer, the
/// output), its shader module from WGSL `source` (named `path`), and its
/// pipeline layout.
pub fn compute_over_map(
    gpu: &Gpu,
    label: &str,
    inputs: u32,
    path: &str,
    source: &'static str,
) -> (
    wgpu::BindGroupLayout,
    wgpu::ShaderModule,
    wgpu::PipelineLayout,
) {
    let stage = wgpu::ShaderStages::COMPUTE;
    let depth = wgpu::TextureSampleType::Float { filterable: false };
    let mut entries = vec![texture_entry(0, depth, wgpu::TextureViewDimension::D2)];
    entries[0].visibility = stage;
    entries.extend((1..=inputs).map(|b| storage_entry(b, stage, false, None)));
    let mut out = storage_entry(inputs + 1, stage, false, None);
    out.ty = wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only: false },
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    entries.push(out);
    let layout = self::layout(gpu, label, &entries);
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(path),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
    let pipeline_layout = gpu
        .device
        .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
    (layout, module, pipeline_layout)
}
