//! Stencil shadow volumes, taught once (lessons 05 and 06) and reused by
//! lessons 07 (depth clamp / infinite extrusion) and 08 (depth bounds).
//!
//! # What a frame does
//!
//! ```text
//! base pass (depth + ambient)              scene.base_pass
//! for each light:
//!     volume pass: clear stencil, draw     ShadowVolumes::volume_pass
//!                  volumes, count in stencil
//!     lit pass where stencil == 0          scene.lit_pass with lit_stencil()
//! ```
//!
//! The volume pass clears the stencil itself (its stencil attachment is
//! `LoadOp::Clear(0)`, depth is loaded): that is the per-light stencil
//! clear, merged into the pass that needs it.
//!
//! # Building the volumes: two methods ([`Extrusion`])
//!
//! WebGPU has no geometry shader, so the silhouette is found either
//!
//! - [`Extrusion::Cpu`]: on the CPU every frame, as Doom 3 did. The light is
//!   moved into object space (inverse model), [`Adjacency::face_facing`]
//!   and [`Adjacency::silhouette_edges_for`] give the sides, and the
//!   light-facing triangles give the caps. Vertices are `(position, w)`:
//!   `w = 1` stays, `w = 0` goes to infinity. Call
//!   [`ShadowVolumes::prepare_cpu`] once per frame, before the passes (it is
//!   timed as `cpu_silhouette`).
//! - [`Extrusion::Quads`]: degenerate quads built once, in advance (one per
//!   manifold edge; one per (edge, face) pair for open and non-manifold
//!   edges, whose other side never faces the light), plus front and back
//!   cap triangles. The vertex shader tests the facing of each vertex's face
//!   and moves it (see `vs_volume_quads` in `shaders/shadow_volume.wgsl`).
//!   No per-frame CPU work.
//!
//! Both give the same volumes: the boundary of the union of the
//! light-facing faces' own volumes, counted with the rule of
//! [`Adjacency::silhouette_edges`] (open edges are silhouettes when their
//! face is lit; a non-manifold edge is the sum of its faces). Open,
//! non-manifold or misoriented meshes cast as two-sided surfaces: their
//! adjacency holds every triangle twice, once reversed
//! ([`caster_adjacency`]), so a quad lit from behind still casts. A mirrored
//! model (det < 0) reverses every winding in world space: such casters are
//! drawn with a pipeline whose front face is `Cw` ([`VolumePipelines::get`]).
//!
//! # Counting: [`Method`]
//!
//! Two-sided stencil with wrapping 8-bit arithmetic, no colour, no depth
//! write, depth test `Less` against the base pass's depth:
//! - `ZPass`: front faces that pass increment, back faces that pass
//!   decrement. Wrong when the eye is inside a volume or the near plane cuts
//!   one (the missing "enter" count).
//! - `ZFail` (Carmack's reverse): back faces that fail increment, front
//!   faces that fail decrement. Needs both caps ([`CasterDraw::front_cap`],
//!   [`CasterDraw::back_cap`]).
//!
//! The lit pass uses [`lit_stencil`]: compare `Equal`, reference 0.
//!
//! # Far plane: [`FarPlane`]
//!
//! Vertices at infinity (w = 0) lie beyond any finite far plane. Lessons 05
//! and 06 use scenes with `far = "infinite"` (the whole frame uses the
//! infinite projection, so the base pass's depths and the volumes agree).
//! [`FarPlane::Clip`] leaves clipping alone; [`FarPlane::Unclipped`] sets
//! `unclipped_depth` (needs `DEPTH_CLIP_CONTROL`; [`VolumePipelines::new`]
//! fails with one line naming it otherwise). Lesson 07 chooses.
//!
//! # Leaving out work: [`ShadowVolumes::plan`]
//!
//! Per light and caster: skip a caster whose volume cannot reach the view
//! frustum; use z-fail (with caps) only where the caster can shadow the
//! near-plane rectangle (the occlusion pyramid of the 2005 article), else
//! z-pass without caps. The counts, and so the pixels, are the same as
//! z-fail everywhere.
//!
//! # Counters
//!
//! [`FragmentCounter`] counts the fragments the volume geometry rasterises
//! (pipeline statistics: fragment-shader invocations of an untimed copy of
//! the volume pass with the depth test off and a one-value fragment
//! shader), when the adapter has `PIPELINE_STATISTICS_QUERY` (lavapipe does,
//! GL does not: the key is then omitted). [`max_volume_overlap`] samples the
//! stencil count on the CPU to detect 8-bit wrap (256 nested volumes).
//!
//! # Reuse from another lesson
//!
//! `ShadowVolumes::new` builds everything with `shaders/shadow_volume.wgsl`.
//! To change the vertex shader or add bind groups (group 2 on), compile a
//! module with [`volume_shader_module`] and build [`VolumePipelines`] with
//! [`VolumePipelines::with_entry`], then draw with
//! [`ShadowVolumes::draw_casters`] inside your own pass.

use std::ops::Range;

use anyhow::{bail, Result};
use glam::{DMat4, DVec3, DVec4, Mat4, Vec3};

use crate::adjacency::{Adjacency, LightDir};
use crate::bvh::Bvh;
use crate::gpu::Gpu;
use crate::render::{pipeline_layout_for, shader_module, FrameTargets, SceneGpu};
use crate::scene::LightKind;
use crate::timing::Frame;

