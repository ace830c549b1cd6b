//! The quads route of lesson 05: every edge turned once, in advance, into
//! a degenerate quad (one per unit of the count the edge can reach: two
//! for a two-sided caster's interior edge), plus front and back cap
//! triangles ([`degenerate_quads`]). Each quad vertex carries its edge's
//! faces; the vertex shader adds up the edge's count for the light, as the
//! CPU does, and opens the quad or collapses it (`vs_volume_quads` in
//! `shaders/lesson_05/volume.wgsl`). No per-frame CPU work, but memory:
//! every edge is four vertices and every face six ([`quad_sizes`]), each
//! [`QUAD_VERTEX_BYTES`] bytes.

use std::collections::HashMap;

use super::adjacency::Adjacency;
use super::extrusion::VolumeRanges;
use common::glam::Vec3;

// ANCHOR: quad_vertex
/// Pre-built quad/cap vertex. Every vertex carries the faces that decide
/// it: its edge's faces (up to [`FACES_PER_QUAD`]) or its cap's one face.
/// The vertex shader sums them into the edge's *count* for the light
/// (`vs_volume_quads`), as [`silhouette_edges`](super::silhouette::silhouette_edges)
/// does on the CPU.
///
/// 76 bytes: the small fields share one word ([`QuadFlags`]); the two
/// faces' normals and points stay `f32`, so that the shader's "faces the
/// light" is the CPU's, bit for bit. (It was 96 bytes with each small
/// field a word or two of its own, and the 4.2 M-triangle torus's quads
/// needed a 4.8 GB buffer, more than an H100's 4.29 GB `max_buffer_size`.)
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct QuadVertex {
    /// Where the vertex is when the count is positive.
    pub position: [f32; 3],
    /// [`QuadFlags::pack`]: far, copy, each face's runs and two-sidedness.
    pub flags: u32,
    /// Where the vertex is when the count is negative: the other end of
    /// its edge, or its cap partner. Swapping reverses the winding.
    pub reversed: [f32; 3],
    /// Per face: its unnormalised object-space normal and first vertex.
    pub face_normal: [[f32; 3]; FACES_PER_QUAD],
    pub face_point: [[f32; 3]; FACES_PER_QUAD],
}

/// Bytes per quad vertex.
pub const QUAD_VERTEX_BYTES: u64 = std::mem::size_of::<QuadVertex>() as u64;
// ANCHOR_END: quad_vertex

// ANCHOR: quad_flags
/// The small fields of a [`QuadVertex`], packed into one `u32` (the
/// shader's `quad_flags` unpacks them): bit 0 `far`, bits 1–3 `copy`,
/// bits 4–5 and 6–7 `runs[k] + 1`, bits 8 and 9 `two_sided[k]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QuadFlags {
    /// false: stays where it is (a quad's near corner, the front cap);
    /// true: goes to infinity (a quad's far corner, the back cap).
    pub far: bool,
    /// This quad is copy `copy` of its edge: drawn when |count| > copy.
    pub copy: u32,
    /// Per face: +1 if it runs along the edge from `v[0]` to `v[1]`
    /// (a cap's face: +1), −1 if it runs back, 0 if there is no face.
    pub runs: [i32; FACES_PER_QUAD],
    /// Per face: it stands for itself *and* its reversed twin (a
    /// two-sided caster's triangle): it then counts −1 when the twin faces
    /// the light.
    pub two_sided: [bool; FACES_PER_QUAD],
}

impl QuadFlags {
    pub fn pack(self) -> u32 {
        assert!(self.copy < 8, "copy {} needs more than 3 bits", self.copy);
        let mut w = self.far as u32 | self.copy << 1;
        for k in 0..FACES_PER_QUAD {
            assert!((-1..=1).contains(&self.runs[k]));
            w |= ((self.runs[k] + 1) as u32) << (4 + 2 * k);
            w |= (self.two_sided[k] as u32) << (8 + k);
        }
        w
    }

    pub fn unpack(w: u32) -> QuadFlags {
        QuadFlags {
            far: w & 1 == 1,
            copy: (w >> 1) & 7,
            runs: [0, 1].map(|k| ((w >> (4 + 2 * k)) & 3) as i32 - 1),
            two_sided: [0, 1].map(|k| (w >> (8 + k)) & 1 == 1),
        }
    }
}
// ANCHOR_END: quad_flags

/// How many faces one quad vertex carries. A manifold edge has two, and so
/// has a two-sided caster's interior edge once each face is paired with
/// its twin; an edge with more gets one set of quads per two faces.
pub const FACES_PER_QUAD: usize = 2;

