//! Cube-map shadows for point lights (lesson 04): the light renders six 90°
//! faces into the six layers of one depth texture; the lit pass samples it
//! through a `Cube` view with the direction from the light.
//!
//! Also here: the per-face light uniforms (six faces in one submission need
//! six uniform slots), the two ways to store depth, and the lit pass's
//! parameters. Culling is in [`super::culling`], the picture of the six
//! faces in [`super::cross`].

use common::glam::dcamera::rh::proj::directx as webgpu;
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec3, Mat4};
use common::gpu::bindings::{self, params_buffer, sampler_entry, storage_entry, texture_entry};
use common::gpu::render::{pipeline_layout_for, vertex_state, SceneGpu, SCENE_BUFFER_USAGE};
use common::gpu::targets::depth_texture;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::scene::camera::{light_uniform, LightUniform};
use common::scene::{Light, LightKind, Scene};

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

/// The light's position (relative to `origin`, the scene's) and range;
/// `None` for a directional light.
pub fn point_light(scene: &Scene, origin: DVec3, light: usize) -> Option<(DVec3, f64)> {
    match scene.lights[light].kind {
        LightKind::Point { position, range }
        | LightKind::Spot {
            position, range, ..
        } => Some((position - origin, range)),
        LightKind::Directional { .. } => None,
    }
}

/// [`light_uniform`] of each light, made again only when the light
/// changes (the window moves lights): making it finds the scene's origin,
/// and a directional light's map the scene's bounds, passes over every
/// vertex that no frame needs to repeat (objects do not move).
#[derive(Clone, Debug, Default)]
pub struct LightUniforms(Vec<Option<(Light, LightUniform)>>);

impl LightUniforms {
    /// Light `light`'s uniform, as [`light_uniform`] makes it.
    pub fn get(&mut self, scene: &Scene, light: usize) -> LightUniform {
        let l = scene.lights[light];
        if self.0.len() <= light {
            self.0.resize(light + 1, None);
        }
        match self.0[light] {
            Some((made_for, u)) if made_for == l => u,
            _ => {
                let u = light_uniform(scene, light);
                self.0[light] = Some((l, u));
                u
            }
        }
    }
}

/// A cube of six square depth layers: one `D2` view per face to render
/// into, one view to sample: `Cube`, or for [`CubeShadowMap::new_faces`]
/// a `D2Array` of the six layers.
pub struct CubeShadowMap {
    pub size: u32,
    pub texture: wgpu::Texture,
    pub face_views: Vec<wgpu::TextureView>,
    pub cube_view: wgpu::TextureView,
    /// `cube_view` is the six layers as a 2D array (the exercise's lookup).
    pub faces: bool,
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
        let face_views = common::gpu::targets::layer_views(&texture, 6);
        let cube_view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::Cube),
            ..Default::default()
        });
        CubeShadowMap {
            size,
            texture,
            face_views,
            cube_view,
            faces: false,
            empty: [false; 6],
        }
    }

    /// The same six faces, sampled as a `D2Array` (`exercise_cube_faces`):
    /// no cube view at all. A seventh, unused layer keeps the texture from
    /// being cube-compatible, which GL would make a cube map texture.
    pub fn new_faces(gpu: &Gpu, size: u32) -> CubeShadowMap {
        let label = format!("cube shadow map {size} as a 2D array");
        let texture = depth_texture(gpu, &label, size, 7, CUBE_FORMAT);
        let face_views = common::gpu::targets::layer_views(&texture, 6);
        let cube_view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            array_layer_count: Some(6),
            ..Default::default()
        });
        CubeShadowMap {
            size,
            texture,
            face_views,
            cube_view,
            faces: true,
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
    /// The scene's origin, found once (objects do not move), each light's
    /// uniform, made once per light, and the six slots last written for
    /// each light.
    pub origin: DVec3,
    lights: LightUniforms,
    written: Vec<Vec<u8>>,
}

impl FaceUniforms {
    pub fn new(gpu: &Gpu, scene: &SceneGpu) -> FaceUniforms {
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cube face lights"),
            size: SLOT * 6 * scene.scene.lights.len().max(1) as u64,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        // Binding 0 (the camera) is unused by the shadow shaders but part of the layout.
        let camera = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cube faces: unused camera"),
            size: 96,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        let light_size = std::mem::size_of::<LightUniform>() as u64;
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
        FaceUniforms {
            buffer,
            group,
            origin: scene.scene.origin(),
            lights: LightUniforms::default(),
            written: vec![Vec::new(); scene.scene.lights.len()],
        }
    }

