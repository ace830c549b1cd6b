//! Counting volumes in the stencil (lesson 05): the z-pass stencil
//! state, the volume pipelines that count with it, the lit pass where the
//! count is 0, and the check that the 8-bit count does not wrap.
//!
//! Two-sided stencil with wrapping 8-bit arithmetic, no colour, no depth
//! write, depth test `Less` against the base pass's depth. Z-pass counts
//! the volume faces in front of the visible surface: front faces that pass
//! increment, back faces that pass decrement. It is wrong when the eye is
//! inside a volume or the near plane cuts one (the missing "enter" count);
//! lesson 06 counts behind the surface instead (z-fail, with caps).

use anyhow::{bail, Result};

use super::adjacency::validate;
use common::glam::Vec3;
use common::gpu::render::{pipeline_layout_for, SceneGpu};
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, DEGENERATE_TRIANGLES, MAX_VOLUME_OVERLAP, NONMANIFOLD_EDGES, OPEN_EDGES,
};
use common::reference::bvh::Bvh;
use common::reference::primary_ray;
use common::scene::mesh::face_normal;

use super::extrusion::volume_shader_module;
use super::extrusion::{world_light, Extrusion, CPU_VERTEX_LAYOUT};
use super::quads::{QUAD_VERTEX_LAYOUT, REACH_VERTEX_LAYOUT};
use super::silhouette::{casts_two_sided, LightDir};
use crate::lesson_01::tally::TallyShader;

/// How the stencil counts a caster's volume faces: z-pass (here) or
/// z-fail (lesson 06, `lesson_06::caps`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    ZPass,
    ZFail,
}

// ANCHOR: stencil_states
/// One face's stencil ops: count with `pass_op` where the depth test
/// passes, with `depth_fail_op` where it fails. Wrapping arithmetic, so
/// the order in which faces arrive does not matter: +1 − 1 is 0 even from 0.
pub fn count_face(
    pass_op: wgpu::StencilOperation,
    depth_fail_op: wgpu::StencilOperation,
) -> wgpu::StencilFaceState {
    wgpu::StencilFaceState {
        compare: wgpu::CompareFunction::Always,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op,
        pass_op,
    }
}

/// Two-sided stencil: one rule for front faces, one for back faces.
pub fn two_sided(
    front: wgpu::StencilFaceState,
    back: wgpu::StencilFaceState,
) -> wgpu::StencilState {
    wgpu::StencilState {
        front,
        back,
        read_mask: 0xff,
        write_mask: 0xff,
    }
}

/// Z-pass: counted in front of the surface, entering +1, leaving −1.
pub fn zpass_stencil() -> wgpu::StencilState {
    use wgpu::StencilOperation::{DecrementWrap, IncrementWrap, Keep};
    two_sided(
        count_face(IncrementWrap, Keep),
        count_face(DecrementWrap, Keep),
    )
}
// ANCHOR_END: stencil_states

// ANCHOR: lit_stencil
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
// ANCHOR_END: lit_stencil

/// What the volume pipelines count with: the stencil state of each
/// [`Method`], the depth bias of caps, and whether depth is clamped instead
/// of clipped. Lesson 05 counts with z-pass only ([`Counting::zpass`]);
/// lesson 06 adds z-fail and caps, lesson 07 depth clamping.
#[derive(Clone, Debug)]
pub struct Counting {
    pub zpass: wgpu::StencilState,
    /// `None`: no z-fail pipelines are built (lesson 05 draws no caps).
    pub zfail: Option<wgpu::StencilState>,
    pub cap_bias: wgpu::DepthBiasState,
    /// Depth clamped instead of clipped (needs DEPTH_CLIP_CONTROL).
    pub unclipped_depth: bool,
    /// The quads are extruded by a per-caster reach (`vs_volume_quads_reach`,
    /// lesson 06 under a finite far plane) instead of to infinity.
    pub finite_reach: bool,
}

impl Counting {
    /// Lesson 05: z-pass, sides only, ordinary clipping.
    pub fn zpass() -> Counting {
        Counting {
            zpass: zpass_stencil(),
            zfail: None,
            cap_bias: Default::default(),
            unclipped_depth: false,
            finite_reach: false,
        }
    }
}

