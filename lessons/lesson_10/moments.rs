//! Filterable shadow maps (lesson 10): the variance map made from the
//! shadow map by two full-screen passes (`shaders/lesson_10/moments.wgsl`),
//! its depth moments box-blurred along x, then along y. The lit pass reads
//! it with `soft.wgsl`'s Chebyshev bound.

use common::gpu::bindings::{self, float_texture_entry, storage_entry};
use common::gpu::fullscreen::Fullscreen;
use common::gpu::targets::render_texture;
use common::gpu::Gpu;

use crate::lesson_01::shadow_map::ShadowMap;
use crate::lesson_10::soft::{LightGeometry, Variance};

/// The moments' format: 32-bit floats, read with `textureLoad` (filtering
/// 32-bit floats is an optional feature; the shader blends by hand).
pub const MOMENTS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;

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
    _pad: f32,
}

/// The variance map and the passes that make it.
pub struct MomentsMap {
    /// The blurred moments, bound at group 2 binding 3 of the lit pass.
    pub view: wgpu::TextureView,
    /// The first pass's output (blurred along x).
    first: wgpu::TextureView,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

/// One variance map's passes for one light: the groups of its two passes.
pub struct MomentsPasses {
    along_x: wgpu::BindGroup,
    along_y: wgpu::BindGroup,
}

impl MomentsMap {
    pub fn new(gpu: &Gpu, size: u32) -> MomentsMap {
        let usage = wgpu::TextureUsages::TEXTURE_BINDING;
        let texture = |label| {
            render_texture(gpu, label, size, size, MOMENTS_FORMAT, usage)
                .create_view(&Default::default())
        };
        let stage = wgpu::ShaderStages::FRAGMENT;
        let entries = [
            float_texture_entry(0),
            float_texture_entry(1),
            storage_entry(2, stage, false, None),
        ];
        let layout = bindings::layout(gpu, "moments", &entries);
        let wgsl = include_str!("../../shaders/lesson_10/moments.wgsl");
        let pipeline =
            Fullscreen::image("moments", wgsl, "fs_blur", &[&layout], MOMENTS_FORMAT).pipeline(gpu);
        MomentsMap {
            view: texture("moments"),
            first: texture("moments along x"),
            pipeline,
            layout,
        }
    }

    /// The two passes' groups for variance map `v` of `map`, for a light of
    /// geometry `g`.
    pub fn passes(
        &self,
        gpu: &Gpu,
        map: &ShadowMap,
        v: &Variance,
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
                _pad: 0.0,
            };
            let buffer = bindings::params_buffer(gpu, "blur", bytemuck::bytes_of(&u));
            // The pass along x reads the depths; along y, the first pass.
            // Each binds the texture it does not write as the other input.
            let other = if vertical { &self.first } else { &self.view };
            let resources = [
                wgpu::BindingResource::TextureView(&map.view),
                wgpu::BindingResource::TextureView(other),
                buffer.as_entire_binding(),
            ];
            bindings::group(gpu, "moments", &self.layout, &resources)
        };
        MomentsPasses {
            along_x: group(false),
            along_y: group(true),
        }
    }

    // ANCHOR: record
    /// Records the two passes: the moments blurred along x into the first
    /// texture, then along y into the map.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        passes: &MomentsPasses,
        vertical: bool,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) {
        let (target, group) = if vertical {
            (&self.view, &passes.along_y)
        } else {
            (&self.first, &passes.along_x)
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("moments"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: ts,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.draw(0..3, 0..1);
    }
    // ANCHOR_END: record
}