    /// Binds face `face` of light `light` as group 0.
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>, light: usize, face: usize) {
        let offset = (SLOT * (6 * light + face) as u64) as u32;
        pass.set_bind_group(0, &self.group, &[offset]);
    }

    /// Writes the six faces' view-projections of light `light`, from `near`
    /// to `far` (`None`: the light's range).
    pub fn write(&mut self, gpu: &Gpu, scene: &Scene, light: usize, near: f64, far: Option<f64>) {
        let Some((pos, range)) = point_light(scene, self.origin, light) else {
            return;
        };
        let far = far.unwrap_or(range);
        let base = self.lights.get(scene, light);
        // The six slots in one write, when they change (the light moved,
        // or another variant's near and far).
        let mut slots = vec![0u8; 6 * SLOT as usize];
        for (face, slot) in slots.chunks_exact_mut(SLOT as usize).enumerate() {
            let mut u = base;
            u.view_proj = face_view_proj(pos, face, near, far).to_cols_array_2d();
            // The faces' far plane in the range's slot: what the linear
            // storage divides the distance by (`fs_cube_linear`).
            u.color_range[3] = far as f32;
            slot[..std::mem::size_of::<LightUniform>()].copy_from_slice(bytemuck::bytes_of(&u));
        }
        if self.written[light] != slots {
            gpu.queue
                .write_buffer(&self.buffer, SLOT * 6 * light as u64, &slots);
            self.written[light] = slots;
        }
    }
}

// ANCHOR: storage
/// How the lit pass compares: what the cube stores, and how the receiver's
/// depth is computed to match it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Storage {
    /// distance / range, from the fragment shader.
    Linear,
    /// The face's hardware depth, the receiver converted along its major axis.
    Depth,
    /// Hardware depth compared with |v| instead: the naive mistake.
    DepthEuclid,
    /// Hardware depth, read without a cube: the face and texel chosen by
    /// the chapter's exercise (`exercise_cube_texel` in `exercises.wgsl`)
    /// in the six layers seen as a 2D array.
    DepthExercise,
}

impl Storage {
    /// The shadow pass that fills the cube for this storage.
    pub fn pass(self) -> DepthStorage {
        match self {
            Storage::Linear => DepthStorage::Linear {
                vs_entry: "vs_cube_linear",
                fs_entry: "fs_cube_linear",
            },
            Storage::Depth | Storage::DepthEuclid | Storage::DepthExercise => {
                DepthStorage::Hardware
            }
        }
    }
}
// ANCHOR_END: storage

/// The lit pass's parameters (`CubeParams` in `shaders/lesson_04/cube_map.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CubeParams {
    /// The faces' near plane.
    pub near: f32,
    /// 2 / face resolution: a texel's width 1 m from the light.
    pub texel_at_1m: f32,
    /// 1: clamp the receiver to the far plane.
    pub clamp_range: u32,
    /// The faces' far plane in metres; 0: the light's range.
    pub far: f32,
    /// A constant bias in world units.
    pub bias_world: f32,
    /// A bias in texels, plus `slope` × tan θ texels.
    pub bias_texels: f32,
    pub slope: f32,
    /// 3D PCF radius in texels, where [`LitKey::filtered`].
    pub pcf: f32,
    /// LearnOpenGL: the disk's radius per (1 + view distance / range), in
    /// world units; Bevy: the normal bias per unit of major-axis distance.
    pub peer_scale: f32,
    pub _pad: [f32; 3],
}

/// The lit pipeline's constants (`override`s in `cube_map.wgsl`): the
/// lookup's shape, compiled in, so that a variant runs only its own taps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LitKey {
    /// 0 linear distance, 1 hardware depth, 2 hardware depth compared with
    /// the Euclidean distance, 3 the exercise's ([`Storage`] in order).
    pub storage: u32,
    /// A renderer's lookup instead (`shaders/lesson_04/peers.wgsl`): 0 none,
    /// 1 LearnOpenGL's 20-tap disk, 2 Bevy's offsets and 8-tap Gaussian
    /// ([`super::peers::Peer`]).
    pub peer: u32,
    /// 3D PCF (20 taps) instead of one tap.
    pub filtered: bool,
}