/// The shared volume WGSL (appended after `common.wgsl`).
pub const SHADOW_VOLUME_WGSL: &str = include_str!("../../shaders/shadow_volume.wgsl");

/// `common.wgsl` + `shadow_volume.wgsl` + a lesson's own WGSL.
pub fn volume_shader_module(gpu: &Gpu, label: &str, extra_wgsl: &str) -> wgpu::ShaderModule {
    shader_module(gpu, label, &format!("{SHADOW_VOLUME_WGSL}\n{extra_wgsl}"))
}

/// How the stencil counts volume faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    ZPass,
    ZFail,
}

/// How the volume geometry is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extrusion {
    /// Silhouettes on the CPU every frame (Doom 3).
    Cpu,
    /// Degenerate quads built in advance, extruded in the vertex shader.
    Quads,
}

/// What happens to volume geometry beyond the far plane.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FarPlane {
    /// Ordinary clipping (fine with `far = "infinite"`).
    #[default]
    Clip,
    /// `unclipped_depth`: depth clamped instead of clipped (DEPTH_CLIP_CONTROL).
    Unclipped,
}

/// One caster's volume in one light's volume pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CasterDraw {
    /// Index into `scene.objects`.
    pub object: usize,
    pub method: Method,
    pub front_cap: bool,
    pub back_cap: bool,
}

impl CasterDraw {
    /// Sides only, z-pass.
    pub fn zpass(object: usize) -> CasterDraw {
        CasterDraw {
            object,
            method: Method::ZPass,
            front_cap: false,
            back_cap: false,
        }
    }
    /// Sides and both caps, z-fail.
    pub fn zfail(object: usize) -> CasterDraw {
        CasterDraw {
            object,
            method: Method::ZFail,
            front_cap: true,
            back_cap: true,
        }
    }
}

/// What [`ShadowVolumes::plan`] leaves out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PlanStats {
    pub zpass: u32,
    pub zfail: u32,
    pub skipped: u32,
}

// ANCHOR: stencil_states
/// Two-sided stencil for the volume pass. Wrapping arithmetic, so that the
/// order in which faces arrive does not matter: +1 − 1 is 0 even from 0.
pub fn volume_stencil(method: Method) -> wgpu::StencilState {
    use wgpu::StencilOperation::{DecrementWrap, IncrementWrap, Keep};
    let face = |pass_op, depth_fail_op| wgpu::StencilFaceState {
        compare: wgpu::CompareFunction::Always,
        fail_op: Keep,
        depth_fail_op,
        pass_op,
    };
    let (front, back) = match method {
        // Counted in front of the surface: entering +1, leaving −1.
        Method::ZPass => (face(IncrementWrap, Keep), face(DecrementWrap, Keep)),
        // Counted behind the surface: leaving (back face) +1, entering −1.
        Method::ZFail => (face(Keep, DecrementWrap), face(Keep, IncrementWrap)),
    };
    wgpu::StencilState {
        front,
        back,
        read_mask: 0xff,
        write_mask: 0xff,
    }
}

/// The lit pass adds the light only where the count is 0.
pub fn lit_stencil() -> wgpu::StencilState {
    let face = wgpu::StencilFaceState {
        compare: wgpu::CompareFunction::Equal,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op: wgpu::StencilOperation::Keep,
        pass_op: wgpu::StencilOperation::Keep,
    };
    wgpu::StencilState {
        front: face,
        back: face,
        read_mask: 0xff,
        write_mask: 0,
    }
}
// ANCHOR_END: stencil_states

/// CPU-path vertex: object-space position and w (1 stays, 0 to infinity).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CpuVertex {
    pub position: [f32; 3],
    pub w: f32,
}

pub const CPU_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<CpuVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32],
};

/// Pre-built quad/cap vertex: position, kind (0 edge, 1 front cap, 2 back
/// cap), and its face's unnormalised normal and first vertex.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct QuadVertex {
    pub position: [f32; 3],
    pub kind: u32,
    pub face_normal: [f32; 3],
    pub face_point: [f32; 3],
}

pub const QUAD_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<QuadVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Uint32, 2 => Float32x3, 3 => Float32x3],
};

/// Vertex ranges of one caster's volume: sides, front cap, back cap.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VolumeRanges {
    pub sides: Range<u32>,
    pub front: Range<u32>,
    pub back: Range<u32>,
}

impl VolumeRanges {
    /// The ranges `d` draws, each with "is it a cap?".
    fn for_draw(&self, d: &CasterDraw) -> impl Iterator<Item = (Range<u32>, bool)> {
        [
            Some((self.sides.clone(), false)),
            d.front_cap.then(|| (self.front.clone(), true)),
            d.back_cap.then(|| (self.back.clone(), true)),
        ]
        .into_iter()
        .flatten()
        .filter(|(r, _)| !r.is_empty())
    }
}

