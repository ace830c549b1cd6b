//! The scene on the GPU: meshes, camera, light and object uniforms, the
//! shader prelude every lesson shares, and the base pass (depth, ambient,
//! object id). The lit pass that adds each light is in [`crate::gpu::lit`].

use anyhow::{anyhow, Result};
use glam::Mat4;
use wgpu::util::DeviceExt;

use crate::gpu::bindings;
use crate::gpu::chapter_copy;
pub use crate::gpu::chapter_copy::{chapter_copy_calls, CHAPTER_COPY_CALLS};
use crate::gpu::targets::{FrameTargets, COLOR_FORMAT, ID_FORMAT};
use crate::gpu::Gpu;
use crate::scene::camera::{camera_matrices, light_uniform, CameraMatrices, LightUniform};
use crate::scene::Scene;

/// The WGSL every lesson shader is appended to.
pub const COMMON_WGSL: &str = include_str!("../../../shaders/common.wgsl");

/// Background colour of the shaded frame (linear).
pub const CLEAR_COLOR: wgpu::Color = wgpu::Color {
    r: 0.02,
    g: 0.025,
    b: 0.035,
    a: 1.0,
};

/// Uniform slots are spaced by the device's dynamic-offset alignment.
const SLOT: u64 = 256;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
}

pub const VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<Vertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CameraUniform {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    ambient: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ObjectUniform {
    model: [[f32; 4]; 4],
    normal_matrix: [[f32; 4]; 4],
    color: [f32; 4],
    id: [u32; 4],
}

pub struct GpuMesh {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
}

/// Everything about the scene that lives on the GPU.
pub struct SceneGpu {
    pub scene: Scene,
    pub width: u32,
    pub height: u32,
    pub camera: CameraMatrices,
    /// The runner's sub-pixel move of the camera (`--fragile`): a
    /// clip-space translation applied after the view-projection, the
    /// identity otherwise. A lesson that draws with a camera of its own
    /// (lesson 07) applies it too ([`SceneGpu::set_jitter`]).
    pub jitter: Mat4,
    /// The view-projection before [`SceneGpu::set_jitter`] moved it.
    unjittered: Option<Mat4>,
    /// The runner's sub-texel move of every light's shadow map
    /// (`--fragile`; none otherwise): a lesson applies it where it builds
    /// a light's matrix for a map.
    pub light_jitter: crate::reference::fragile::LightJitter,
    pub meshes: Vec<GpuMesh>,
    camera_buf: wgpu::Buffer,
    light_buf: wgpu::Buffer,
    object_buf: wgpu::Buffer,
    /// group(0): camera + light (dynamic offset per light).
    pub frame_layout: wgpu::BindGroupLayout,
    /// group(1): object (dynamic offset per object).
    pub object_layout: wgpu::BindGroupLayout,
    pub frame_group: wgpu::BindGroup,
    pub object_group: wgpu::BindGroup,
    base_pipeline: wgpu::RenderPipeline,
    pub depth_format: wgpu::TextureFormat,
}

/// How the scene's camera, light and object data are bound: read-only
/// storage buffers, not uniform buffers.
///
/// Why not uniforms: lavapipe (Mesa 22.3) recompiles a fragment shader whose
/// branches test uniform values ("uniform inlining") every time a uniform
/// buffer is rebound, which here is every draw (the object's dynamic offset),
/// and never frees the old code: about 1 MB leaked per draw. It does not
/// inline storage buffers. The WGSL side is `var<storage, read>` in
/// `shaders/common.wgsl`; the data and its layout are the same.
pub const SCENE_BUFFER_USAGE: wgpu::BufferUsages =
    wgpu::BufferUsages::STORAGE.union(wgpu::BufferUsages::COPY_DST);

/// A scene buffer (camera, light, object): read by both stages.
fn scene_entry(binding: u32, dynamic: bool, size: u64) -> wgpu::BindGroupLayoutEntry {
    let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
    bindings::storage_entry(binding, stages, dynamic, Some(size))
}

/// Compiles `common.wgsl` followed by a lesson's own WGSL.
pub fn shader_module(gpu: &Gpu, label: &str, lesson_wgsl: &str) -> wgpu::ShaderModule {
    let source = format!("{COMMON_WGSL}\n// ---- {label} ----\n{lesson_wgsl}");
    gpu.device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        })
}

/// Compiles `common.wgsl` followed by a lesson's WGSL files, each given as
/// (path from the repository root, text): an error in one of them names
/// that file, line and column ([`crate::gpu::wgsl`]).
pub fn shader_module_from_files(
    gpu: &Gpu,
    label: &str,
    files: &[(&str, &str)],
) -> Result<wgpu::ShaderModule> {
    let mut source = crate::gpu::wgsl::WgslSource::new();
    source.push("shaders/common.wgsl", COMMON_WGSL);
    for (path, text) in files {
        source.push(path, &chapter_copy::chapter_copy_half(path, text));
    }
    Ok(source.shader_module(gpu, label)?)
}

