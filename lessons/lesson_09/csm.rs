//! Cascaded shadow maps on the GPU (lesson 09): the depth texture array
//! (one layer per cascade), the per-cascade light matrices the shadow pass
//! draws with, and what the lit pass reads to pick and sample a cascade
//! (`shaders/lesson_09/csm.wgsl`).

use common::glam::{DVec3, Mat4};
use common::gpu::bindings::{self, sampler_entry, storage_entry, texture_entry};
use common::gpu::render::{SceneGpu, SCENE_BUFFER_USAGE};
use common::gpu::targets::depth_texture;
use common::gpu::Gpu;
use common::scene::camera::LightUniform;
use common::scene::Scene;

use super::cascades::Cascade;
use super::caster_culling::Kept;
use crate::lesson_01::shadow_map::{
    begin_shadow_pass, comparison_sampler, ShadowMap, SHADOW_FORMAT,
};
use crate::lesson_04::faces::LightUniforms;

/// The most cascades a variant may have (`Cascades` in `csm.wgsl`).
pub const MAX_CASCADES: usize = 4;
/// Light uniform slots are spaced by the dynamic-offset alignment.
const SLOT: u64 = 256;

/// K square depth layers, one per cascade.
pub struct CascadeMaps {
    pub size: u32,
    pub count: usize,
    pub texture: wgpu::Texture,
    /// One `D2` view per layer: the shadow pass renders into it.
    pub layer_views: Vec<wgpu::TextureView>,
    /// The `D2Array` view the lit pass samples.
    pub array_view: wgpu::TextureView,
}

impl CascadeMaps {
    pub fn new(gpu: &Gpu, size: u32, count: usize) -> CascadeMaps {
        // At least 2 layers: GL makes a 1-layer texture a plain 2D texture,
        // which has no array view (a 6-layer one a cube map: never 6 here).
        let layers = count.max(2) as u32;
        let label = format!("cascades {count}x{size}");
        let texture = depth_texture(gpu, &label, size, layers, SHADOW_FORMAT);
        let layer_views = common::gpu::targets::layer_views(&texture, layers);
        let array_view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        CascadeMaps {
            size,
            count,
            texture,
            layer_views,
            array_view,
        }
    }

    /// Layer `i` as lesson 01's [`ShadowMap`], to read it back or save it.
    pub fn layer(&self, i: usize) -> ShadowMap {
        ShadowMap {
            size: self.size,
            texture: self.texture.clone(),
            view: self.layer_views[i].clone(),
        }
    }
}

/// One light uniform per cascade, bound as group 0 with the scene's frame
/// layout, so lesson 01's shadow pipeline (`vs_light_depth`) draws each
/// cascade with its own matrix: the queue writes all land before the
/// frame's submission, so one slot per cascade, not one rewritten slot.
pub struct CascadeLights {
    buffer: wgpu::Buffer,
    group: wgpu::BindGroup,
    /// The light's own uniform, made again only when the light changes.
    uniform: LightUniforms,
}

impl CascadeLights {
    pub fn new(gpu: &Gpu, scene: &SceneGpu) -> CascadeLights {
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cascade lights"),
            size: SLOT * MAX_CASCADES as u64,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        // Binding 0 (the camera) is part of the layout; the shadow pass
        // does not read it.
        let camera = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cascade lights: unused camera"),
            size: 96,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        let light_size = std::mem::size_of::<LightUniform>() as u64;
        let light = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &buffer,
            offset: 0,
            size: wgpu::BufferSize::new(light_size),
        });
        let resources = [camera.as_entire_binding(), light];
        let group = bindings::group(gpu, "cascade lights", &scene.frame_layout, &resources);
        CascadeLights {
            buffer,
            group,
            uniform: LightUniforms::default(),
        }
    }

    /// Light `light`'s own matrix: lesson 01's one map over the scene.
    pub fn light_view_proj(&mut self, scene: &Scene, light: usize) -> Mat4 {
        Mat4::from_cols_array_2d(&self.uniform.get(scene, light).view_proj)
    }

    /// Writes light `light`'s uniform with each cascade's matrix.
    pub fn write(&mut self, gpu: &Gpu, scene: &SceneGpu, light: usize, cascades: &[Cascade]) {
        let base = self.uniform.get(&scene.scene, light);
        // Every cascade's slot in one write.
        let mut slots = vec![0u8; cascades.len() * SLOT as usize];
        for (slot, c) in slots.chunks_exact_mut(SLOT as usize).zip(cascades) {
            let mut u = base;
            u.view_proj = c.view_proj.as_mat4().to_cols_array_2d();
            slot[..std::mem::size_of::<LightUniform>()].copy_from_slice(bytemuck::bytes_of(&u));
        }
        if !slots.is_empty() {
            gpu.queue.write_buffer(&self.buffer, 0, &slots);
        }
    }

    /// Binds cascade `i` as group 0.
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>, i: usize) {
        pass.set_bind_group(0, &self.group, &[(SLOT * i as u64) as u32]);
    }
}