// ANCHOR: cpu_volume
/// The CPU path: one caster's volume for one light (object space), appended
/// to `out`. Sides from the silhouette; caps from the light-facing faces.
pub fn cpu_volume(adj: &Adjacency, light: LightDir, out: &mut Vec<CpuVertex>) -> VolumeRanges {
    let facing = adj.face_facing(light);
    let v = |i: u32, w: f32| CpuVertex {
        position: adj.positions[i as usize].to_array(),
        w,
    };
    let directional = matches!(light, LightDir::Directional(_));
    let start = out.len() as u32;
    for e in adj.silhouette_edges_for(&facing) {
        // The lit face runs a → b; its side of the volume, seen from
        // outside, runs b → a → a∞ → b∞ (counter-clockwise, like the caps).
        out.extend([v(e.a, 1.0), v(e.b, 0.0), v(e.b, 1.0)]);
        if !directional {
            // Directional: a∞ = b∞, the second triangle would have no area.
            out.extend([v(e.a, 1.0), v(e.a, 0.0), v(e.b, 0.0)]);
        }
    }
    let sides_end = out.len() as u32;
    let lit = adj.light_facing_triangles_for(&facing);
    for t in &lit {
        out.extend(t.map(|i| v(i, 1.0)));
    }
    let front_end = out.len() as u32;
    if !directional {
        // The back cap: the same triangles at infinity, reversed.
        for t in &lit {
            out.extend([v(t[0], 0.0), v(t[2], 0.0), v(t[1], 0.0)]);
        }
    }
    VolumeRanges {
        sides: start..sides_end,
        front: sides_end..front_end,
        back: front_end..out.len() as u32,
    }
}
// ANCHOR_END: cpu_volume

// ANCHOR: degenerate_quads
/// The quads path, built once: one degenerate quad per manifold edge whose
/// two faces run along it in opposite directions; one quad per (edge, face)
/// for every other edge (open, non-manifold, misoriented), with a far side
/// that never faces the light. Then front and back cap triangles for every
/// face. Returns (vertices, indices, index ranges).
pub fn degenerate_quads(adj: &Adjacency) -> (Vec<QuadVertex>, Vec<u32>, VolumeRanges) {
    let mut verts: Vec<QuadVertex> = Vec::new();
    let mut idx: Vec<u32> = Vec::new();
    let face_data = |f: Option<u32>| match f {
        Some(f) => {
            let t = adj.triangles[f as usize];
            (
                adj.face_normals[f as usize].to_array(),
                adj.positions[t[0] as usize].to_array(),
            )
        }
        None => ([0.0; 3], [0.0; 3]), // never faces the light: always extruded
    };
    let vertex = |i: u32, kind: u32, f: Option<u32>| {
        let (n, p0) = face_data(f);
        QuadVertex {
            position: adj.positions[i as usize].to_array(),
            kind,
            face_normal: n,
            face_point: p0,
        }
    };
    let mut quad = |a: u32, b: u32, near: Option<u32>, far: Option<u32>| {
        // a, b belong to the face running a → b; b', a' to the other side.
        let base = verts.len() as u32;
        verts.extend([
            vertex(a, 0, near),
            vertex(b, 0, near),
            vertex(b, 0, far),
            vertex(a, 0, far),
        ]);
        // Wound b → a → a∞ → b∞ when the near face is lit: outward.
        idx.extend([base, base + 2, base + 1, base, base + 3, base + 2]);
    };
    for e in &adj.edges {
        let faces = adj.faces_of(e);
        let [v0, v1] = e.v;
        match faces {
            [f, g] if f.forward != g.forward => {
                let (fwd, bwd) = if f.forward { (f, g) } else { (g, f) };
                quad(v0, v1, Some(fwd.face), Some(bwd.face));
            }
            _ => {
                for f in faces {
                    let (a, b) = if f.forward { (v0, v1) } else { (v1, v0) };
                    quad(a, b, Some(f.face), None);
                }
            }
        }
    }
    let sides = 0..idx.len() as u32;
    for kind in [1u32, 2] {
        for (f, t) in adj.triangles.iter().enumerate() {
            let base = verts.len() as u32;
            verts.extend(t.map(|i| vertex(i, kind, Some(f as u32))));
            // The back cap winds the other way (it faces away from the light).
            idx.extend(if kind == 1 {
                [base, base + 1, base + 2]
            } else {
                [base, base + 2, base + 1]
            });
        }
    }
    let n = adj.triangles.len() as u32 * 3;
    let ranges = VolumeRanges {
        sides: sides.clone(),
        front: sides.end..sides.end + n,
        back: sides.end + n..sides.end + 2 * n,
    };
    (verts, idx, ranges)
}
// ANCHOR_END: degenerate_quads

/// The volume pipelines of one vertex layout: `[method][mirrored][cap]`,
/// plus the fragment-counting pipeline.
pub struct VolumePipelines {
    pipelines: [[[wgpu::RenderPipeline; 2]; 2]; 2],
    count: wgpu::RenderPipeline,
}

// ANCHOR: cap_bias
/// Caps are drawn pushed back by a hair. The front cap lies exactly on the
/// caster's lit faces, and z-fail needs it to *fail* there (equal depth
/// counts as behind). That holds only if the volume shader reproduces the
/// base pass's depth to the bit, which GL drivers do not promise across
/// programs: llvmpipe GL let a grazing front cap pass in stripes.
pub const CAP_DEPTH_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: 4,
    slope_scale: 2.0,
    clamp: 0.0,
};
// ANCHOR_END: cap_bias

impl VolumePipelines {
    /// The shared shader's entry for `extrusion`.
    pub fn new(
        gpu: &Gpu,
        scene: &SceneGpu,
        extrusion: Extrusion,
        far: FarPlane,
    ) -> Result<VolumePipelines> {
        let module = volume_shader_module(gpu, "shadow volume", "");
        let (entry, layout) = match extrusion {
            Extrusion::Cpu => ("vs_volume_cpu", CPU_VERTEX_LAYOUT),
            Extrusion::Quads => ("vs_volume_quads", QUAD_VERTEX_LAYOUT),
        };
        VolumePipelines::with_entry(gpu, scene, &module, entry, layout, &[], far)
    }

