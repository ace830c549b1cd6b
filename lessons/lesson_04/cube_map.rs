//! Cube-map shadows for point lights (lesson 04): the light renders six 90°
//! faces ([`super::faces`]) into the six layers of one depth texture; the lit pass samples it
//! through a `Cube` view with the direction from the light.
//!
//! Also here: the two ways to store depth, and the lit pass's parameters.
//! The faces' directions, view-projections and light uniforms are in
//! [`super::faces`], culling in
//! [`super::culling`], the picture of the six faces in [`super::cross`].

use common::gpu::bindings::{self, params_buffer, sampler_entry, storage_entry, texture_entry};
use common::gpu::render::{pipeline_layout_for, vertex_state, SceneGpu};
use common::gpu::targets::depth_texture;
use common::gpu::Gpu;
use common::measure::timing::Frame;

use super::faces::FaceRects;

pub const CUBE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

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
    // ... then the exercise's (the chapter's end).
    // ANCHOR_END: storage
    /// Hardware depth, read without a cube: the face and texel chosen by
    /// the chapter's exercise (`exercise_cube_texel` in `exercises.wgsl`)
    /// in the six layers seen as a 2D array.
    DepthExercise,
}

// ANCHOR: storage_pass
impl Storage {
    /// The shadow pass that fills the cube for this storage.
    pub fn pass(self) -> DepthStorage {
        match self {
            Storage::Linear => DepthStorage::Linear {
                vs_entry: "vs_cube_linear",
                fs_entry: "fs_cube_linear",
            },
            // Every other storage keeps the face's hardware depth.
            _ => DepthStorage::Hardware,
        }
    }
}
// ANCHOR_END: storage_pass

/// The lit pass's parameters (`CubeParams` in `shaders/lesson_04/cube_map.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CubeParams {
    /// The faces' near plane.
    pub near: f32,
    /// 2 / face resolution: a texel's width 1 m from the light.
    pub texel_at_1m: f32,
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
    /// Receivers past the far plane compare at 1.0 (lit) instead of
    /// behind the cleared cube (shadowed).
    pub clamp_range: bool,
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
            ("CLAMP_RANGE", self.clamp_range as u32 as f64),
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

// ANCHOR: cube_shadow_passes
/// Renders light `light`'s six faces, one render pass each, each only over
/// its rectangle in `rects` (the texels a visible receiver can look up:
/// [`super::face_rects`]). `casters(face)` lists the objects to draw into
/// a face; a face with none, or with no rectangle, is skipped (it is
/// cleared once, then left alone). Returns each face's draws.
pub fn cube_shadow_passes(
    frame: &mut Frame,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    map: &mut CubeShadowMap,
    faces: &super::faces::FaceUniforms,
    (light, rects): (usize, &FaceRects),
    casters: impl Fn(usize) -> Vec<usize>,
) -> [u32; 6] {
    let mut drawn = [0; 6];
    for (face, draws) in drawn.iter_mut().enumerate() {
        let list = rects[face].map_or_else(Vec::new, |_| casters(face));
        if list.is_empty() && map.empty[face] {
            continue;
        }
        frame.pass("shadow", |enc, ts| {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("cube face"),
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &map.face_views[face],
                    depth_ops: Some(wgpu::Operations {
                        // The whole face: the scissor does not hold back a clear.
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: ts.render(),
                ..Default::default()
            });
            pass.set_pipeline(pipeline);
            faces.bind(&mut pass, light, face);
            if let Some(r) = rects[face] {
                pass.set_scissor_rect(r.x, r.y, r.w, r.h);
            }
            *draws = scene.draw_objects(&mut pass, |i| list.contains(&i));
        });
        map.empty[face] = list.is_empty();
    }
    drawn
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
