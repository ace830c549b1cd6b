//! The compute route's bind group layout and pipeline
//! (`shaders/lesson_05/extrude.wgsl`): plumbing of [`super::ComputeVolumes`].

use common::gpu::Gpu;

use super::Params;

pub(super) fn bind_group_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let params = wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            // One Params per (light, caster), picked by a dynamic offset.
            has_dynamic_offset: true,
            min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<Params>() as u64),
        },
        count: None,
    };
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("extrude"),
            entries: &[
                params,
                storage(1, true),
                storage(2, false),
                storage(3, false),
            ],
        })
}

pub(super) fn compute_pipeline(
    gpu: &Gpu,
    module: &wgpu::ShaderModule,
    layout: &wgpu::BindGroupLayout,
) -> wgpu::ComputePipeline {
    let layout = gpu
        .device
        .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("extrude"),
            bind_group_layouts: &[Some(layout)],
            immediate_size: 0,
        });
    gpu.device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("extrude"),
            layout: Some(&layout),
            module,
            entry_point: Some("extrude"),
            compilation_options: Default::default(),
            cache: None,
        })
}