    /// Pipelines from any module and vertex entry (lessons 07 and 08).
    /// `module` must contain `fs_volume_count` (it does when made by
    /// [`volume_shader_module`]). `extra` layouts start at group 2.
    pub fn with_entry(
        gpu: &Gpu,
        scene: &SceneGpu,
        module: &wgpu::ShaderModule,
        vs_entry: &str,
        vertex_layout: wgpu::VertexBufferLayout<'static>,
        extra: &[&wgpu::BindGroupLayout],
        far: FarPlane,
    ) -> Result<VolumePipelines> {
        if far == FarPlane::Unclipped && !gpu.has(wgpu::Features::DEPTH_CLIP_CONTROL) {
            bail!(
                "FarPlane::Unclipped needs the DEPTH_CLIP_CONTROL feature, which {} does not have",
                gpu.adapter_name()
            );
        }
        let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, extra);
        let buffers = [Some(vertex_layout)];
        let make = |method: Option<Method>, front_face: wgpu::FrontFace, cap: bool| {
            let primitive = wgpu::PrimitiveState {
                front_face,
                // Both sides of the volume count: one increments, one decrements.
                cull_mode: None,
                unclipped_depth: far == FarPlane::Unclipped,
                ..Default::default()
            };
            let vertex = wgpu::VertexState {
                module,
                entry_point: Some(vs_entry),
                compilation_options: Default::default(),
                buffers: &buffers,
            };
            let targets = [Some(wgpu::TextureFormat::R8Unorm.into())];
            let (depth_stencil, fragment) = match method {
                // No colour, no depth write: the stencil is the only output.
                Some(m) => (
                    Some(wgpu::DepthStencilState {
                        format: scene.depth_format,
                        depth_write_enabled: Some(false),
                        depth_compare: Some(wgpu::CompareFunction::Less),
                        stencil: volume_stencil(m),
                        bias: if cap {
                            CAP_DEPTH_BIAS
                        } else {
                            Default::default()
                        },
                    }),
                    None,
                ),
                // Counting copy: no depth test, a fragment shader to count.
                None => (
                    None,
                    Some(wgpu::FragmentState {
                        module,
                        entry_point: Some("fs_volume_count"),
                        compilation_options: Default::default(),
                        targets: &targets,
                    }),
                ),
            };
            gpu.device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("shadow volume"),
                    layout: Some(&layout),
                    vertex,
                    primitive,
                    depth_stencil,
                    multisample: Default::default(),
                    fragment,
                    multiview_mask: None,
                    cache: None,
                })
        };
        let caps = |m, f| [make(Some(m), f, false), make(Some(m), f, true)];
        let pair = |m| [caps(m, wgpu::FrontFace::Ccw), caps(m, wgpu::FrontFace::Cw)];
        Ok(VolumePipelines {
            pipelines: [pair(Method::ZPass), pair(Method::ZFail)],
            count: make(None, wgpu::FrontFace::Ccw, false),
        })
    }

    /// The pipeline for `method`; `mirrored` casters (det < 0) wind the
    /// other way in world space, so their front face is `Cw`.
    pub fn get(&self, method: Method, mirrored: bool) -> &wgpu::RenderPipeline {
        &self.pipelines[(method == Method::ZFail) as usize][mirrored as usize][0]
    }

    /// The same for caps, drawn with [`CAP_DEPTH_BIAS`].
    pub fn get_cap(&self, method: Method, mirrored: bool) -> &wgpu::RenderPipeline {
        &self.pipelines[(method == Method::ZFail) as usize][mirrored as usize][1]
    }
}

/// One shadow caster: its welded adjacency and its pre-built quads.
pub struct VolumeCaster {
    /// Index into `scene.objects`.
    pub object: usize,
    pub adjacency: Adjacency,
    /// det(model) < 0: windings flip in world space.
    pub mirrored: bool,
    /// Origin-relative bounding sphere.
    pub center: DVec3,
    pub radius: f64,
    quad_vertices: wgpu::Buffer,
    quad_indices: wgpu::Buffer,
    pub quad_ranges: VolumeRanges,
}

impl VolumeCaster {
    /// The pre-built quads' vertex and index buffers (cheap handles), and
    /// the index count of the whole volume: sides, front cap and back cap.
    pub fn quad_buffers(&self) -> (wgpu::Buffer, wgpu::Buffer, u32) {
        let r = &self.quad_ranges;
        let count = r.sides.end.max(r.front.end).max(r.back.end);
        (self.quad_vertices.clone(), self.quad_indices.clone(), count)
    }
}

/// The per-frame CPU geometry: one buffer for every light, so the writes of
/// light 0 and light 1 do not overwrite each other before the submit.
#[derive(Default)]
struct CpuGeometry {
    buffer: Option<wgpu::Buffer>,
    /// `ranges[light][caster]`.
    ranges: Vec<Vec<VolumeRanges>>,
    vertices: Vec<CpuVertex>,
}

/// Every caster's volume data and the pipelines of both extrusion methods.
pub struct ShadowVolumes {
    pub casters: Vec<VolumeCaster>,
    cpu: CpuGeometry,
    cpu_pipelines: VolumePipelines,
    quad_pipelines: VolumePipelines,
    counter: Option<FragmentCounter>,
}