/// The lit pass of a stencil technique: `fs_stencil_lit` where the count is 0.
pub fn stencil_lit_pipeline(gpu: &Gpu, scene: &SceneGpu) -> wgpu::RenderPipeline {
    let module = volume_shader_module(gpu, "stencil lit pass", "");
    scene.lit_pipeline(gpu, &module, "fs_stencil_lit", &[], lit_stencil())
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
        let n = face_normal(t[0], t[1], t[2]);
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
            let (o, d) = primary_ray(inv, i, j, w, h);
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

/// Möller–Trumbore, a small offset away from the start point (the start's
/// own triangle does not count). Chapter 05's stencil diagram uses it too.
pub fn segment_crosses(o: Vec3, d: Vec3, t_max: f32, t: &[Vec3; 3]) -> bool {
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

/// Report counters about the casters, computed once: mesh validation
/// ([`OPEN_EDGES`], [`NONMANIFOLD_EDGES`], [`DEGENERATE_TRIANGLES`], summed
/// over casters) and [`MAX_VOLUME_OVERLAP`] (the largest stencil count
/// found on a 64 × 36 pixel grid, over all lights). No warning: see
/// [`scene_counters`].
pub fn caster_counters(scene: &SceneGpu) -> Counts {
    let mut c = Counts::new();
    for o in scene.scene.objects.iter().filter(|o| o.casts_shadow) {
        let v = validate(&o.mesh);
        c.add(OPEN_EDGES, v.boundary_edges as u64);
        c.add(NONMANIFOLD_EDGES, v.nonmanifold_edges as u64);
        c.add(DEGENERATE_TRIANGLES, v.degenerate_triangles as u64);
    }
    let overlap = (0..scene.scene.lights.len())
        .map(|k| max_volume_overlap(scene, k, 64, 36))
        .max()
        .unwrap_or(0);
    c.set(MAX_VOLUME_OVERLAP, overlap as u64);
    c
}

/// [`caster_counters`], with a warning on stderr when the 8-bit stencil
/// count wraps (256 or more overlapping volumes).
pub fn scene_counters(scene: &SceneGpu) -> Counts {
    let c = caster_counters(scene);
    let overlap = c.get(MAX_VOLUME_OVERLAP).unwrap_or(0);
    if overlap >= 256 {
        eprintln!("warning: up to {overlap} shadow volumes overlap: the 8-bit stencil count wraps (256 reads as 0, lit)");
    }
    c
}

/// What a volume pipeline is for: counting in the stencil, or one of the
/// counting copies (pipeline statistics, a tally).
#[derive(Clone)]
enum Role {
    Stencil(wgpu::StencilState),
    Statistics,
    Tally { depth_test: bool },
}

/// `[mirrored][cap]`: one counting rule's pipelines.
type PipelineSet = [[wgpu::RenderPipeline; 2]; 2];

/// The volume pipelines of one extrusion: each method's pipeline set,
/// plus the fragment-counting pipeline.
pub struct VolumePipelines {
    zpass: PipelineSet,
    zfail: Option<PipelineSet>,
    count: wgpu::RenderPipeline,
    /// `[depth_test][cap]`: counting copies for a [`Tally`](crate::lesson_01::tally::Tally),
    /// without a depth test or with the volume pass's `Less` (and the cap bias).
    tally: [[wgpu::RenderPipeline; 2]; 2],
}

impl VolumePipelines {
    /// The volume shader's entry for `extrusion`, counting with `counting`.
    pub fn new(
        gpu: &Gpu,
        scene: &SceneGpu,
        extrusion: Extrusion,
        counting: &Counting,
    ) -> Result<VolumePipelines> {
        if counting.unclipped_depth && !gpu.has(wgpu::Features::DEPTH_CLIP_CONTROL) {
            bail!(
                "unclipped_depth needs the DEPTH_CLIP_CONTROL feature, which {} does not have",
                gpu.adapter_name()
            );
        }
        let module = volume_shader_module(gpu, "shadow volume", "");
        let (vs_entry, buffers) = match extrusion {
            // The compute route writes the CPU route's vertices.
            Extrusion::Cpu | Extrusion::Compute => ("vs_volume_cpu", vec![Some(CPU_VERTEX_LAYOUT)]),
            Extrusion::Quads if counting.finite_reach => (
                "vs_volume_quads_reach",
                vec![Some(QUAD_VERTEX_LAYOUT), Some(REACH_VERTEX_LAYOUT)],
            ),
            Extrusion::Quads => ("vs_volume_quads", vec![Some(QUAD_VERTEX_LAYOUT)]),
        };
        let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
        let targets = [Some(wgpu::TextureFormat::R8Unorm.into())];
        let tally = TallyShader::new(gpu);
        let make = |kind: Role, front_face, cap: bool| {
            let bias = if cap {
                counting.cap_bias
            } else {
                Default::default()
            };
            let (depth_stencil, fragment) = match kind {
                // Tally copies: stencil untouched, depth as the volume pass
                // tests it (`Less`), or not at all (`Always`).
                Role::Tally { depth_test } => (
                    Some(wgpu::DepthStencilState {
                        format: scene.depth_format,
                        depth_write_enabled: Some(false),
                        depth_compare: Some(if depth_test {
                            wgpu::CompareFunction::Less
                        } else {
                            wgpu::CompareFunction::Always
                        }),
                        stencil: Default::default(),
                        bias,
                    }),
                    Some(tally.fragment()),
                ),
                // No colour, no depth write: the stencil is the only output.
                Role::Stencil(stencil) => (
                    Some(wgpu::DepthStencilState {
                        format: scene.depth_format,
                        depth_write_enabled: Some(false),
                        depth_compare: Some(wgpu::CompareFunction::Less),
                        stencil,
                        bias,
                    }),
                    None,
                ),
                // Counting copy: no depth test, a fragment shader to count.
                Role::Statistics => (
                    None,
                    Some(wgpu::FragmentState {
                        module: &module,
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
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some(vs_entry),
                        compilation_options: Default::default(),
                        buffers: &buffers,
                    },
                    primitive: wgpu::PrimitiveState {
                        front_face,
                        // Both sides of the volume count: one increments, one decrements.
                        cull_mode: None,
                        unclipped_depth: counting.unclipped_depth,
                        ..Default::default()
                    },
                    depth_stencil,
                    multisample: Default::default(),
                    fragment,
                    multiview_mask: None,
                    cache: None,
                })
        };
        let set = |s: &wgpu::StencilState| {
            let caps = |f| {
                [
                    make(Role::Stencil(s.clone()), f, false),
                    make(Role::Stencil(s.clone()), f, true),
                ]
            };
            [caps(wgpu::FrontFace::Ccw), caps(wgpu::FrontFace::Cw)]
        };
        Ok(VolumePipelines {
            zpass: set(&counting.zpass),
            zfail: counting.zfail.as_ref().map(set),
            count: make(Role::Statistics, wgpu::FrontFace::Ccw, false),
            tally: [false, true].map(|depth_test| {
                let kind = Role::Tally { depth_test };
                [false, true].map(|cap| make(kind.clone(), wgpu::FrontFace::Ccw, cap))
            }),
        })
    }

    /// The pipeline for `method`; `mirrored` casters (det < 0) wind the
    /// other way in world space, so their front face is `Cw`. Caps are
    /// drawn with the counting's cap bias.
    /// The copy that counts rasterised fragments (no depth test).
    pub fn counting(&self) -> &wgpu::RenderPipeline {
        &self.count
    }

    /// The tally copy: with the volume pass's depth test or none.
    pub fn tally(&self, depth_test: bool, cap: bool) -> &wgpu::RenderPipeline {
        &self.tally[depth_test as usize][cap as usize]
    }

    pub fn get(&self, method: Method, mirrored: bool, cap: bool) -> &wgpu::RenderPipeline {
        let set = match method {
            Method::ZPass => &self.zpass,
            Method::ZFail => self
                .zfail
                .as_ref()
                .expect("z-fail draws need a Counting with z-fail (lesson_06::caps)"),
        };
        &set[mirrored as usize][cap as usize]
    }
}
