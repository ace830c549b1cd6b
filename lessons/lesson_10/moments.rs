//! Filterable shadow maps (lesson 10): the variance map made from the
//! shadow map by two compute passes (`shaders/lesson_10/moments.wgsl`), its
//! depth moments box-blurred along x, then along y, into a storage buffer.
//! The lit pass reads it with `soft.wgsl`'s Chebyshev bound.

use std::cell::RefCell;
use std::collections::HashMap;

use common::gpu::bindings;
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

/// `Blur` in `moments.wgsl`: the light's geometry and the warp's exponents.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BlurUniform {
    perspective: u32,
    exponent: f32,
    near: f32,
    far: f32,
    negative: f32,
    spread: f32,
    _pad: [u32; 2],
}

/// A blur pass's constants (`moments.wgsl`'s `override`s): its pipeline
/// holds only its own direction, warp and width.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BlurKey {
    pub vertical: bool,
    pub exponential: bool,
    pub radius: u32,
    /// three.js's samples; 0: the box.
    pub samples: u32,
}

impl BlurKey {
    fn pairs(self) -> [(&'static str, f64); 4] {
        [
            ("VERTICAL", self.vertical as u32 as f64),
            ("EXPONENTIAL", self.exponential as u32 as f64),
            ("RADIUS", self.radius as f64),
            ("SAMPLES", self.samples as f64),
        ]
    }
}

/// The variance map and the passes that make it.
pub struct MomentsMap {
    /// The blurred moments, four 32-bit floats per texel, row by row: bound
    /// at group 2 binding 3 of the lit pass.
    pub buffer: wgpu::Buffer,
    /// The first pass's output (blurred along x; along y for three.js, whose blur runs y first).
    first: wgpu::Buffer,
    size: u32,
    module: wgpu::ShaderModule,
    pipeline_layout: wgpu::PipelineLayout,
    /// One pipeline per pass's constants, built when a variant first asks.
    pipelines: RefCell<HashMap<BlurKey, wgpu::ComputePipeline>>,
    layout: wgpu::BindGroupLayout,
}

/// One variance map's passes for one light: the groups and pipelines of
/// its two passes.
pub struct MomentsPasses {
    along_x: (wgpu::BindGroup, wgpu::ComputePipeline),
    along_y: (wgpu::BindGroup, wgpu::ComputePipeline),
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
        let (layout, module, pipeline_layout) = bindings::compute_over_map(
            gpu,
            "moments",
            2,
            "shaders/lesson_10/moments.wgsl",
            include_str!("../../shaders/lesson_10/moments.wgsl"),
        );
        MomentsMap {
            buffer: buffer("moments"),
            first: buffer("moments along x"),
            size,
            module,
            pipeline_layout,
            pipelines: RefCell::new(HashMap::new()),
            layout,
        }
    }

    /// The pipeline of a pass with constants `key`.
    fn pipeline(&self, gpu: &Gpu, key: BlurKey) -> wgpu::ComputePipeline {
        let mut pipelines = self.pipelines.borrow_mut();
        let made = pipelines.entry(key).or_insert_with(|| {
            gpu.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("moments"),
                    layout: Some(&self.pipeline_layout),
                    module: &self.module,
                    entry_point: Some("cs_blur"),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants: &key.pairs(),
                        ..Default::default()
                    },
                    cache: None,
                })
        });
        made.clone()
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
        let u = BlurUniform {
            perspective: g.perspective as u32,
            exponent: v.exponent.unwrap_or(0.0),
            near: g.near,
            far: g.far,
            negative: v.negative.unwrap_or(0.0),
            spread: three.map_or(0.0, |t| t.radius),
            _pad: [0; 2],
        };
        let params = bindings::params_buffer(gpu, "blur", bytemuck::bytes_of(&u));
        let group = |vertical: bool| {
            let key = BlurKey {
                vertical,
                exponential: v.exponent.is_some(),
                radius: v.blur,
                samples: three.map_or(0, |t| t.samples),
            };
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
            let group = bindings::group(gpu, "moments", &self.layout, &resources);
            (group, self.pipeline(gpu, key))
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
        let (group, pipeline) = if vertical {
            &passes.along_y
        } else {
            &passes.along_x
        };
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("moments"),
            timestamp_writes,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, group, &[]);
        let groups = self.size.div_ceil(8);
        pass.dispatch_workgroups(groups, groups, 1);
    }
    // ANCHOR_END: record
}