impl ShadowVolumes {
    pub fn new(gpu: &Gpu, scene: &SceneGpu, far: FarPlane) -> Result<ShadowVolumes> {
        use wgpu::util::DeviceExt;
        let mut casters = Vec::new();
        for (i, o) in scene.scene.objects.iter().enumerate() {
            if !o.casts_shadow {
                continue;
            }
            let adjacency = caster_adjacency(&o.mesh);
            let model = scene.scene.model_relative(i);
            let world: Vec<DVec3> = adjacency
                .positions
                .iter()
                .map(|p| model.as_dmat4().transform_point3(p.as_dvec3()))
                .collect();
            let (lo, hi) = world
                .iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), p| {
                    (a.min(*p), b.max(*p))
                });
            let center = (lo + hi) * 0.5;
            let radius =
                world.iter().map(|p| p.distance(center)).fold(0.0, f64::max) * (1.0 + 1e-6) + 1e-6;
            let (verts, idx, quad_ranges) = degenerate_quads(&adjacency);
            let buf = |label: &str, contents: &[u8], usage| {
                gpu.device
                    .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(label),
                        contents,
                        usage,
                    })
            };
            // wgpu rejects empty buffers: a caster with no edges gets one dummy.
            let verts = if verts.is_empty() {
                vec![QuadVertex::zeroed_vertex()]
            } else {
                verts
            };
            let idx_bytes: Vec<u32> = if idx.is_empty() { vec![0] } else { idx };
            casters.push(VolumeCaster {
                object: i,
                mirrored: model.determinant() < 0.0,
                center,
                radius,
                quad_vertices: buf(
                    "volume quads",
                    bytemuck::cast_slice(&verts),
                    wgpu::BufferUsages::VERTEX,
                ),
                quad_indices: buf(
                    "volume quad indices",
                    bytemuck::cast_slice(&idx_bytes),
                    wgpu::BufferUsages::INDEX,
                ),
                quad_ranges,
                adjacency,
            });
        }
        Ok(ShadowVolumes {
            casters,
            cpu: CpuGeometry::default(),
            cpu_pipelines: VolumePipelines::new(gpu, scene, Extrusion::Cpu, far)?,
            quad_pipelines: VolumePipelines::new(gpu, scene, Extrusion::Quads, far)?,
            counter: FragmentCounter::new(gpu, scene.width, scene.height),
        })
    }

    /// Every caster with one method (z-fail draws both caps).
    pub fn all(&self, method: Method) -> Vec<CasterDraw> {
        self.casters
            .iter()
            .map(|c| match method {
                Method::ZPass => CasterDraw::zpass(c.object),
                Method::ZFail => CasterDraw::zfail(c.object),
            })
            .collect()
    }

    fn caster(&self, object: usize) -> Option<(usize, &VolumeCaster)> {
        self.casters
            .iter()
            .enumerate()
            .find(|(_, c)| c.object == object)
    }

    // ANCHOR: prepare_cpu
    /// The CPU path's per-frame work: silhouettes and caps for every light
    /// and the casters in `draws[light]`, uploaded in one write. Timed as
    /// `cpu_silhouette`.
    pub fn prepare_cpu(&mut self, frame: &mut Frame, scene: &SceneGpu, draws: &[Vec<CasterDraw>]) {
        let gpu = frame.gpu;
        let cpu = &mut self.cpu;
        let casters = &self.casters;
        frame.cpu("silhouette", || {
            cpu.vertices.clear();
            cpu.ranges.clear();
            for (k, draws_k) in draws.iter().enumerate() {
                let light = world_light(scene, k);
                let mut ranges = vec![VolumeRanges::default(); casters.len()];
                for (ci, c) in casters.iter().enumerate() {
                    if !draws_k.iter().any(|d| d.object == c.object) {
                        continue;
                    }
                    // Silhouettes in object space: the light moves, not the mesh.
                    let model = scene.scene.model_relative(c.object);
                    ranges[ci] = cpu_volume(
                        &c.adjacency,
                        light.to_object_space(model),
                        &mut cpu.vertices,
                    );
                }
                cpu.ranges.push(ranges);
            }
            let bytes = (cpu.vertices.len().max(1) * std::mem::size_of::<CpuVertex>()) as u64;
            if cpu.buffer.as_ref().is_none_or(|b| b.size() < bytes) {
                cpu.buffer = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("cpu shadow volumes"),
                    size: bytes.next_power_of_two(),
                    usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }));
            }
            if let Some(b) = &cpu.buffer {
                gpu.queue
                    .write_buffer(b, 0, bytemuck::cast_slice(&cpu.vertices));
            }
        });
    }
    // ANCHOR_END: prepare_cpu

    /// Number of CPU-path volume vertices of the last `prepare_cpu`.
    pub fn cpu_vertex_count(&self) -> usize {
        self.cpu.vertices.len()
    }

    /// Draws `draws` for light `light` into an open pass, with the volume
    /// pipelines of `extrusion` (or `pipelines`, when given: lessons 07/08).
    /// Returns the number of casters drawn.
    #[allow(clippy::too_many_arguments)]
    pub fn draw_casters(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        scene: &SceneGpu,
        light: usize,
        extrusion: Extrusion,
        draws: &[CasterDraw],
        pipelines: Option<&VolumePipelines>,
        counting: bool,
    ) -> u32 {
        let pipes = pipelines.unwrap_or(match extrusion {
            Extrusion::Cpu => &self.cpu_pipelines,
            Extrusion::Quads => &self.quad_pipelines,
        });
        scene.bind_frame(pass, light);
        let mut drawn = 0;
        for d in draws {
            let Some((ci, c)) = self.caster(d.object) else {
                continue;
            };
            let pipeline = |cap: bool| match (counting, cap) {
                (true, _) => &pipes.count,
                (false, false) => pipes.get(d.method, c.mirrored),
                (false, true) => pipes.get_cap(d.method, c.mirrored),
            };
            scene.bind_object(pass, c.object);
            match extrusion {
                Extrusion::Cpu => {
                    let (Some(buf), Some(r)) = (
                        &self.cpu.buffer,
                        self.cpu.ranges.get(light).and_then(|r| r.get(ci)),
                    ) else {
                        continue;
                    };
                    pass.set_vertex_buffer(0, buf.slice(..));
                    for (range, cap) in r.for_draw(d) {
                        pass.set_pipeline(pipeline(cap));
                        pass.draw(range, 0..1);
                    }
                }
                Extrusion::Quads => {
                    pass.set_vertex_buffer(0, c.quad_vertices.slice(..));
                    pass.set_index_buffer(c.quad_indices.slice(..), wgpu::IndexFormat::Uint32);
                    for (range, cap) in c.quad_ranges.for_draw(d) {
                        pass.set_pipeline(pipeline(cap));
                        pass.draw_indexed(range, 0, 0..1);
                    }
                }
            }
            drawn += 1;
        }
        drawn
    }

    // ANCHOR: volume_pass
    /// One light's volume pass: clears the stencil (depth is loaded from the
    /// base pass) and counts the volumes of `draws` into it.
    #[allow(clippy::too_many_arguments)]
    pub fn volume_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &SceneGpu,
        targets: &FrameTargets,
        light: usize,
        extrusion: Extrusion,
        draws: &[CasterDraw],
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) -> u32 {
        let mut pass = targets.stencil_pass(encoder, "volume pass", ts, None);
        self.draw_casters(&mut pass, scene, light, extrusion, draws, None, false)
    }
    // ANCHOR_END: volume_pass

    /// Fragments rasterised by the volumes of `draws[light]` for every light
    /// (see [`FragmentCounter`]); `None` without PIPELINE_STATISTICS_QUERY.
    /// Call after `prepare_cpu` for the CPU path. Untimed: its own submit.
    pub fn count_fragments(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        extrusion: Extrusion,
        draws: &[Vec<CasterDraw>],
    ) -> Option<u64> {
        let counter = self.counter.as_ref()?;
        counter
            .count(gpu, |pass| {
                for (k, d) in draws.iter().enumerate() {
                    self.draw_casters(pass, scene, k, extrusion, d, None, true);
                }
            })
            .ok()
    }

    /// Lessons 07/08: count with their own pipelines' counting copy.
    pub fn counter(&self) -> Option<&FragmentCounter> {
        self.counter.as_ref()
    }

    /// Which casters need z-fail, which z-pass, and which can be skipped,
    /// for light `light` (see the module doc). The counts are the same as
    /// with z-fail everywhere.
    pub fn plan(&self, scene: &SceneGpu, light: usize) -> (Vec<CasterDraw>, PlanStats) {
        let view_proj = scene.camera.view_proj.as_dmat4();
        let frustum = frustum_planes(view_proj);
        let near_rect = near_rectangle(view_proj);
        let l = world_light(scene, light);
        let (l_point, l_dir) = match l {
            LightDir::Point(p) => (Some(p.as_dvec3()), None),
            LightDir::Directional(d) => (None, Some(d.as_dvec3())),
        };
        let pyramid = occlusion_pyramid(&near_rect, l_point, l_dir);
        let mut stats = PlanStats::default();
        let mut out = Vec::new();
        for c in &self.casters {
            let outside = |(n, d): &(DVec3, f64)| {
                let s = n.dot(c.center) + d;
                if s + c.radius >= 0.0 {
                    return false;
                }
                // The extrusion must also move away from the plane.
                match (l_point, l_dir) {
                    (Some(p), _) => s + c.radius <= n.dot(p) + d,
                    (_, Some(dir)) => n.dot(dir) <= 0.0,
                    _ => false,
                }
            };
            if frustum.iter().any(outside) {
                stats.skipped += 1;
                continue;
            }
            let reaches_near = match &pyramid {
                Some(planes) => !planes.iter().any(|(n, d)| n.dot(c.center) + d < -c.radius),
                None => true, // degenerate pyramid: be safe
            };
            if reaches_near {
                stats.zfail += 1;
                out.push(CasterDraw::zfail(c.object));
            } else {
                stats.zpass += 1;
                out.push(CasterDraw::zpass(c.object));
            }
        }
        (out, stats)
    }
}

