//! The scene on the GPU, the frame's render targets, and the passes every
//! lesson shares: the base pass (depth, ambient, object id) and the lit pass
//! (one light added on top, with the technique's visibility written out).

use anyhow::{anyhow, Result};
use glam::Mat4;
use wgpu::util::DeviceExt;

use crate::camera::{camera_matrices, light_uniform, CameraMatrices, LightUniform};
use crate::gpu::Gpu;
use crate::scene::Scene;

/// The WGSL every lesson shader is appended to.
pub const COMMON_WGSL: &str = include_str!("../../shaders/common.wgsl");

pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
pub const ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
/// 8-bit, like the visibility PNGs; R32Float is not renderable on downlevel GL.
pub const VISIBILITY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;
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

fn uniform_entry(binding: u32, dynamic: bool, size: u64) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic,
            min_binding_size: wgpu::BufferSize::new(size),
        },
        count: None,
    }
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
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let light_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lights"),
            size: SLOT * scene.lights.len() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let object_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("objects"),
            size: SLOT * scene.objects.len() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[
                uniform_entry(0, false, std::mem::size_of::<CameraUniform>() as u64),
                uniform_entry(1, true, std::mem::size_of::<LightUniform>() as u64),
            ],
        });
        let object_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("object"),
            entries: &[uniform_entry(
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
        let module = shader_module(gpu, "base pass", "");
        let layout = pipeline_layout_for(gpu, &frame_layout, &object_layout, &[]);
        let base_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("base pass"),
            layout: Some(&layout),
            vertex: vertex_state(&module, "vs_scene"),
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: depth_format,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_base"),
                compilation_options: Default::default(),
                targets: &[Some(COLOR_FORMAT.into()), Some(ID_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let camera = camera_matrices(&scene, width, height);
        let s = SceneGpu {
            scene,
            width,
            height,
            camera,
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
        for (i, o) in self.scene.objects.iter().enumerate() {
            let model = self.scene.model_relative(i);
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
        self.upload_uniforms(gpu);
    }

    /// Overrides light `k`'s view-projection (lesson 04 renders six cube faces).
    pub fn write_light_view_proj(&self, gpu: &Gpu, k: usize, view_proj: Mat4) {
        let mut l = light_uniform(&self.scene, k);
        l.view_proj = view_proj.to_cols_array_2d();
        gpu.queue
            .write_buffer(&self.light_buf, SLOT * k as u64, bytemuck::bytes_of(&l));
    }

    /// Binds group 0 for light `k`.
    pub fn bind_frame(&self, pass: &mut wgpu::RenderPass<'_>, light: usize) {
        pass.set_bind_group(0, &self.frame_group, &[(SLOT * light as u64) as u32]);
    }

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
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("base pass"),
            color_attachments: &[
                Some(t.color_attachment(wgpu::LoadOp::Clear(CLEAR_COLOR))),
                Some(t.id_attachment()),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &t.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
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
        pass.set_pipeline(&self.base_pipeline);
        self.bind_frame(&mut pass, 0);
        self.draw_objects(&mut pass, |_| true);
    }
    // ANCHOR_END: base_pass

    /// A lit-pass pipeline: the lesson's `fs_entry` adds one light where the
    /// depth equals the base pass's, and writes its visibility. Extra bind
    /// groups (the shadow map, ...) start at group 2.
    pub fn lit_pipeline(
        &self,
        gpu: &Gpu,
        module: &wgpu::ShaderModule,
        fs_entry: &str,
        extra: &[&wgpu::BindGroupLayout],
        stencil: wgpu::StencilState,
    ) -> wgpu::RenderPipeline {
        let layout = pipeline_layout_for(gpu, &self.frame_layout, &self.object_layout, extra);
        let add = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent::OVER,
        };
        gpu.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(fs_entry),
                layout: Some(&layout),
                vertex: vertex_state(module, "vs_scene"),
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: self.depth_format,
                    depth_write_enabled: Some(false),
                    // Same vertices, same matrices, @invariant: the depths are equal.
                    depth_compare: Some(wgpu::CompareFunction::LessEqual),
                    stencil,
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(fs_entry),
                    compilation_options: Default::default(),
                    targets: &[
                        Some(wgpu::ColorTargetState {
                            format: COLOR_FORMAT,
                            blend: Some(add),
                            write_mask: wgpu::ColorWrites::ALL,
                        }),
                        Some(VISIBILITY_FORMAT.into()),
                    ],
                }),
                multiview_mask: None,
                cache: None,
            })
    }

    /// Adds light `light` to the frame through `pipeline`, writing its visibility.
    // One argument per thing a learner varies between lessons; a struct would hide them.
    #[allow(clippy::too_many_arguments)]
    pub fn lit_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        t: &FrameTargets,
        light: usize,
        pipeline: &wgpu::RenderPipeline,
        extra: &[&wgpu::BindGroup],
        stencil_reference: u32,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("lit pass"),
            color_attachments: &[
                Some(t.color_attachment(wgpu::LoadOp::Load)),
                Some(wgpu::RenderPassColorAttachment {
                    view: &t.visibility_views[light],
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                }),
            ],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &t.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                }),
            }),
            timestamp_writes: ts,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_stencil_reference(stencil_reference);
        self.bind_frame(&mut pass, light);
        for (i, g) in extra.iter().enumerate() {
            pass.set_bind_group(2 + i as u32, *g, &[]);
        }
        self.draw_objects(&mut pass, |_| true);
    }
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

