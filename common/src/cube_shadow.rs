//! Cube-map shadows for point lights (lesson 04): the light renders six 90°
//! faces into the six layers of one depth texture; the lit pass samples it
//! through a `Cube` view with the direction from the light.
//!
//! Also here: the per-face light uniforms (six faces in one submission need
//! six uniform slots), the bounding spheres that cull casters per face, and
//! a GL-safe picture of the six faces.

use std::path::Path;

use anyhow::Result;
use glam::dcamera::rh::proj::directx as webgpu;
use glam::dcamera::rh::view::look_at_mat4;
use glam::{DMat4, DVec3, Mat4};

use crate::camera::light_uniform;
use crate::gpu::Gpu;
use crate::render::{
    depth_texture, pipeline_layout_for, read_texture, render_texture, vertex_state, SceneGpu,
};
use crate::scene::{LightKind, Scene};
use crate::timing::Frame;

pub const CUBE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Uniform slots are spaced by the dynamic-offset alignment.
const SLOT: u64 = 256;

// ANCHOR: cube_faces
/// The six faces in wgpu's layer order +X, −X, +Y, −Y, +Z, −Z: the axis each
/// face looks along, and its `up` (the usual cube-map up vectors).
pub const CUBE_FACES: [(DVec3, DVec3); 6] = [
    (DVec3::X, DVec3::NEG_Y),
    (DVec3::NEG_X, DVec3::NEG_Y),
    (DVec3::Y, DVec3::Z),
    (DVec3::NEG_Y, DVec3::NEG_Z),
    (DVec3::Z, DVec3::NEG_Y),
    (DVec3::NEG_Z, DVec3::NEG_Y),
];

/// Face `face`'s view-projection for a light at `light` (origin-relative):
/// a square 90° frustum, so the six faces tile every direction exactly.
pub fn face_view_proj(light: DVec3, face: usize, near: f64, far: f64) -> Mat4 {
    let (axis, up) = CUBE_FACES[face];
    let view = look_at_mat4(light, light + axis, up);
    let proj = webgpu::perspective(std::f64::consts::FRAC_PI_2, 1.0, near, far);
    // Those up vectors were made for OpenGL, whose framebuffer rows grow
    // upwards; WebGPU's grow downwards. Flip y, or every face is read upside down.
    (DMat4::from_scale(DVec3::new(1.0, -1.0, 1.0)) * proj * view).as_mat4()
}
// ANCHOR_END: cube_faces

/// The light's position (origin-relative) and range; `None` for a directional light.
pub fn point_light(scene: &Scene, light: usize) -> Option<(DVec3, f64)> {
    match scene.lights[light].kind {
        LightKind::Point { position, range }
        | LightKind::Spot {
            position, range, ..
        } => Some((position - scene.origin(), range)),
        LightKind::Directional { .. } => None,
    }
}

/// A bounding sphere, origin-relative.
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    pub centre: DVec3,
    pub radius: f64,
}

/// Each object's bounding sphere: around its world-space bounding box.
pub fn bounding_spheres(scene: &Scene) -> Vec<Sphere> {
    let o = scene.origin();
    scene
        .objects
        .iter()
        .map(|obj| {
            let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            for p in &obj.mesh.positions {
                let w = obj.model.transform_point3(p.as_dvec3()) - o;
                lo = lo.min(w);
                hi = hi.max(w);
            }
            Sphere {
                centre: (lo + hi) * 0.5,
                radius: (hi - lo).length() * 0.5,
            }
        })
        .collect()
}

// ANCHOR: sphere_in_face
/// Whether a sphere (centre relative to the light) can touch face `face`'s
/// frustum. Face +X holds the directions with x ≥ |y| and x ≥ |z|: four
/// planes through the light, with normals (1, ∓1, 0)/√2 and (1, 0, ∓1)/√2.
pub fn sphere_touches_face(centre: DVec3, radius: f64, face: usize) -> bool {
    let (axis, up) = CUBE_FACES[face];
    let side = axis.cross(up);
    let m = centre.dot(axis);
    let (a, b) = (centre.dot(up), centre.dot(side));
    // The signed distance to each side plane must be > -radius.
    (m - a.abs()) / 2f64.sqrt() > -radius && (m - b.abs()) / 2f64.sqrt() > -radius
}
// ANCHOR_END: sphere_in_face

/// A cube of six square depth layers: one `D2` view per face to render
/// into, one `Cube` view to sample.
pub struct CubeShadowMap {
    pub size: u32,
    pub texture: wgpu::Texture,
    pub face_views: Vec<wgpu::TextureView>,
    pub cube_view: wgpu::TextureView,
    /// Faces holding only the clear value: a skipped face needs no pass at all.
    empty: [bool; 6],
}