// ANCHOR: caster_adjacency
/// The adjacency a caster's volumes are built from. A closed, consistently
/// wound mesh casts from its light-facing faces only. An open (or
/// non-manifold, or misoriented) mesh is a two-sided surface: a single quad
/// lit from behind must cast too. It gets each triangle twice, once
/// reversed, so that for any light one copy of every face faces it.
pub fn caster_adjacency(mesh: &crate::mesh::Mesh) -> Adjacency {
    if casts_two_sided(mesh) {
        let reversed = mesh
            .indices
            .chunks_exact(3)
            .flat_map(|t| [t[0], t[2], t[1]]);
        let indices: Vec<u32> = mesh.indices.iter().copied().chain(reversed).collect();
        Adjacency::from_triangles(&mesh.positions, &indices)
    } else {
        Adjacency::new(mesh)
    }
}

/// Does this mesh cast as a two-sided surface (see [`caster_adjacency`])?
pub fn casts_two_sided(mesh: &crate::mesh::Mesh) -> bool {
    let v = crate::mesh::validate(mesh);
    !(v.closed && v.misoriented_edges == 0)
}
// ANCHOR_END: caster_adjacency

impl QuadVertex {
    fn zeroed_vertex() -> QuadVertex {
        bytemuck::Zeroable::zeroed()
    }
}

