//! Extruding silhouettes into shadow volumes (lesson 05), two ways.
//!
//! WebGPU has no geometry shader, so the silhouette is found either
//!
//! - [`Extrusion::Cpu`]: on the CPU every frame, as Doom 3 did. The light is
//!   moved into object space (inverse model), [`face_facing`] and
//!   [`silhouette_edges_for`] give the sides, and the light-facing
//!   triangles give the caps ([`cpu_volume`]). Vertices are
//!   `(position, w)`: `w = 1` stays, `w = 0` goes to infinity.
//! - [`Extrusion::Quads`]: degenerate quads built once, in advance (one per
//!   edge and per unit of the count the edge can reach: two for a
//!   two-sided caster's interior edge), plus front and back cap triangles
//!   ([`degenerate_quads`]). Each quad vertex carries its edge's faces; the
//!   vertex shader adds up the edge's count for the light, as the CPU
//!   does, and opens the quad or collapses it (`vs_volume_quads` in
//!   `shaders/lesson_05/volume.wgsl`). No per-frame CPU work.
//!
//! Both give the same volumes: the boundary of the union of the
//! light-facing faces' own volumes (see [`silhouette_edges`](super::silhouette::silhouette_edges)).

use std::collections::HashMap;
use std::ops::Range;

use super::adjacency::Adjacency;
use common::glam::Vec3;
use common::gpu::render::shader_module;
use common::gpu::Gpu;

pub use super::silhouette::world_light;
use super::silhouette::{
    face_facing, light_facing_triangles_for, silhouette_edges_for, LightDir, SilhouetteEdge,
};

/// The volume WGSL (`shaders/lesson_05/volume.wgsl`), after `common.wgsl`.
pub const VOLUME_WGSL: &str = include_str!("../../shaders/lesson_05/volume.wgsl");

/// `common.wgsl` + `volume.wgsl` + a lesson's own WGSL.
pub fn volume_shader_module(gpu: &Gpu, label: &str, extra_wgsl: &str) -> wgpu::ShaderModule {
    shader_module(gpu, label, &format!("{VOLUME_WGSL}\n{extra_wgsl}"))
}

/// How the volume geometry is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extrusion {
    /// Silhouettes on the CPU every frame (Doom 3).
    Cpu,
    /// Degenerate quads built in advance, extruded in the vertex shader.
    Quads,
    /// Silhouettes and caps written by a compute shader every frame, the
    /// CPU route's triangles, drawn indirectly with its pipelines
    /// ([`compute`](super::compute)).
    Compute,
}

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

/// Pre-built quad/cap vertex. Every vertex carries the faces that decide
/// it: its edge's faces (up to [`FACES_PER_QUAD`]) or its cap's one face.
/// The vertex shader sums them into the edge's *count* for the light
/// (`vs_volume_quads`), as [`silhouette_edges`](super::silhouette::silhouette_edges)
/// does on the CPU.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct QuadVertex {
    /// Where the vertex is when the count is positive.
    pub position: [f32; 3],
    /// 0: stays where it is (a quad's near corner, the front cap);
    /// 1: goes to infinity (a quad's far corner, the back cap).
    pub far: u32,
    /// Where the vertex is when the count is negative: the other end of
    /// its edge, or its cap partner. Swapping reverses the winding.
    pub reversed: [f32; 3],
    /// This quad is copy `copy` of its edge: drawn when |count| > copy.
    pub copy: u32,
    /// Per face: +1 if it runs along the edge from `v[0]` to `v[1]`
    /// (a cap's face: +1), −1 if it runs back, 0 if there is no face.
    pub runs: [i32; 2],
    /// Per face: 1 if it stands for itself *and* its reversed twin (a
    /// two-sided caster's triangle): it then counts −1 when the twin faces
    /// the light.
    pub two_sided: [u32; 2],
    /// Per face: its unnormalised object-space normal and first vertex.
    pub face_normal: [[f32; 3]; FACES_PER_QUAD],
    pub face_point: [[f32; 3]; FACES_PER_QUAD],
}

/// How many faces one quad vertex carries. A manifold edge has two, and so
/// has a two-sided caster's interior edge once each face is paired with
/// its twin; an edge with more gets one set of quads per two faces.
pub const FACES_PER_QUAD: usize = 2;