impl SceneGpu {
    pub fn new(gpu: &Gpu, scene: Scene, width: u32, height: u32) -> Result<SceneGpu> {
        let device = &gpu.device;
        let depth_format = gpu.depth_stencil_format();
        let meshes = (0..scene.objects.len())
            .map(|i| upload_mesh(gpu, &scene, i))
            .collect::<Result<Vec<_>>>()?;
        let camera_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("camera"),
            size: std::mem::size_of::<CameraUniform>() as u64,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        let light_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lights"),
            size: SLOT * scene.lights.len() as u64,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        let object_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("objects"),
            size: SLOT * scene.objects.len() as u64,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[
                scene_entry(0, false, std::mem::size_of::<CameraUniform>() as u64),
                scene_entry(1, true, std::mem::size_of::<LightUniform>() as u64),
            ],
        });
        let object_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("object"),
            entries: &[scene_entry(
                0,
                true,
                std::mem::size_of::<ObjectUniform>() as u64,
            )],
        });
        fn binding(buf: &wgpu::Buffer, size: usize) -> wgpu::BindingResource<'_> {
            wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: buf,
                offset: 0,
                size: wgpu::BufferSize::new(size as u64),
            })
        }
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &frame_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: camera_buf.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: binding(&light_buf, std::mem::size_of::<LightUniform>()),
                },
            ],
        });
        let object_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("object"),
            layout: &object_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: binding(&object_buf, std::mem::size_of::<ObjectUniform>()),
            }],
        });
        let base_pipeline = base_pipeline(
            gpu,
            &frame_layout,
            &object_layout,
            wgpu::DepthStencilState {
                format: depth_format,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            },
        );
        let camera = camera_matrices(&scene, width, height);
        let s = SceneGpu {
            scene,
            width,
            height,
            camera,
            jitter: Mat4::IDENTITY,
            unjittered: None,
            light_jitter: Default::default(),
            meshes,
            camera_buf,
            light_buf,
            object_buf,
            frame_layout,
            object_layout,
            frame_group,
            object_group,
            base_pipeline,
            depth_format,
        };
        s.upload_uniforms(gpu);
        Ok(s)
    }

    /// Re-uploads camera, lights and objects after the scene changed
    /// (the window mode orbits the camera and moves lights).
    pub fn upload_uniforms(&self, gpu: &Gpu) {
        let cam = CameraUniform {
            view_proj: self.camera.view_proj.to_cols_array_2d(),
            eye: self.camera.eye.extend(1.0).to_array(),
            ambient: self.scene.ambient.extend(1.0).to_array(),
        };
        gpu.queue
            .write_buffer(&self.camera_buf, 0, bytemuck::bytes_of(&cam));
        for k in 0..self.scene.lights.len() {
            let l = light_uniform(&self.scene, k);
            gpu.queue
                .write_buffer(&self.light_buf, SLOT * k as u64, bytemuck::bytes_of(&l));
        }
        let models = self.scene.relative_models();
        for (i, (o, &model)) in self.scene.objects.iter().zip(&models).enumerate() {
            let u = ObjectUniform {
                model: model.to_cols_array_2d(),
                normal_matrix: model.inverse().transpose().to_cols_array_2d(),
                color: o.color.extend(1.0).to_array(),
                id: [i as u32 + 1, 0, 0, 0],
            };
            gpu.queue
                .write_buffer(&self.object_buf, SLOT * i as u64, bytemuck::bytes_of(&u));
        }
    }

    /// Recomputes the camera after `scene.camera` changed.
    pub fn set_camera(&mut self, gpu: &Gpu) {
        self.camera = camera_matrices(&self.scene, self.width, self.height);
        (self.jitter, self.unjittered) = (Mat4::IDENTITY, None);
        self.upload_uniforms(gpu);
    }

    /// Moves the camera's image by the clip-space translation `jitter`
    /// (see [`SceneGpu::jitter`]) and uploads it; the identity puts back
    /// the very view-projection it had.
    pub fn set_jitter(&mut self, gpu: &Gpu, jitter: Mat4) {
        if jitter == self.jitter {
            return;
        }
        let base = *self.unjittered.get_or_insert(self.camera.view_proj);
        self.camera.view_proj = if jitter == Mat4::IDENTITY {
            self.unjittered = None;
            base
        } else {
            jitter * base
        };
        self.jitter = jitter;
        self.upload_uniforms(gpu);
    }

    /// Overrides light `k`'s view-projection (lesson 04 renders six cube faces).
    pub fn write_light_view_proj(&self, gpu: &Gpu, k: usize, view_proj: Mat4) {
        let mut l = light_uniform(&self.scene, k);
        l.view_proj = view_proj.to_cols_array_2d();
        gpu.queue
            .write_buffer(&self.light_buf, SLOT * k as u64, bytemuck::bytes_of(&l));
    }

    /// Render targets of the scene's size, with one visibility image per light.
    pub fn frame_targets(&self, gpu: &Gpu) -> FrameTargets {
        let size = (self.width, self.height);
        FrameTargets::new(gpu, size, self.depth_format, self.scene.lights.len())
    }

    // ANCHOR: bind_frame
    /// Binds group 0 for light `light`: the camera, and the light's slot of
    /// the light buffer (a dynamic offset), `light` in the shaders.
    pub fn bind_frame(&self, pass: &mut wgpu::RenderPass<'_>, light: usize) {
        pass.set_bind_group(0, &self.frame_group, &[(SLOT * light as u64) as u32]);
    }
    // ANCHOR_END: bind_frame

    /// Binds object `i`'s uniforms at group 1 (shadow volumes draw their own geometry).
    pub fn bind_object(&self, pass: &mut wgpu::RenderPass<'_>, i: usize) {
        pass.set_bind_group(1, &self.object_group, &[(SLOT * i as u64) as u32]);
    }

    /// Draws the objects `keep` selects, binding each one's uniforms at group 1.
    pub fn draw_objects(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        keep: impl Fn(usize) -> bool,
    ) -> u32 {
        let mut drawn = 0;
        for (i, m) in self.meshes.iter().enumerate() {
            if !keep(i) {
                continue;
            }
            pass.set_bind_group(1, &self.object_group, &[(SLOT * i as u64) as u32]);
            pass.set_vertex_buffer(0, m.vertices.slice(..));
            pass.set_index_buffer(m.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..m.index_count, 0, 0..1);
            drawn += 1;
        }
        drawn
    }

    /// The objects that cast shadows.
    pub fn casts_shadow(&self, i: usize) -> bool {
        self.scene.objects[i].casts_shadow
    }

    // ANCHOR: base_pass
    /// Depth, the ambient term and the object id, for every object.
    pub fn base_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        t: &FrameTargets,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) {
        self.base_pass_with(encoder, t, &self.base_pipeline, 1.0, ts);
    }

    /// [`SceneGpu::base_pass`] with another pipeline and depth clear value
    /// (lesson 07's reversed-Z clears to 0 and tests `Greater`).
    pub fn base_pass_with(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        t: &FrameTargets,
        pipeline: &wgpu::RenderPipeline,
        clear_depth: f32,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("base pass"),
            color_attachments: &[
                Some(t.color_attachment(wgpu::LoadOp::Clear(CLEAR_COLOR))),
                Some(t.id_attachment()),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &t.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear_depth),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0),
                    store: wgpu::StoreOp::Store,
                }),
            }),
            timestamp_writes: ts,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        self.bind_frame(&mut pass, 0);
        self.draw_objects(&mut pass, |_| true);
    }
    // ANCHOR_END: base_pass
}