impl LitKey {
    /// The lit pipeline for this key: `fs_lit` compiled with its constants.
    pub fn pipeline(
        self,
        gpu: &Gpu,
        scene: &SceneGpu,
        module: &wgpu::ShaderModule,
        layout: &wgpu::BindGroupLayout,
    ) -> wgpu::RenderPipeline {
        let constants = [
            ("STORAGE", self.storage as f64),
            ("PEER", self.peer as f64),
            ("FILTERED", self.filtered as u32 as f64),
        ];
        // The exercise's lookup has its own entry point (no cube bound).
        let entry = if self.storage == Storage::DepthExercise as u32 {
            "fs_lit_faces"
        } else {
            "fs_lit"
        };
        scene.lit_pipeline_with_depth(
            gpu,
            module,
            entry,
            &[layout],
            scene.lit_depth_state(Default::default()),
            &constants,
        )
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
    let (vs, fs) = match storage {
        DepthStorage::Linear { vs_entry, fs_entry } => (vs_entry, Some(fs_entry)),
        DepthStorage::Hardware => ("vs_light_depth", None),
    };
    let fragment = fs.map(|entry| wgpu::FragmentState {
        module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        targets: &[],
    });
    let compare = wgpu::CompareFunction::Less;
    cube_pipeline_with(gpu, scene, module, vs, fragment, compare, unclipped)
}

/// A cube-face pipeline with vertex entry `vs`, `fragment` and depth test
/// `compare`: the shadow pass, or a counting copy of it (`super::costs`).
pub(crate) fn cube_pipeline_with(
    gpu: &Gpu,
    scene: &SceneGpu,
    module: &wgpu::ShaderModule,
    vs: &str,
    fragment: Option<wgpu::FragmentState<'_>>,
    compare: wgpu::CompareFunction,
    unclipped: bool,
) -> wgpu::RenderPipeline {
    let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
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
                depth_compare: Some(compare),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment,
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
            faces.bind(&mut pass, light, face);
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
/// `faces`: the six faces as a 2D array at binding 3 instead of the cube.
pub fn cube_map_layout(gpu: &Gpu, params_size: u64, faces: bool) -> wgpu::BindGroupLayout {
    use wgpu::{SamplerBindingType, ShaderStages, TextureSampleType, TextureViewDimension};
    let texture = match faces {
        false => texture_entry(0, TextureSampleType::Depth, TextureViewDimension::Cube),
        true => texture_entry(3, TextureSampleType::Depth, TextureViewDimension::D2Array),
    };
    let entries = [
        texture,
        sampler_entry(1, SamplerBindingType::Comparison),
        storage_entry(2, ShaderStages::FRAGMENT, false, Some(params_size)),
    ];
    bindings::layout(gpu, "cube shadow map", &entries)
}

/// The matching bind group, with its own parameter buffer holding `params`.
pub fn cube_map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &CubeShadowMap,
    filter: wgpu::FilterMode,
    params: &[u8],
) -> wgpu::BindGroup {
    let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("cube comparison"),
        mag_filter: filter,
        min_filter: filter,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    });
    let buffer = params_buffer(gpu, "cube params", params);
    cube_group(gpu, layout, map, &sampler, &buffer)
}

/// The cube map, its sampler and a parameter buffer as bindings 0, 1, 2
/// (the map's faces as a 2D array at 3 instead of 0, for a faces map).
pub(crate) fn cube_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &CubeShadowMap,
    sampler: &wgpu::Sampler,
    params: &wgpu::Buffer,
) -> wgpu::BindGroup {
    let resources = [
        wgpu::BindingResource::TextureView(&map.cube_view),
        wgpu::BindingResource::Sampler(sampler),
        params.as_entire_binding(),
    ];
    if !map.faces {
        return bindings::group(gpu, "cube shadow map", layout, &resources);
    }
    let entries: Vec<wgpu::BindGroupEntry<'_>> = [3, 1, 2]
        .into_iter()
        .zip(resources)
        .map(|(binding, resource)| wgpu::BindGroupEntry { binding, resource })
        .collect();
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("cube shadow map faces"),
        layout,
        entries: &entries,
    })
}