/// Light `k` as the volumes see it: origin-relative world space. Spot
/// lights cast like point lights (the cone is applied in the lit pass).
pub fn world_light(scene: &SceneGpu, k: usize) -> LightDir {
    let o = scene.scene.origin();
    match scene.scene.lights[k].kind {
        LightKind::Directional { direction } => LightDir::Directional(direction.as_vec3()),
        LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
            LightDir::Point((position - o).as_vec3())
        }
    }
}

/// Planes `(n, d)` with n·p + d ≥ 0 inside, from a WebGPU view-projection
/// (depth in [0, 1]). A far plane at infinity is left out.
pub fn frustum_planes(vp: DMat4) -> Vec<(DVec3, f64)> {
    let r = |i: usize| vp.row(i);
    let candidates = [
        r(3) + r(0),
        r(3) - r(0),
        r(3) + r(1),
        r(3) - r(1),
        r(2),
        r(3) - r(2),
    ];
    candidates
        .iter()
        .filter_map(|p: &DVec4| {
            let len = p.truncate().length();
            (len > 1e-9 * p.length().max(1.0)).then(|| (p.truncate() / len, p.w / len))
        })
        .collect()
}

/// The four world corners of the near-plane rectangle.
pub fn near_rectangle(vp: DMat4) -> [DVec3; 4] {
    let inv = vp.inverse();
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| inv.project_point3(DVec3::new(x, y, 0.0)))
}

// ANCHOR: occlusion_pyramid
/// The region whose casters can shadow the near-plane rectangle: the
/// pyramid from a point light to the rectangle, or the rectangle swept
/// towards a directional light. Planes face inward; `None` when the region
/// is degenerate (light on the near plane, or travelling along it).
pub fn occlusion_pyramid(
    rect: &[DVec3; 4],
    point: Option<DVec3>,
    dir: Option<DVec3>,
) -> Option<Vec<(DVec3, f64)>> {
    let centre = rect.iter().sum::<DVec3>() / 4.0;
    let near_n = (rect[1] - rect[0]).cross(rect[3] - rect[0]).normalize();
    let (towards_light, interior) = match (point, dir) {
        (Some(l), _) => (l - centre, (l + centre) * 0.5),
        (_, Some(d)) => (-d, centre - d),
        _ => return None,
    };
    let size = (rect[2] - rect[0]).length();
    if near_n.dot(towards_light).abs() < 1e-9 * size.max(towards_light.length()) {
        return None;
    }
    let mut planes = Vec::new();
    let mut add = |n: DVec3, p: DVec3| {
        let n = n.normalize();
        let (n, d) = (n, -n.dot(p));
        // Orient towards the interior point.
        if n.dot(interior) + d < 0.0 {
            planes.push((-n, -d));
        } else {
            planes.push((n, d));
        }
    };
    add(near_n, centre);
    for i in 0..4 {
        let (a, b) = (rect[i], rect[(i + 1) % 4]);
        let side = match (point, dir) {
            (Some(l), _) => (a - l).cross(b - l),
            (_, Some(d)) => (b - a).cross(d),
            _ => unreachable!(),
        };
        add(side, a);
    }
    if planes.iter().any(|(n, _)| !n.is_finite()) {
        return None;
    }
    Some(planes)
}
// ANCHOR_END: occlusion_pyramid

/// Counts the fragments a set of draws rasterises, with a pipeline
/// statistics query (FRAGMENT_SHADER_INVOCATIONS) around a pass that has no
/// depth test and a throw-away R8 target. `None` from [`FragmentCounter::new`]
/// when the adapter lacks PIPELINE_STATISTICS_QUERY (GL): omit the key then.
pub struct FragmentCounter {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    target: wgpu::TextureView,
}

impl FragmentCounter {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Option<FragmentCounter> {
        if !gpu.has(wgpu::Features::PIPELINE_STATISTICS_QUERY) {
            return None;
        }
        let set = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("volume fragments"),
            ty: wgpu::QueryType::PipelineStatistics(
                wgpu::PipelineStatisticsTypes::FRAGMENT_SHADER_INVOCATIONS,
            ),
            count: 1,
        });
        let buffer = |usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("volume fragments"),
                size: 8,
                usage,
                mapped_at_creation: false,
            })
        };
        let resolve = buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC);
        let read = buffer(wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST);
        let tex = crate::render::render_texture(
            gpu,
            "fragment count target",
            width,
            height,
            wgpu::TextureFormat::R8Unorm,
            wgpu::TextureUsages::empty(),
        );
        Some(FragmentCounter {
            set,
            resolve,
            read,
            target: tex.create_view(&Default::default()),
        })
    }

    /// Records `draw` (which must set counting pipelines: no depth-stencil,
    /// one R8Unorm target) in its own pass and submit; returns the count.
    pub fn count(&self, gpu: &Gpu, draw: impl FnOnce(&mut wgpu::RenderPass<'_>)) -> Result<u64> {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("count volume fragments"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Discard,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.begin_pipeline_statistics_query(&self.set, 0);
            draw(&mut pass);
            pass.end_pipeline_statistics_query();
        }
        enc.resolve_query_set(&self.set, 0..1, &self.resolve, 0);
        enc.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 8);
        gpu.queue.submit([enc.finish()]);
        let slice = self.read.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        gpu.wait()?;
        let n = {
            let view = slice
                .get_mapped_range()
                .map_err(|e| anyhow::anyhow!("fragment count readback: {e}"))?;
            bytemuck::pod_read_unaligned::<u64>(&view[..8])
        };
        self.read.unmap();
        Ok(n)
    }
}