pub const QUAD_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<QuadVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Uint32, 2 => Float32x3, 3 => Uint32, 4 => Sint32x2,
        5 => Uint32x2, 6 => Float32x3, 7 => Float32x3, 8 => Float32x3, 9 => Float32x3
    ],
};

/// The quads path's reach (lesson 06): one `f32` per caster and light, the
/// `w` its extruded vertices get (`vs_volume_quads_reach`), read per
/// instance at location 10. 0 is infinity. Slots are [`REACH_SLOT`] bytes.
pub const REACH_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: REACH_SLOT,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![10 => Float32],
};

/// Bytes per caster and light in the reach buffer.
pub const REACH_SLOT: u64 = 16;

/// Vertex ranges of one caster's volume: sides, front cap, back cap.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VolumeRanges {
    pub sides: Range<u32>,
    pub front: Range<u32>,
    pub back: Range<u32>,
}

// ANCHOR: cpu_volume
/// The CPU path: one caster's volume for one light (object space), appended
/// to `out`. Sides from the silhouette; caps from the light-facing faces.
pub fn cpu_volume(adj: &Adjacency, light: LightDir, out: &mut Vec<CpuVertex>) -> VolumeRanges {
    cpu_volume_reaching(adj, light, 0.0, out)
}

/// [`cpu_volume`] with its far vertices at `w = reach_w` instead of 0:
/// `0 < reach_w < 1` moves them `1 / reach_w` times as far from the light
/// (lesson 06's finite extrusion, [`REACH_VERTEX_LAYOUT`]); 0 is infinity.
pub fn cpu_volume_reaching(
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
    out: &mut Vec<CpuVertex>,
) -> VolumeRanges {
    cpu_volume_parts(adj, light, reach_w, CpuParts::default(), out)
}

/// [`cpu_volume_reaching`], with the sides or the caps found by `parts`
/// where it says so (an exercise's code), else by the lesson's own.
pub fn cpu_volume_parts(
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
    parts: CpuParts,
    out: &mut Vec<CpuVertex>,
) -> VolumeRanges {
    let facing = face_facing(adj, light);
    let v = |i: u32, w: f32| CpuVertex {
        position: adj.positions[i as usize].to_array(),
        // w = 0 marks "extruded"; it becomes reach_w (0 stays infinity).
        w: if w == 0.0 { reach_w } else { w },
    };
    let directional = matches!(light, LightDir::Directional(_));
    let start = out.len() as u32;
    let edges = match parts.sides {
        Some(sides) => sides(adj, light),
        None => silhouette_edges_for(adj, &facing),
    };
    for e in edges {
        // The lit face runs a → b; its side of the volume, seen from
        // outside, runs b → a → a∞ → b∞ (counter-clockwise, like the caps).
        out.extend([v(e.a, 1.0), v(e.b, 0.0), v(e.b, 1.0)]);
        if !directional {
            // Directional: a∞ = b∞, the second triangle would have no area.
            out.extend([v(e.a, 1.0), v(e.a, 0.0), v(e.b, 0.0)]);
        }
    }
    let sides_end = out.len() as u32;
    // The front cap: the light-facing triangles. The back cap: the same
    // triangles at infinity, reversed.
    let (front, back) = match parts.caps {
        Some(caps) => caps(adj, light),
        None => {
            let lit = light_facing_triangles_for(adj, &facing);
            let back = lit.iter().map(|t| [t[0], t[2], t[1]]).collect();
            (lit, back)
        }
    };
    for t in &front {
        out.extend(t.map(|i| v(i, 1.0)));
    }
    let front_end = out.len() as u32;
    if !directional {
        // Directional: the back cap shrinks to a point at infinity.
        for t in &back {
            out.extend(t.map(|i| v(i, 0.0)));
        }
    }
    VolumeRanges {
        sides: start..sides_end,
        front: sides_end..front_end,
        back: front_end..out.len() as u32,
    }
}
// ANCHOR_END: cpu_volume

/// A silhouette finder: the edges to extrude, as
/// [`silhouette_edges`](super::silhouette::silhouette_edges) gives them.
pub type SidesFn = fn(&Adjacency, LightDir) -> Vec<SilhouetteEdge>;