pub const QUAD_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: QUAD_VERTEX_BYTES,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Uint32, 2 => Float32x3,
        3 => Float32x3, 4 => Float32x3, 5 => Float32x3, 6 => Float32x3
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

/// The quads of one edge's faces, in groups of at most [`FACES_PER_QUAD`]:
/// per group, (its faces as (runs, two-sided)), and how many copies of the
/// quad it needs: the largest |count| the group can reach.
fn quad_copies(group: &[(i32, bool)]) -> u32 {
    let reach = |sign: i32| group.iter().filter(|f| f.1 || f.0 == sign).count();
    reach(1).max(reach(-1)) as u32
}

/// (vertices, indices) [`degenerate_quads`] builds for `adj`, counted
/// without building them: what the quads route's buffers will hold, to
/// check against the adapter's limits first.
pub fn quad_sizes(adj: &Adjacency) -> (u64, u64) {
    sizes_with(adj, &pair_twins(adj))
}

/// [`quad_sizes`] with the faces' pairing ([`pair_twins`]) already made.
fn sizes_with(adj: &Adjacency, two_sided: &[Option<bool>]) -> (u64, u64) {
    let (mut vertices, mut indices) = (0u64, 0u64);
    for e in &adj.edges {
        let faces: Vec<(i32, bool)> = (adj.faces_of(e).iter())
            .filter_map(|f| Some((if f.forward { 1 } else { -1 }, two_sided[f.face as usize]?)))
            .collect();
        for group in faces.chunks(FACES_PER_QUAD) {
            let copies = quad_copies(group) as u64;
            (vertices, indices) = (vertices + 4 * copies, indices + 6 * copies);
        }
    }
    let caps = two_sided.iter().filter(|t| t.is_some()).count() as u64;
    (vertices + 6 * caps, indices + 6 * caps)
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
    let (n_verts, n_idx) = sizes_with(adj, &two_sided);
    let mut verts: Vec<QuadVertex> = Vec::with_capacity(n_verts as usize);
    let mut idx: Vec<u32> = Vec::with_capacity(n_idx as usize);
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
            let mut flags = QuadFlags {
                far: far == 1,
                copy,
                ..QuadFlags::default()
            };
            for (k, &(runs, two, n, p)) in faces.iter().enumerate() {
                flags.runs[k] = runs;
                flags.two_sided[k] = two;
                (v.face_normal[k], v.face_point[k]) = (n.to_array(), p.to_array());
            }
            v.flags = flags.pack();
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
            let runs: Vec<(i32, bool)> = group.iter().map(|f| (f.0, f.1)).collect();
            for copy in 0..quad_copies(&runs) {
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
        caster_adjacency, light_facing_triangles, silhouette_edges, LightDir,
    };
    use common::scene::mesh::builtin;

    #[test]
    fn flags_round_trip_and_the_vertex_is_76_bytes() {
        assert_eq!(QUAD_VERTEX_BYTES, 76);
        for far in [false, true] {
            for copy in 0..8 {
                for runs in [[-1, 0], [1, -1], [0, 1], [1, 1]] {
                    for two_sided in [[false, true], [true, false]] {
                        let f = QuadFlags {
                            far,
                            copy,
                            runs,
                            two_sided,
                        };
                        assert_eq!(QuadFlags::unpack(f.pack()), f);
                    }
                }
            }
        }
    }

    /// `vs_volume_quads` on the CPU, for an identity model: where the
    /// vertex goes (position, far), or `None` where it collapses.
    fn shade(v: &QuadVertex, light: LightDir) -> Option<([f32; 3], u32)> {
        let f = QuadFlags::unpack(v.flags);
        let count: i32 = (0..FACES_PER_QUAD)
            .map(|k| {
                let n = Vec3::from(v.face_normal[k]);
                let side = match light {
                    LightDir::Point(p) => n.dot(p - Vec3::from(v.face_point[k])),
                    LightDir::Directional(d) => n.dot(-d),
                };
                match side {
                    s if s > 0.0 => f.runs[k],
                    s if s < 0.0 && f.two_sided[k] => -f.runs[k],
                    _ => 0,
                }
            })
            .sum();
        let at = if count < 0 { v.reversed } else { v.position };
        (count.unsigned_abs() > f.copy).then_some((at, f.far as u32))
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
            let sizes = (verts.len() as u64, idx.len() as u64);
            assert_eq!(quad_sizes(&adj), sizes, "{}: counted as built", mesh.name);
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
