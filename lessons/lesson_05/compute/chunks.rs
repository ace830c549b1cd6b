//! The compute route's casters in chunks (lesson 05): a run of a caster's
//! edges and a run of its faces, packed with the vertices and faces they
//! read, so that no storage binding holds a whole mesh. Each chunk's
//! tables and its worst-case volume stay under the adapter's storage
//! binding limit; a larger mesh is more chunks, bounded only by memory.
//!
//! A chunk's tables are those of extrude.wgsl's `mesh` binding,
//! renumbered: its own faces first (the caps it writes), then the other
//! faces its edges use (only tested for facing), and the vertices they
//! all touch, by increasing id. The numbers themselves (positions,
//! normals) are copied bit for bit, so every facing test, and so every
//! triangle, is the one the whole mesh gives.

use std::ops::Range;

use anyhow::{bail, Result};

use super::super::adjacency::Adjacency;

/// Bytes of one volume vertex (`CpuVertex`).
const VERTEX_BYTES: u64 = 16;

/// One chunk's tables as extrude.wgsl reads them: one `u32` array of five
/// tables, and how many vertices its volume can need at most.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PackedMesh {
    pub words: Vec<u32>,
    /// Where positions, normals, triangles, edges and face uses start.
    pub offsets: [u32; 5],
    /// The chunk's edges, and its own faces (the first `faces` of its
    /// face tables, whose caps it writes).
    pub edges: u32,
    pub faces: u32,
    /// Side vertices when every edge is a silhouette as often as it can
    /// be: max(faces running one way, faces running the other) per edge,
    /// 6 vertices each (a point light's two triangles).
    pub max_side_vertices: u32,
}

impl PackedMesh {
    /// The worst-case volume's vertices: every side, both caps.
    pub fn max_vertices(&self) -> u64 {
        self.max_side_vertices as u64 + 6 * self.faces as u64
    }

    /// The bytes of the `mesh` binding and of the worst-case volume.
    pub fn bytes(&self) -> (u64, u64) {
        (
            4 * self.words.len() as u64,
            VERTEX_BYTES * self.max_vertices(),
        )
    }
}

// ANCHOR: pack_adjacency
/// Packs all of `adj` for extrude.wgsl (see the shader's `mesh` binding).
pub fn pack_adjacency(adj: &Adjacency) -> PackedMesh {
    pack_chunk(adj, 0..adj.edges.len(), 0..adj.triangles.len())
}

/// Packs `adj`'s edges `edges` and faces `faces`, renumbered (see the
/// module's doc).
pub fn pack_chunk(adj: &Adjacency, edges: Range<usize>, faces: Range<usize>) -> PackedMesh {
    let edges = &adj.edges[edges];
    // Faces: the chunk's own, then the others its edges use, by id.
    let mut others: Vec<u32> = (edges.iter())
        .flat_map(|e| adj.faces_of(e).iter().map(|u| u.face))
        .filter(|&f| !faces.contains(&(f as usize)))
        .collect();
    others.sort_unstable();
    others.dedup();
    let own = faces.clone().map(|f| f as u32);
    let face_ids: Vec<u32> = own.chain(others.iter().copied()).collect();
    let local_face = |f: u32| match faces.contains(&(f as usize)) {
        true => f - faces.start as u32,
        false => faces.len() as u32 + others.binary_search(&f).expect("an edge's face") as u32,
    };
    // Vertices: the edges' ends and the faces' corners, by id.
    let corners = face_ids.iter().flat_map(|&f| adj.triangles[f as usize]);
    let mut vertices: Vec<u32> = edges.iter().flat_map(|e| e.v).chain(corners).collect();
    vertices.sort_unstable();
    vertices.dedup();
    let local_vertex = |v: u32| vertices.binary_search(&v).expect("a chunk's vertex") as u32;

    let mut w: Vec<u32> = Vec::new();
    let mut offsets = [0u32; 5];
    let bits = |v: common::glam::Vec3| v.to_array().map(f32::to_bits);
    w.extend(
        vertices
            .iter()
            .flat_map(|&v| bits(adj.positions[v as usize])),
    );
    offsets[1] = w.len() as u32;
    w.extend(
        face_ids
            .iter()
            .flat_map(|&f| bits(adj.face_normals[f as usize])),
    );
    offsets[2] = w.len() as u32;
    w.extend(
        face_ids
            .iter()
            .flat_map(|&f| adj.triangles[f as usize].map(local_vertex)),
    );
    offsets[3] = w.len() as u32;
    let (mut uses, mut max_sides) = (Vec::new(), 0u32);
    for e in edges {
        let used = adj.faces_of(e);
        let [v0, v1] = e.v.map(local_vertex);
        w.extend([v0, v1, uses.len() as u32, used.len() as u32]);
        uses.extend(
            used.iter()
                .map(|u| local_face(u.face) << 1 | u.forward as u32),
        );
        let forward = used.iter().filter(|u| u.forward).count() as u32;
        max_sides += forward.max(used.len() as u32 - forward);
    }
    offsets[4] = w.len() as u32;
    w.extend(uses);
    w.push(0); // never empty: wgpu rejects a zero-sized binding
    PackedMesh {
        words: w,
        offsets,
        edges: edges.len() as u32,
        faces: faces.len() as u32,
        max_side_vertices: 6 * max_sides,
    }
}
// ANCHOR_END: pack_adjacency