/// A cap builder: (front cap, back cap) triangles, welded ids, each wound
/// as drawn (the back cap's vertices go to infinity).
pub type CapsFn = fn(&Adjacency, LightDir) -> (Vec<[u32; 3]>, Vec<[u32; 3]>);

/// Which parts of the CPU path's volume an exercise's code builds
/// ([`cpu_volume_parts`]); `None`: the lesson's own. The default is the
/// lesson's own everywhere.
#[derive(Clone, Copy, Debug, Default)]
pub struct CpuParts {
    pub sides: Option<SidesFn>,
    pub caps: Option<CapsFn>,
}

// ANCHOR: degenerate_quads
/// The quads path, built once. The vertex shader cannot see an edge's
/// neighbours, so each quad vertex carries its edge's faces, and the
/// shader adds up the edge's *count* for the light exactly as
/// [`silhouette_edges`](super::silhouette::silhouette_edges) does: +1 for
/// each light-facing face that runs `v[0] → v[1]`, −1 for each that runs
/// back. The quad opens into a side where the count is not 0 (wound by
/// its sign), and collapses to a point, drawing nothing, where it is 0.
///
/// - A closed mesh: one quad per edge (count −1, 0 or +1).
/// - A two-sided caster (each triangle and its reversed twin, from
///   [`caster_adjacency`](super::silhouette::caster_adjacency)): the pair
///   is one *two-sided* face, +1 when the triangle faces the light and −1
///   when its twin does. An interior edge's count is then −2, 0 or +2:
///   two quads, copy 0 drawn when |count| > 0 and copy 1 when
///   |count| > 1. Its pairs' caps are drawn once, by the side that faces.
/// - More than [`FACES_PER_QUAD`] faces on an edge (non-manifold): one
///   set of quads per two faces. Still right, but those may cancel only
///   in the stencil.
///
/// Then front and back cap triangles for every face (a twin pair: once).
/// Returns (vertices, indices, index ranges).
pub fn degenerate_quads(adj: &Adjacency) -> (Vec<QuadVertex>, Vec<u32>, VolumeRanges) {
    let two_sided = pair_twins(adj);
    let mut verts: Vec<QuadVertex> = Vec::new();
    let mut idx: Vec<u32> = Vec::new();
    // One face as a quad vertex sees it: (runs, two-sided, normal, point).
    let face = |f: u32, runs: i32| {
        let p0 = adj.positions[adj.triangles[f as usize][0] as usize];
        let n = adj.face_normals[f as usize];
        (runs, two_sided[f as usize] == Some(true), n, p0)
    };
    let vertex =
        |at: u32, reversed: u32, far: u32, copy: u32, faces: &[(i32, bool, Vec3, Vec3)]| {
            let mut v = QuadVertex::zeroed_vertex();
            v.position = adj.positions[at as usize].to_array();
            v.reversed = adj.positions[reversed as usize].to_array();
            (v.far, v.copy) = (far, copy);
            for (k, &(runs, two, n, p)) in faces.iter().enumerate() {
                v.runs[k] = runs;
                v.two_sided[k] = two as u32;
                (v.face_normal[k], v.face_point[k]) = (n.to_array(), p.to_array());
            }
            v
        };
    for e in &adj.edges {
        let [a, b] = e.v;
        let faces: Vec<_> = (adj.faces_of(e).iter())
            .filter(|f| two_sided[f.face as usize].is_some())
            .map(|f| face(f.face, if f.forward { 1 } else { -1 }))
            .collect();
        for group in faces.chunks(FACES_PER_QUAD) {
            // The largest |count| the group can reach: one quad for each.
            let reach = |sign: i32| group.iter().filter(|f| f.1 || f.0 == sign).count();
            for copy in 0..reach(1).max(reach(-1)) as u32 {
                let base = verts.len() as u32;
                verts.extend([
                    vertex(a, b, 0, copy, group),
                    vertex(b, a, 0, copy, group),
                    vertex(b, a, 1, copy, group),
                    vertex(a, b, 1, copy, group),
                ]);
                // Wound a → b → b∞ → a∞ reversed: outward when the lit
                // faces run a → b (count > 0).
                idx.extend([base, base + 2, base + 1, base, base + 3, base + 2]);
            }
        }
    }
    let sides = 0..idx.len() as u32;
    let caps: Vec<u32> = (0..adj.triangles.len() as u32)
        .filter(|f| two_sided[*f as usize].is_some())
        .collect();
    for far in [0u32, 1] {
        for &f in &caps {
            let [t0, t1, t2] = adj.triangles[f as usize];
            let one = [face(f, 1)];
            let base = verts.len() as u32;
            // A negative count (the twin faces) swaps t1 and t2: reversed.
            verts.extend([
                vertex(t0, t0, far, 0, &one),
                vertex(t1, t2, far, 0, &one),
                vertex(t2, t1, far, 0, &one),
            ]);
            // The back cap winds the other way (it faces away from the light).
            idx.extend(if far == 0 {
                [base, base + 1, base + 2]
            } else {
                [base, base + 2, base + 1]
            });
        }
    }
    let n = caps.len() as u32 * 3;
    let ranges = VolumeRanges {
        sides: sides.clone(),
        front: sides.end..sides.end + n,
        back: sides.end + n..sides.end + 2 * n,
    };
    (verts, idx, ranges)
}