impl CubeShadowMap {
    pub fn new(gpu: &Gpu, size: u32) -> CubeShadowMap {
        // Six square layers: GL makes this a cube map texture (wgpu's rule).
        let texture = depth_texture(
            gpu,
            &format!("cube shadow map {size}"),
            size,
            6,
            CUBE_FORMAT,
        );
        let face_views = (0..6)
            .map(|i| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: i,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        let cube_view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::Cube),
            ..Default::default()
        });
        CubeShadowMap {
            size,
            texture,
            face_views,
            cube_view,
            empty: [false; 6],
        }
    }
}

/// Six light uniforms per light (one per face), bound as group 0 with the
/// scene's frame layout: `write_light_view_proj` has one slot per light, and
/// queue writes all land before the frame's single submission.
pub struct FaceUniforms {
    buffer: wgpu::Buffer,
    group: wgpu::BindGroup,
}

impl FaceUniforms {
    pub fn new(gpu: &Gpu, scene: &SceneGpu) -> FaceUniforms {
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cube face lights"),
            size: SLOT * 6 * scene.scene.lights.len().max(1) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Binding 0 (the camera) is unused by the shadow shaders but part of the layout.
        let camera = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cube faces: unused camera"),
            size: 96,
            usage: wgpu::BufferUsages::UNIFORM,
            mapped_at_creation: false,
        });
        let light_size = std::mem::size_of::<crate::camera::LightUniform>() as u64;
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cube faces"),
            layout: &scene.frame_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: camera.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(light_size),
                    }),
                },
            ],
        });
        FaceUniforms { buffer, group }
    }

    /// Writes the six faces' view-projections of light `light`.
    pub fn write(&self, gpu: &Gpu, scene: &Scene, light: usize, near: f64) {
        let Some((pos, range)) = point_light(scene, light) else {
            return;
        };
        for face in 0..6 {
            let mut u = light_uniform(scene, light);
            u.view_proj = face_view_proj(pos, face, near, range).to_cols_array_2d();
            gpu.queue.write_buffer(
                &self.buffer,
                SLOT * (6 * light + face) as u64,
                bytemuck::bytes_of(&u),
            );
        }
    }
}

/// How the cube stores depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthStorage {
    /// distance / range, written by the fragment shader (`fs_entry`).
    Linear {
        vs_entry: &'static str,
        fs_entry: &'static str,
    },
    /// The face projection's own depth (`vs_light_depth`, no fragment shader).
    Hardware,
}

/// The depth-only pipeline of the cube faces. `unclipped` turns off the
/// near/far clip (needs DEPTH_CLIP_CONTROL): depth is clamped instead.
pub fn cube_shadow_pipeline(
    gpu: &Gpu,
    scene: &SceneGpu,
    module: &wgpu::ShaderModule,
    storage: DepthStorage,
    unclipped: bool,
) -> wgpu::RenderPipeline {
    let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
    let (vs, fs) = match storage {
        DepthStorage::Linear { vs_entry, fs_entry } => (vs_entry, Some(fs_entry)),
        DepthStorage::Hardware => ("vs_light_depth", None),
    };
    gpu.device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("cube shadow pass"),
            layout: Some(&layout),
            vertex: vertex_state(module, vs),
            primitive: wgpu::PrimitiveState {
                unclipped_depth: unclipped,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: CUBE_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: fs.map(|entry| wgpu::FragmentState {
                module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                targets: &[],
            }),
            multiview_mask: None,
            cache: None,
        })
}

/// What the shadow passes drew.
#[derive(Clone, Copy, Debug, Default)]
pub struct CubeStats {
    pub faces_rendered: u64,
    pub caster_draws: u64,
}

// ANCHOR: cube_shadow_passes
/// Renders light `light`'s six faces, one render pass each (timed as
/// "shadow"). `casters(face)` lists the objects to draw into a face; a face
/// with none is skipped (it is cleared once, then left alone).
pub fn cube_shadow_passes(
    frame: &mut Frame,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    map: &mut CubeShadowMap,
    faces: &FaceUniforms,
    light: usize,
    casters: impl Fn(usize) -> Vec<usize>,
) -> CubeStats {
    let mut stats = CubeStats::default();
    for face in 0..6 {
        let list = casters(face);
        if list.is_empty() && map.empty[face] {
            continue;
        }
        frame.pass("shadow", |enc, ts| {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("cube face"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &map.face_views[face],
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: ts.render(),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(
                0,
                &faces.group,
                &[(SLOT * (6 * light + face) as u64) as u32],
            );
            stats.caster_draws += scene.draw_objects(&mut pass, |i| list.contains(&i)) as u64;
        });
        map.empty[face] = list.is_empty();
        stats.faces_rendered += u64::from(!list.is_empty());
    }
    stats
}
// ANCHOR_END: cube_shadow_passes

/// Bind group layout for the lit pass (group 2): the cube (binding 0), a
/// comparison sampler (1), and the lesson's parameters (2, `params_size` bytes).
pub fn cube_map_layout(gpu: &Gpu, params_size: u64) -> wgpu::BindGroupLayout {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cube shadow map"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: fragment,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::Cube,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: fragment,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: fragment,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(params_size),
                    },
                    count: None,
                },
            ],
        })
}