// ANCHOR: max_volume_overlap
/// The largest stencil count on a `cols × rows` grid of pixels, counted on
/// the CPU: for each sampled visible point, the number of light-facing
/// caster faces between it and the light (each one is a volume the point
/// is inside). A count of 256 or more wraps the 8-bit stencil to 0 and
/// shows as false light.
pub fn max_volume_overlap(scene: &SceneGpu, light: usize, cols: u32, rows: u32) -> u32 {
    let tris = scene.scene.world_triangles();
    let bvh = Bvh::build(tris.iter().map(|(t, _)| *t).collect());
    let l = world_light(scene, light);
    // Light-facing triangles of the casters, in world space.
    let mut lit: Vec<[Vec3; 3]> = Vec::new();
    let two_sided: Vec<bool> = scene
        .scene
        .objects
        .iter()
        .map(|o| casts_two_sided(&o.mesh))
        .collect();
    for (t, o) in &tris {
        if !scene.scene.objects[*o as usize].casts_shadow {
            continue;
        }
        let n = crate::mesh::face_normal(t[0], t[1], t[2]);
        let towards = match l {
            LightDir::Point(p) => n.dot(p - t[0]),
            LightDir::Directional(d) => n.dot(-d),
        };
        // A two-sided caster has one facing copy of every (non edge-on) face.
        if towards > 0.0 || (two_sided[*o as usize] && towards < 0.0) {
            lit.push(*t);
        }
    }
    let inv = scene.camera.view_proj.as_dmat4().inverse();
    let (w, h) = (scene.width, scene.height);
    let mut best = 0;
    for r in 0..rows {
        for c in 0..cols {
            let (i, j) = ((c * w + w / 2) / cols, (r * h + h / 2) / rows);
            let (o, d) = crate::reference::primary_ray(inv, i, j, w, h);
            let Some(hit) = bvh.closest_hit(o, d, f32::INFINITY) else {
                continue;
            };
            let p = o + d * hit.t;
            let (to, t_max) = match l {
                LightDir::Point(lp) => ((lp - p).normalize(), (lp - p).length()),
                LightDir::Directional(dir) => (-dir.normalize(), f32::INFINITY),
            };
            let count = lit
                .iter()
                .filter(|t| segment_crosses(p, to, t_max, t))
                .count() as u32;
            best = best.max(count);
        }
    }
    best
}
// ANCHOR_END: max_volume_overlap

/// Möller–Trumbore, a small offset away from the start point.
fn segment_crosses(o: Vec3, d: Vec3, t_max: f32, t: &[Vec3; 3]) -> bool {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return false;
    }
    let s = o - t[0];
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    let dist = e2.dot(q) / det;
    (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && dist > 1e-4 && dist < t_max
}

/// `Mat4` helper for tests and lessons: is this model mirrored?
pub fn is_mirrored(model: Mat4) -> bool {
    model.determinant() < 0.0
}

/// The lit pass of a stencil technique: `fs_stencil_lit` where the count is 0.
pub fn stencil_lit_pipeline(gpu: &Gpu, scene: &SceneGpu) -> wgpu::RenderPipeline {
    let module = volume_shader_module(gpu, "stencil lit pass", "");
    scene.lit_pipeline(gpu, &module, "fs_stencil_lit", &[], lit_stencil())
}

/// Report counters about the casters, computed once: mesh validation
/// (`open_edges`, `nonmanifold_edges`, `degenerate_triangles`, summed over
/// casters) and `max_volume_overlap` (the largest stencil count found on a
/// 64 × 36 pixel grid, over all lights). Warns on stderr when the 8-bit
/// stencil wraps (256 or more).
pub fn scene_counters(scene: &SceneGpu) -> std::collections::BTreeMap<String, u64> {
    let mut c = std::collections::BTreeMap::new();
    for o in scene.scene.objects.iter().filter(|o| o.casts_shadow) {
        let v = crate::mesh::validate(&o.mesh);
        *c.entry("open_edges".to_string()).or_default() += v.boundary_edges as u64;
        *c.entry("nonmanifold_edges".to_string()).or_default() += v.nonmanifold_edges as u64;
        *c.entry("degenerate_triangles".to_string()).or_default() += v.degenerate_triangles as u64;
    }
    let overlap = (0..scene.scene.lights.len())
        .map(|k| max_volume_overlap(scene, k, 64, 36))
        .max()
        .unwrap_or(0);
    if overlap >= 256 {
        eprintln!("warning: up to {overlap} shadow volumes overlap: the 8-bit stencil count wraps (256 reads as 0, lit)");
    }
    c.insert("max_volume_overlap".to_string(), overlap as u64);
    c
}