/// For every face: `Some(true)` if it stands for a two-sided pair (a later
/// face is its reversed twin `[t0, t2, t1]`, as
/// [`caster_adjacency`](super::silhouette::caster_adjacency) adds it),
/// `None` if it is such a twin (left out: its partner counts for it),
/// `Some(false)` otherwise. The twin's normal is exactly the negated
/// normal, so "the twin faces the light" is exactly "n · (L − p0) < 0".
fn pair_twins(adj: &Adjacency) -> Vec<Option<bool>> {
    let mut open: HashMap<[u32; 3], Vec<usize>> = HashMap::new();
    let mut out = vec![Some(false); adj.triangles.len()];
    for (f, t) in adj.triangles.iter().enumerate() {
        let twin_of = [t[0], t[2], t[1]];
        match open.get_mut(&twin_of).and_then(|v| v.pop()) {
            Some(first) => (out[first], out[f]) = (Some(true), None),
            None => open.entry(*t).or_default().push(f),
        }
    }
    out
}
// ANCHOR_END: degenerate_quads

impl QuadVertex {
    pub fn zeroed_vertex() -> QuadVertex {
        bytemuck::Zeroable::zeroed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson_05::adjacency::validate;
    use crate::lesson_05::silhouette::{
        caster_adjacency, light_facing_triangles, silhouette_edges,
    };
    use common::scene::mesh::builtin;

    /// The lesson's caps, as a [`CapsFn`] would give them.
    fn lesson_caps(adj: &Adjacency, light: LightDir) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
        let front = light_facing_triangles(adj, light);
        let back = front.iter().map(|t| [t[0], t[2], t[1]]).collect();
        (front, back)
    }

    #[test]
    fn parts_given_as_functions_build_the_same_volume() {
        let adj = Adjacency::new(&builtin("knot").unwrap());
        let parts = CpuParts {
            sides: Some(silhouette_edges),
            caps: Some(lesson_caps),
        };
        for light in [
            LightDir::Point(Vec3::new(1.0, 3.0, 0.5)),
            LightDir::Directional(Vec3::new(-0.4, -1.0, 0.3)),
        ] {
            for reach in [0.0, 0.25] {
                let (mut own, mut given) = (Vec::new(), Vec::new());
                let r = cpu_volume_reaching(&adj, light, reach, &mut own);
                let s = cpu_volume_parts(&adj, light, reach, parts, &mut given);
                assert_eq!((r, &own), (s, &given), "{light:?}, reach {reach}");
                assert!(!own.is_empty());
            }
        }
    }

    /// `vs_volume_quads` on the CPU, for an identity model: where the
    /// vertex goes (position, far), or `None` where it collapses.
    fn shade(v: &QuadVertex, light: LightDir) -> Option<([f32; 3], u32)> {
        let count: i32 = (0..FACES_PER_QUAD)
            .map(|k| {
                let n = Vec3::from(v.face_normal[k]);
                let side = match light {
                    LightDir::Point(p) => n.dot(p - Vec3::from(v.face_point[k])),
                    LightDir::Directional(d) => n.dot(-d),
                };
                match side {
                    s if s > 0.0 => v.runs[k],
                    s if s < 0.0 && v.two_sided[k] == 1 => -v.runs[k],
                    _ => 0,
                }
            })
            .sum();
        let at = if count < 0 { v.reversed } else { v.position };
        (count.unsigned_abs() > v.copy).then_some((at, v.far))
    }