/// The matching bind group, with its own parameter buffer holding `params`.
pub fn cube_map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &CubeShadowMap,
    filter: wgpu::FilterMode,
    params: &[u8],
) -> wgpu::BindGroup {
    use wgpu::util::DeviceExt;
    let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("cube comparison"),
        mag_filter: filter,
        min_filter: filter,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    });
    let buffer = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("cube params"),
            contents: params,
            usage: wgpu::BufferUsages::UNIFORM,
        });
    cube_group(gpu, layout, map, &sampler, &buffer)
}

const CROSS_WGSL: &str = r#"
// The cube bound as unfilterable float (GL cannot textureLoad a depth cube).
@group(0) @binding(0) var cube: texture_cube<f32>;
@group(0) @binding(1) var nearest: sampler;
@group(0) @binding(2) var<uniform> face_px: vec4<f32>;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
}
// A horizontal cross: +Y above, then -X +Z +X -Z, then -Y below. Each cell is
// turned into the direction the sampler maps to it (the cube-map rules).
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let cell = vec2<i32>(p.xy / face_px.x);
    let st = fract(p.xy / face_px.x) * 2.0 - 1.0;
    var d = vec3<f32>(0.0);
    if cell.y == 0 && cell.x == 1 { d = vec3<f32>(st.x, 1.0, st.y); }
    if cell.y == 2 && cell.x == 1 { d = vec3<f32>(st.x, -1.0, -st.y); }
    if cell.y == 1 && cell.x == 0 { d = vec3<f32>(-1.0, -st.y, st.x); }
    if cell.y == 1 && cell.x == 1 { d = vec3<f32>(st.x, -st.y, 1.0); }
    if cell.y == 1 && cell.x == 2 { d = vec3<f32>(1.0, -st.y, -st.x); }
    if cell.y == 1 && cell.x == 3 { d = vec3<f32>(-st.x, -st.y, -1.0); }
    var depth = -1.0;
    if any(d != vec3<f32>(0.0)) { depth = textureSampleLevel(cube, nearest, d, 0.0).r; }
    return unpack4x8unorm(bitcast<u32>(depth));
}
"#;

/// Writes the six faces as a cross (`face_px` pixels per face): near dark,
/// far light, stretched over the depths the map holds; background black.
pub fn write_cross_png(gpu: &Gpu, map: &CubeShadowMap, face_px: u32, path: &Path) -> Result<()> {
    use wgpu::util::DeviceExt;
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("cube cross"),
        source: wgpu::ShaderSource::Wgsl(CROSS_WGSL.into()),
    });
    let fragment = wgpu::ShaderStages::FRAGMENT;
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("cube cross"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: fragment,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::Cube,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: fragment,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::NonFiltering),
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: fragment,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    });
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor::default());
    let px = [face_px as f32, 0.0, 0.0, 0.0];
    let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::bytes_of(&px),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let group = cube_group(gpu, &layout, map, &sampler, &buf);
    let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("cube cross"),
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
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let (w, h) = (4 * face_px, 3 * face_px);
    let target = render_texture(
        gpu,
        "cube cross",
        w,
        h,
        format,
        wgpu::TextureUsages::empty(),
    );
    let view = target.create_view(&Default::default());
    let mut enc = device.create_command_encoder(&Default::default());
    crate::render::draw_fullscreen(&mut enc, &view, &pipeline, &group);
    gpu.queue.submit([enc.finish()]);
    let bytes = read_texture(gpu, &target, 4)?;
    let d: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        .collect();
    let lo = d
        .iter()
        .copied()
        .filter(|&x| x >= 0.0)
        .fold(f32::INFINITY, f32::min);
    let hi = d
        .iter()
        .copied()
        .filter(|x| (0.0..1.0).contains(x))
        .fold(lo, f32::max);
    let span = (hi - lo).max(1e-12);
    let img = image::GrayImage::from_fn(w, h, |x, y| {
        let v = d[(y * w + x) as usize];
        image::Luma([if v < 0.0 {
            0
        } else if v >= 1.0 {
            255
        } else {
            20 + (((v - lo) / span) * 215.0).round() as u8
        }])
    });
    crate::app::save(&img, path)
}

/// The cube map, its sampler and a parameter buffer as bindings 0, 1, 2.
fn cube_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &CubeShadowMap,
    sampler: &wgpu::Sampler,
    params: &wgpu::Buffer,
) -> wgpu::BindGroup {
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("cube shadow map"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&map.cube_view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(sampler),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: params.as_entire_binding(),
            },
        ],
    })
}