/// `adj` in as few chunks as keep each chunk's tables and worst-case
/// volume within `max_bytes` (the adapter's storage binding limit): `n`
/// equal runs of edges and of faces, `n` doubled until every one fits.
/// An error only if one edge or face alone would not fit.
pub fn split(adj: &Adjacency, max_bytes: u64) -> Result<Vec<PackedMesh>> {
    let (e, f) = (adj.edges.len(), adj.triangles.len());
    let fits = |p: &PackedMesh| {
        let (tables, volume) = p.bytes();
        tables <= max_bytes && volume <= max_bytes
    };
    let whole = pack_adjacency(adj);
    if fits(&whole) {
        return Ok(vec![whole]);
    }
    let (tables, volume) = whole.bytes();
    let most = e.max(f).max(1);
    let mut n = (tables.max(volume).div_ceil(max_bytes.max(1)) as usize)
        .max(2)
        .min(most);
    loop {
        let run = |len: usize, i: usize| len * i / n..len * (i + 1) / n;
        let chunks: Vec<PackedMesh> = (0..n)
            .map(|i| pack_chunk(adj, run(e, i), run(f, i)))
            .filter(|p| p.edges + p.faces > 0)
            .collect();
        if chunks.iter().all(fits) {
            return Ok(chunks);
        }
        if n == most {
            bail!(
                "one edge or face of a caster needs more than {max_bytes} bytes of tables or volume \
                 (an edge shared by that many faces): the compute route cannot split it"
            );
        }
        n = (2 * n).min(most);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::scene::mesh::builtin;

    /// A chunk's tables read back to the whole mesh's: each of its edges'
    /// ends and face uses, and each of its faces' corners and normal.
    #[test]
    fn chunks_hold_what_their_edges_and_faces_read() {
        let adj = Adjacency::new(&builtin("knot").unwrap());
        let whole = pack_adjacency(&adj);
        let chunks = split(&adj, whole.bytes().1 / 5).unwrap();
        assert!(chunks.len() >= 5, "{} chunks", chunks.len());
        let (mut edges, mut faces) = (0, 0);
        for c in &chunks {
            let o = c.offsets.map(|o| o as usize);
            let pos = |v: u32| &c.words[o[0] + 3 * v as usize..][..3];
            let face = |f: u32| {
                let t = &c.words[o[2] + 3 * f as usize..][..3];
                let n = &c.words[o[1] + 3 * f as usize..][..3];
                (
                    t.iter().map(|&v| pos(v).to_vec()).collect::<Vec<_>>(),
                    n.to_vec(),
                )
            };
            let bits = |p: common::glam::Vec3| p.to_array().map(f32::to_bits).to_vec();
            for i in 0..c.faces {
                let g = adj.triangles[faces + i as usize];
                let want: Vec<Vec<u32>> =
                    g.iter().map(|&v| bits(adj.positions[v as usize])).collect();
                let n = bits(adj.face_normals[faces + i as usize]);
                assert_eq!(face(i), (want, n));
            }
            for i in 0..c.edges as usize {
                let e = &adj.edges[edges + i];
                let row = &c.words[o[3] + 4 * i..][..4];
                let ends: Vec<Vec<u32>> =
                    e.v.iter()
                        .map(|&v| bits(adj.positions[v as usize]))
                        .collect();
                assert_eq!(vec![pos(row[0]).to_vec(), pos(row[1]).to_vec()], ends);
                for (j, u) in adj.faces_of(e).iter().enumerate() {
                    let local = c.words[o[4] + (row[2] + j as u32) as usize];
                    assert_eq!(local & 1, u.forward as u32);
                    let n = bits(adj.face_normals[u.face as usize]);
                    assert_eq!(face(local >> 1).1, n);
                }
            }
            let (tables, volume) = c.bytes();
            assert!(tables <= whole.bytes().1 / 5 && volume <= whole.bytes().1 / 5);
            (edges, faces) = (edges + c.edges as usize, faces + c.faces as usize);
        }
        assert_eq!((edges, faces), (adj.edges.len(), adj.triangles.len()));
        assert_eq!(split(&adj, u64::MAX).unwrap(), vec![whole]);
    }
}