    /// Removes edges that an opposite edge cancels.
    fn cancel_opposite(mut edges: Vec<[[f32; 3]; 2]>) -> Vec<[[f32; 3]; 2]> {
        let mut out: Vec<[[f32; 3]; 2]> = Vec::new();
        while let Some([a, b]) = edges.pop() {
            match out.iter().position(|e| *e == [b, a]) {
                Some(k) => {
                    out.swap_remove(k);
                }
                None => out.push([a, b]),
            }
        }
        out
    }

    /// The quads open into exactly the CPU's silhouette edges (with their
    /// multiplicity and direction) and caps, for closed, open (two-sided)
    /// and non-manifold casters; everything else collapses.
    #[test]
    fn quads_open_into_the_cpu_silhouette() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let book = common::scene::obj::load_obj(&dir.join("nonmanifold_book.obj")).unwrap();
        let meshes = [
            builtin("knot").unwrap(),
            builtin("plane").unwrap(),
            common::scene::mesh_dense::any_builtin("holed_sphere").unwrap(),
            book,
        ];
        let lights = [
            LightDir::Point(Vec3::new(0.3, 2.0, 0.4)),
            LightDir::Point(Vec3::new(0.05, 0.1, -0.02)), // inside the sphere
            LightDir::Point(Vec3::new(-3.0, -1.0, 2.0)),
            LightDir::Directional(Vec3::new(-0.4, -1.0, 0.3)),
            LightDir::Directional(Vec3::new(1.0, 0.2, 0.0)),
        ];
        for mesh in &meshes {
            let adj = caster_adjacency(mesh);
            let (verts, idx, ranges) = degenerate_quads(&adj);
            let p = |i: u32| adj.positions[i as usize].to_array();
            for light in lights {
                let mut want: Vec<_> = (silhouette_edges(&adj, light).iter())
                    .map(|e| [p(e.a), p(e.b)])
                    .collect();
                let mut got = Vec::new();
                for q in idx[ranges.sides.start as usize..ranges.sides.end as usize].chunks(6) {
                    let c: Vec<_> = q
                        .iter()
                        .map(|&i| shade(&verts[i as usize], light))
                        .collect();
                    if let [Some((a, 0)), Some((b, 1)), Some((b2, 0)), _, Some((a2, 1)), _] = c[..]
                    {
                        assert_eq!((a, b), (a2, b2), "{}: a quad opens whole", mesh.name);
                        got.push([a, b]);
                    } else {
                        assert!(c.iter().all(Option::is_none), "{}: {c:?}", mesh.name);
                    }
                }
                let key = |e: &[[f32; 3]; 2]| e.map(|v| v.map(f32::to_bits));
                if validate(mesh).nonmanifold_edges > 0 {
                    // One set of quads per two faces: they may cancel in
                    // pairs (a → b with b → a) only in the stencil.
                    got = cancel_opposite(got);
                }
                want.sort_by_key(key);
                got.sort_by_key(key);
                assert_eq!(got, want, "{}, {light:?}: sides", mesh.name);
                let lit = light_facing_triangles(&adj, light);
                let mut want: Vec<_> = lit.iter().map(|t| t.map(p)).collect();
                let front = &idx[ranges.front.start as usize..ranges.front.end as usize];
                let mut got: Vec<_> = (front.chunks(3))
                    .filter_map(|t| {
                        let v = [0, 1, 2].map(|k| shade(&verts[t[k] as usize], light));
                        v.iter()
                            .all(Option::is_some)
                            .then(|| v.map(|v| v.unwrap().0))
                    })
                    .collect();
                let key = |t: &[[f32; 3]; 3]| t.map(|v| v.map(f32::to_bits));
                want.sort_by_key(key);
                got.sort_by_key(key);
                assert_eq!(got, want, "{}, {light:?}: front cap", mesh.name);
            }
        }
    }
}
