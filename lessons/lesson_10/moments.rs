//! Filterable shadow maps (lesson 10): the variance map made from the
//! shadow map by two compute passes (`shaders/lesson_10/moments.wgsl`), its
//! depth moments box-blurred along x, then along y, into a storage buffer.
//! The lit pass reads it with `soft.wgsl`'s Chebyshev bound.

use common::gpu::bindings::{self, storage_entry, texture_entry};
use common::gpu::Gpu;

use crate::lesson_01::shadow_map::ShadowMap;
use crate::lesson_10::light_geometry::LightGeometry;

/// A variance map's choices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variance {
    /// The box blur's radius, texels (0: the moments, bilinearly).
    pub blur: u32,
    /// `Some(c)`: exponential moments of `exp(c (2z − 1))`.
    pub exponent: Option<f32>,
    /// `Some(c⁻)`: also those of `−exp(−c⁻ (2z − 1))`, the bound the
    /// lower of the two (EVSM4); `None`: the positive warp alone (EVSM2).
    pub negative: Option<f32>,
    /// The least variance (plain), or the least variance over the warped
    /// receiver depth squared (exponential).
    pub min_variance: f32,
    /// The light-bleeding cut: `linstep(lo, hi, p)`; `(0, 1)` is none.
    pub bleed: (f32, f32),
}

/// three.js's variance map (`VSMShadowMap`): the (mean, standard deviation)
/// of `samples` depths over ±`radius` texels, along y then along x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreeVsmBlur {
    pub samples: u32,
    pub radius: f32,
}

/// `Blur` in `moments.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BlurUniform {
    radius: i32,
    vertical: u32,
    exponential: u32,
    perspective: u32,
    exponent: f32,
    near: f32,
    far: f32,
    negative: f32,
    samples: u32,
    spread: f32,
    _pad: [u32; 2],
}

/// The variance map and the passes that make it.
pub struct MomentsMap {
    /// The blurred moments, four 32-bit floats per texel, row by row: bound
    /// at group 2 binding 3 of the lit pass.
    pub buffer: wgpu::Buffer,
    /// The first pass's output (blurred along x; along y for three.js, whose blur runs y first).
    first: wgpu::Buffer,
    size: u32,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// One variance map's passes for one light: the groups of its two passes.
pub struct MomentsPasses {
    along_x: wgpu::BindGroup,
    along_y: wgpu::BindGroup,
}

impl MomentsMap {
    pub fn new(gpu: &Gpu, size: u32) -> MomentsMap {
        let buffer = |label| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64 * size as u64 * 16,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        let stage = wgpu::ShaderStages::COMPUTE;
        let depth = wgpu::TextureSampleType::Float { filterable: false };
        let mut depth_entry = texture_entry(0, depth, wgpu::TextureViewDimension::D2);
        depth_entry.visibility = stage;
        let mut out = storage_entry(3, stage, false, None);
        out.ty = wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: false },
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        let entries = [
            depth_entry,
            storage_entry(1, stage, false, None),
            storage_entry(2, stage, false, None),
            out,
        ];
        let layout = bindings::layout(gpu, "moments", &entries);
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("shaders/lesson_10/moments.wgsl"),
                source: wgpu::ShaderSource::Wgsl(
                    include_str!("../../shaders/lesson_10/moments.wgsl").into(),
                ),
            });
        let pipeline_layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("moments"),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("moments"),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some("cs_blur"),
                compilation_options: Default::default(),
                cache: None,
            });
        MomentsMap {
            buffer: buffer("moments"),
            first: buffer("moments along x"),
            size,
            pipeline,
            layout,
        }
    }

    /// The two passes' groups for variance map `v` of `map`, for a light of
    /// geometry `g`; with `three`, three.js's blur in place of the box.
    pub fn passes(
        &self,
        gpu: &Gpu,
        map: &ShadowMap,
        v: &Variance,
        three: Option<ThreeVsmBlur>,
        g: &LightGeometry,
    ) -> MomentsPasses {
        let group = |vertical: bool| {
            let u = BlurUniform {
                radius: v.blur as i32,
                vertical: vertical as u32,
                exponential: v.exponent.is_some() as u32,
                perspective: g.perspective as u32,
                exponent: v.exponent.unwrap_or(0.0),
                near: g.near,
                far: g.far,
                negative: v.negative.unwrap_or(0.0),
                samples: three.map_or(0, |t| t.samples),
                spread: three.map_or(0.0, |t| t.radius),
                _pad: [0; 2],
            };
            let params = bindings::params_buffer(gpu, "blur", bytemuck::bytes_of(&u));
            // Along x: the depths into `first` (reading the map's buffer,
            // unused); along y: `first` into the map's buffer.
            let (input, output) = match vertical {
                false => (&self.buffer, &self.first),
                true => (&self.first, &self.buffer),
            };
            let resources = [
                wgpu::BindingResource::TextureView(&map.view),
                input.as_entire_binding(),
                params.as_entire_binding(),
                output.as_entire_binding(),
            ];
            bindings::group(gpu, "moments", &self.layout, &resources)
        };
        MomentsPasses {
            along_x: group(false),
            along_y: group(true),
        }
    }

    // ANCHOR: record
    /// Records one of the two passes: the moments blurred along x, or
    /// those blurred again along y.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        passes: &MomentsPasses,
        vertical: bool,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let group = if vertical {
            &passes.along_y
        } else {
            &passes.along_x
        };
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("moments"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        let groups = self.size.div_ceil(8);
        pass.dispatch_workgroups(groups, groups, 1);
    }
    // ANCHOR_END: record
}