/// The frame's render targets: shaded colour, depth-stencil, object id, and
/// one visibility image per light.
pub struct FrameTargets {
    pub width: u32,
    pub height: u32,
    pub color: wgpu::Texture,
    pub color_view: wgpu::TextureView,
    pub depth: wgpu::Texture,
    pub depth_view: wgpu::TextureView,
    pub id: wgpu::Texture,
    pub id_view: wgpu::TextureView,
    pub visibility: Vec<wgpu::Texture>,
    pub visibility_views: Vec<wgpu::TextureView>,
}

pub fn render_texture(
    gpu: &Gpu,
    label: &str,
    w: u32,
    h: u32,
    format: wgpu::TextureFormat,
    extra: wgpu::TextureUsages,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC | extra,
        view_formats: &[],
    })
}

impl FrameTargets {
    pub fn new(gpu: &Gpu, scene: &SceneGpu) -> FrameTargets {
        let (w, h) = (scene.width, scene.height);
        let tb = wgpu::TextureUsages::TEXTURE_BINDING;
        let color = render_texture(gpu, "color", w, h, COLOR_FORMAT, tb);
        let depth = render_texture(gpu, "depth", w, h, scene.depth_format, tb);
        let id = render_texture(gpu, "id", w, h, ID_FORMAT, wgpu::TextureUsages::empty());
        let visibility: Vec<_> = (0..scene.scene.lights.len())
            .map(|k| {
                render_texture(
                    gpu,
                    &format!("visibility {k}"),
                    w,
                    h,
                    VISIBILITY_FORMAT,
                    wgpu::TextureUsages::empty(),
                )
            })
            .collect();
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        FrameTargets {
            width: w,
            height: h,
            color_view: view(&color),
            depth_view: view(&depth),
            id_view: view(&id),
            visibility_views: visibility.iter().map(view).collect(),
            color,
            depth,
            id,
            visibility,
        }
    }