// ANCHOR: cascade_pass
/// Renders the casters that cascade `i` keeps ([`super::caster_culling`])
/// into layer `i` with cascade `i`'s matrix, through lesson 01's shadow
/// pipeline.
#[allow(clippy::too_many_arguments)]
pub fn cascade_pass(
    encoder: &mut wgpu::CommandEncoder,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    maps: &CascadeMaps,
    lights: &CascadeLights,
    i: usize,
    kept: &Kept,
    ts: Option<wgpu::RenderPassTimestampWrites>,
) -> u32 {
    let view = &maps.layer_views[i];
    let mut pass = begin_shadow_pass(encoder, "cascade shadow pass", view, ts);
    pass.set_pipeline(pipeline);
    lights.bind(&mut pass, i);
    draw_kept(&mut pass, scene, kept)
}
// ANCHOR_END: cascade_pass

/// Draws each object once per rectangle `kept` holds for it, with that
/// rectangle as the scissor; the number of draws.
pub fn draw_kept(pass: &mut wgpu::RenderPass<'_>, scene: &SceneGpu, kept: &Kept) -> u32 {
    let mut drawn = 0;
    for (o, rects) in kept.iter().enumerate().filter(|(_, r)| !r.is_empty()) {
        let mesh = &scene.meshes[o];
        scene.bind_object(pass, o);
        pass.set_vertex_buffer(0, mesh.vertices.slice(..));
        pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
        for &[x, y, w, h] in rects {
            pass.set_scissor_rect(x, y, w, h);
            pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            drawn += 1;
        }
    }
    drawn
}

/// `Cascades` in `csm.wgsl`: what the lit pass needs to pick a cascade and
/// sample it.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CsmParams {
    pub view_proj: [[[f32; 4]; 4]; MAX_CASCADES],
    /// The view depth where cascade i ends.
    pub split_far: [f32; MAX_CASCADES],
    /// Cascade i's texel, in metres.
    pub texel: [f32; MAX_CASCADES],
    /// xyz: the camera's view axis; w: unused (the cascade count is the
    /// pipeline's `CASCADES`, [`super::pipelines::Shape`]).
    pub forward: [f32; 4],
    /// x: the blend band (a fraction of the cascade's length, 0: none),
    /// y: the normal offset in texels, z: the first cascade's near depth.
    pub options: [f32; 4],
}

impl CsmParams {
    pub fn new(cascades: &[Cascade], res: u32, forward: DVec3, blend: f32, normal: f32) -> Self {
        let mut p = CsmParams {
            view_proj: [[[0.0; 4]; 4]; MAX_CASCADES],
            split_far: [f32::MAX; MAX_CASCADES],
            texel: [0.0; MAX_CASCADES],
            forward: forward.as_vec3().extend(0.0).to_array(),
            options: [blend, normal, cascades[0].near as f32, 0.0],
        };
        for (i, c) in cascades.iter().enumerate() {
            p.view_proj[i] = c.view_proj.as_mat4().to_cols_array_2d();
            p.split_far[i] = c.far as f32;
            p.texel[i] = (c.width / res as f64) as f32;
        }
        p
    }
}

/// The lit pass's group 2: the array (binding 0), a comparison sampler
/// (binding 1) and the [`CsmParams`] (binding 2).
pub fn csm_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    use wgpu::{SamplerBindingType, TextureSampleType, TextureViewDimension};
    let size = std::mem::size_of::<CsmParams>() as u64;
    let entries = [
        texture_entry(0, TextureSampleType::Depth, TextureViewDimension::D2Array),
        sampler_entry(1, SamplerBindingType::Comparison),
        storage_entry(2, wgpu::ShaderStages::FRAGMENT, false, Some(size)),
    ];
    bindings::layout(gpu, "cascaded shadow maps", &entries)
}

/// The group of [`csm_layout`] for `maps`: lesson 03's hardware 2×2 (a
/// linear comparison sampler), and `params`.
pub fn csm_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    maps: &CascadeMaps,
    params: &wgpu::Buffer,
) -> wgpu::BindGroup {
    let sampler = comparison_sampler(gpu, wgpu::FilterMode::Linear);
    let resources = [
        wgpu::BindingResource::TextureView(&maps.array_view),
        wgpu::BindingResource::Sampler(&sampler),
        params.as_entire_binding(),
    ];
    bindings::group(gpu, "cascaded shadow maps", layout, &resources)
}