/// The base pass's pipeline (`fs_base`: depth, the ambient term, the
/// object id) with `depth_stencil`. [`SceneGpu::new`] makes the standard
/// one (`Less` on the scene's depth format).
pub fn base_pipeline(
    gpu: &Gpu,
    frame_layout: &wgpu::BindGroupLayout,
    object_layout: &wgpu::BindGroupLayout,
    depth_stencil: wgpu::DepthStencilState,
) -> wgpu::RenderPipeline {
    let module = shader_module(gpu, "base pass", "");
    let layout = pipeline_layout_for(gpu, frame_layout, object_layout, &[]);
    gpu.device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("base pass"),
            layout: Some(&layout),
            vertex: vertex_state(&module, "vs_scene"),
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(depth_stencil),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_base"),
                compilation_options: Default::default(),
                targets: &[Some(COLOR_FORMAT.into()), Some(ID_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        })
}

/// Layout with group 0 (frame), group 1 (object), then the lesson's groups.
pub fn pipeline_layout_for(
    gpu: &Gpu,
    frame: &wgpu::BindGroupLayout,
    object: &wgpu::BindGroupLayout,
    extra: &[&wgpu::BindGroupLayout],
) -> wgpu::PipelineLayout {
    let mut layouts: Vec<Option<&wgpu::BindGroupLayout>> = vec![Some(frame), Some(object)];
    layouts.extend(extra.iter().map(|l| Some(*l)));
    gpu.device
        .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &layouts,
            immediate_size: 0,
        })
}

pub fn vertex_state<'a>(module: &'a wgpu::ShaderModule, entry: &'a str) -> wgpu::VertexState<'a> {
    wgpu::VertexState {
        module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        buffers: &[Some(VERTEX_LAYOUT)],
    }
}

fn upload_mesh(gpu: &Gpu, scene: &Scene, i: usize) -> Result<GpuMesh> {
    let m = &scene.objects[i].mesh;
    if m.indices.is_empty() {
        return Err(anyhow!(
            "objects[{i}].mesh: {:?} has no triangles",
            scene.objects[i].mesh_name
        ));
    }
    let verts: Vec<Vertex> = m
        .positions
        .iter()
        .zip(&m.normals)
        .map(|(p, n)| Vertex {
            position: p.to_array(),
            normal: n.to_array(),
        })
        .collect();
    let vertices = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&m.name),
            contents: bytemuck::cast_slice(&verts),
            usage: wgpu::BufferUsages::VERTEX,
        });
    let indices = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&m.name),
            contents: bytemuck::cast_slice(&m.indices),
            usage: wgpu::BufferUsages::INDEX,
        });
    Ok(GpuMesh {
        vertices,
        indices,
        index_count: m.indices.len() as u32,
    })
}