    /// A pass with no colour target that keeps the base pass's depth and
    /// starts the stencil at 0: every light's volume pass begins this way.
    pub fn stencil_pass<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        label: &str,
        ts: Option<wgpu::RenderPassTimestampWrites<'_>>,
        occlusion_query_set: Option<&wgpu::QuerySet>,
    ) -> wgpu::RenderPass<'e> {
        let keep = wgpu::Operations {
            load: wgpu::LoadOp::Load,
            store: wgpu::StoreOp::Store,
        };
        let zero = wgpu::Operations {
            load: wgpu::LoadOp::Clear(0),
            store: wgpu::StoreOp::Store,
        };
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth_view,
                depth_ops: Some(keep),
                stencil_ops: Some(zero),
            }),
            timestamp_writes: ts,
            occlusion_query_set,
            multiview_mask: None,
        })
    }

    pub fn color_attachment(
        &self,
        load: wgpu::LoadOp<wgpu::Color>,
    ) -> wgpu::RenderPassColorAttachment<'_> {
        wgpu::RenderPassColorAttachment {
            view: &self.color_view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load,
                store: wgpu::StoreOp::Store,
            },
        }
    }

    fn id_attachment(&self) -> wgpu::RenderPassColorAttachment<'_> {
        wgpu::RenderPassColorAttachment {
            view: &self.id_view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        }
    }

    /// Reads back the frame: colour (RGBA8), object ids, visibility per light.
    pub fn read(&self, gpu: &Gpu) -> Result<FrameImages> {
        let color = read_texture(gpu, &self.color, 4)?;
        let id: Vec<u32> = bytemuck::cast_slice(&read_texture(gpu, &self.id, 4)?).to_vec();
        let visibility = self
            .visibility
            .iter()
            .map(|t| read_texture(gpu, t, 1).map(|b| b.iter().map(|&v| v as f32 / 255.0).collect()))
            .collect::<Result<Vec<_>>>()?;
        Ok(FrameImages {
            width: self.width,
            height: self.height,
            color,
            id,
            visibility,
        })
    }
}

/// A frame read back to the CPU.
pub struct FrameImages {
    pub width: u32,
    pub height: u32,
    pub color: Vec<u8>,
    pub id: Vec<u32>,
    pub visibility: Vec<Vec<f32>>,
}

/// Copies a 2D texture (one layer) to the CPU, tightly packed.
pub fn read_texture(gpu: &Gpu, tex: &wgpu::Texture, bytes_per_pixel: u32) -> Result<Vec<u8>> {
    read_texture_layer(gpu, tex, bytes_per_pixel, 0, wgpu::TextureAspect::All)
}

/// Copies one layer (and aspect) of a texture to the CPU, tightly packed.
pub fn read_texture_layer(
    gpu: &Gpu,
    tex: &wgpu::Texture,
    bpp: u32,
    layer: u32,
    aspect: wgpu::TextureAspect,
) -> Result<Vec<u8>> {
    let (w, h) = (tex.width(), tex.height());
    let row = w * bpp;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: padded as u64 * h as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    enc.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: tex,
            mip_level: 0,
            origin: wgpu::Origin3d {
                x: 0,
                y: 0,
                z: layer,
            },
            aspect,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buf,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([enc.finish()]);
    let slice = buf.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    gpu.wait()?;
    let mut out = Vec::with_capacity((row * h) as usize);
    {
        let data = slice
            .get_mapped_range()
            .map_err(|e| anyhow!("texture readback: {e}"))?;
        for y in 0..h as usize {
            out.extend_from_slice(&data[y * padded as usize..y * padded as usize + row as usize]);
        }
    }
    buf.unmap();
    Ok(out)
}

/// A depth texture the lesson samples (shadow maps).
pub fn depth_texture(
    gpu: &Gpu,
    label: &str,
    size: u32,
    layers: u32,
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// WGSL for one triangle that covers the target (`vs_fullscreen`), for
/// passes that process an image: prepend it to a fragment shader.
pub const FULLSCREEN_WGSL: &str = r#"
struct FullscreenOut { @builtin(position) pos: vec4<f32>, @location(0) uv: vec2<f32> };
@vertex fn vs_fullscreen(@builtin(vertex_index) i: u32) -> FullscreenOut {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var o: FullscreenOut;
    o.pos = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    o.uv = uv;
    return o;
}
"#;

/// A pipeline drawing `FULLSCREEN_WGSL`'s triangle with `fs_entry` into one
/// colour target, reading bind group 0.
pub fn fullscreen_pipeline(
    gpu: &Gpu,
    label: &str,
    fragment_wgsl: &str,
    fs_entry: &str,
    layout: &wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(format!("{FULLSCREEN_WGSL}\n{fragment_wgsl}").into()),
        });
    let pl = gpu
        .device
        .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(layout)],
            immediate_size: 0,
        });
    gpu.device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(&pl),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_fullscreen"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(fs_entry),
                compilation_options: Default::default(),
                targets: &[Some(format.into())],
            }),
            multiview_mask: None,
            cache: None,
        })
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
