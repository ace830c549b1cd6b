//! Edge adjacency (lesson 05): every edge of a caster and the faces that
//! use it, and [`validate`], which says whether a mesh is closed, manifold
//! and consistently oriented (what shadow volumes need of their casters).
//!
//! Everything here works on the mesh *welded by position* (see
//! [`common::scene::mesh::weld_by_position`]): UV seams and flat-shaded corners
//! duplicate vertices, and a silhouette taken over the unwelded indices
//! would find a false "open" edge along every seam.

use std::ops::Range;

use common::glam::Vec3;
use common::scene::mesh::{face_normal, weld_remap, Mesh};

/// One face using an edge, and which way the face's winding runs along it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeFace {
    pub face: u32,
    /// True when the face's winding goes from `v[0]` to `v[1]`.
    pub forward: bool,
}

/// An undirected edge between two welded vertices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Edge {
    /// The two welded vertex ids, `v[0] < v[1]`.
    pub v: [u32; 2],
    /// Where this edge's faces are in the shared face list; read them
    /// with [`Adjacency::faces_of`]. Closed manifold meshes have 2.
    faces: Range<u32>,
}

/// A mesh welded by position, with every edge and the faces that use it.
#[derive(Clone, Debug, Default)]
pub struct Adjacency {
    /// One position per welded vertex.
    pub positions: Vec<Vec3>,
    /// The mesh's triangles, in the mesh's order, as welded vertex ids.
    pub triangles: Vec<[u32; 3]>,
    /// Unnormalised face normals `(v1 − v0) × (v2 − v0)`. Exactly zero for a
    /// degenerate face, which then never faces any light.
    pub face_normals: Vec<Vec3>,
    /// Every undirected edge once, sorted by `v`.
    pub edges: Vec<Edge>,
    edge_faces: Vec<EdgeFace>,
}

impl Adjacency {
    /// Welds `mesh` by position and finds its edges.
    pub fn new(mesh: &Mesh) -> Adjacency {
        Adjacency::from_triangles(&mesh.positions, &mesh.indices)
    }

    /// The same from raw positions and a triangle list. Panics if an index
    /// is out of range.
    pub fn from_triangles(positions: &[Vec3], indices: &[u32]) -> Adjacency {
        let (positions, remap) = weld_remap(positions);
        let triangles: Vec<[u32; 3]> = indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(|i| remap[i as usize]))
            .collect();
        let face_normals = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| positions[i as usize]);
                face_normal(a, b, c)
            })
            .collect();

        // Each face adds its three directed edges, keyed by the sorted pair.
        let mut uses: Vec<([u32; 2], EdgeFace)> = Vec::with_capacity(3 * triangles.len());
        for (face, t) in triangles.iter().enumerate() {
            // A face with a repeated vertex has no real edges.
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                continue;
            }
            for k in 0..3 {
                let (from, to) = (t[k], t[(k + 1) % 3]);
                let edge_face = EdgeFace {
                    face: face as u32,
                    forward: from < to,
                };
                uses.push(([from.min(to), from.max(to)], edge_face));
            }
        }
        uses.sort_unstable_by_key(|(v, f)| (*v, f.face));

        let mut edges: Vec<Edge> = Vec::new();
        let mut edge_faces = Vec::with_capacity(uses.len());
        for (v, f) in uses {
            let n = edge_faces.len() as u32;
            match edges.last_mut() {
                Some(last) if last.v == v => last.faces.end = n + 1,
                _ => edges.push(Edge { v, faces: n..n + 1 }),
            }
            edge_faces.push(f);
        }
        Adjacency {
            positions,
            triangles,
            face_normals,
            edges,
            edge_faces,
        }
    }

    /// The faces that use `edge`, with their direction along it.
    pub fn faces_of(&self, edge: &Edge) -> &[EdgeFace] {
        &self.edge_faces[edge.faces.start as usize..edge.faces.end as usize]
    }
}

/// What [`validate`] found. Edges are counted on the mesh welded by position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshReport {
    pub triangles: usize,
    /// Triangles with a repeated (welded) vertex, or zero area.
    pub degenerate_triangles: usize,
    /// Edges used by exactly one triangle: the rims of holes.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub nonmanifold_edges: usize,
    /// Edges used by two triangles that both run along it the same way:
    /// the two faces disagree about which side is out.
    pub misoriented_edges: usize,
    /// No boundary and no non-manifold edges: the mesh encloses a volume.
    pub closed: bool,
}

impl std::fmt::Display for MeshReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} triangles ({} degenerate), {} boundary edges, {} non-manifold edges, \
             {} misoriented edges: {}",
            self.triangles,
            self.degenerate_triangles,
            self.boundary_edges,
            self.nonmanifold_edges,
            self.misoriented_edges,
            if self.closed { "closed" } else { "open" }
        )
    }
}

/// Checks a mesh the way shadow volumes need it: welded by position, is it
/// closed, manifold and consistently oriented? Triangles with a repeated
/// welded vertex add no edges; zero-area triangles with three distinct
/// vertices still do (they are degenerate but still connect their edges).
/// Panics if an index is out of range.
pub fn validate(mesh: &Mesh) -> MeshReport {
    let adjacency = Adjacency::new(mesh);
    let mut report = MeshReport {
        triangles: mesh.triangle_count(),
        degenerate_triangles: adjacency
            .face_normals
            .iter()
            .filter(|n| **n == Vec3::ZERO)
            .count(),
        boundary_edges: 0,
        nonmanifold_edges: 0,
        misoriented_edges: 0,
        closed: false,
    };
    for edge in &adjacency.edges {
        match adjacency.faces_of(edge) {
            [_] => report.boundary_edges += 1,
            [f, g] if f.forward == g.forward => report.misoriented_edges += 1,
            [_, _] => {}
            _ => report.nonmanifold_edges += 1,
        }
    }
    report.closed = report.triangles > report.degenerate_triangles
        && report.boundary_edges == 0
        && report.nonmanifold_edges == 0;
    report
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::scene::mesh::{builtin, BUILTIN_NAMES};

    #[test]
    fn closed_builtins_have_two_opposite_faces_per_edge() {
        for name in ["cube", "sphere", "torus", "knot"] {
            let adj = Adjacency::new(&builtin(name).unwrap());
            for e in &adj.edges {
                let f = adj.faces_of(e);
                assert!(
                    f.len() == 2 && f[0].forward != f[1].forward,
                    "{name}: {e:?}"
                );
            }
        }
    }

    #[test]
    fn builtins_validate() {
        for name in BUILTIN_NAMES {
            let r = validate(&builtin(name).unwrap());
            assert_eq!(r.degenerate_triangles, 0, "{name}: {r}");
            assert_eq!(r.misoriented_edges, 0, "{name}: {r}");
            assert_eq!(r.nonmanifold_edges, 0, "{name}: {r}");
            assert_eq!(r.closed, name != "plane", "{name}: {r}");
        }
        let plane = validate(&builtin("plane").unwrap());
        assert_eq!(plane.boundary_edges, 4);
    }

    #[test]
    fn split_seams_weld_closed() {
        // Give every triangle its own three vertices: closed only after welding.
        let cube = builtin("cube").unwrap();
        let positions: Vec<Vec3> = cube
            .indices
            .iter()
            .map(|&i| cube.positions[i as usize])
            .collect();
        let split = Mesh {
            name: "split".into(),
            normals: vec![Vec3::Y; positions.len()],
            indices: (0..positions.len() as u32).collect(),
            positions,
        };
        let r = validate(&split);
        assert!(r.closed && r.boundary_edges == 0, "{r}");
    }

    #[test]
    fn validate_counts_open_nonmanifold_and_misoriented_edges() {
        let p = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::NEG_Z,
            Vec3::ONE,
        ];
        let mesh = |indices: Vec<u32>| Mesh {
            positions: p.clone(),
            normals: vec![Vec3::Y; 6],
            indices,
            ..Default::default()
        };
        // Three triangles on edge 0–1: non-manifold; the other edges open.
        let r = validate(&mesh(vec![0, 1, 2, 1, 0, 3, 0, 1, 4]));
        assert_eq!(
            (r.nonmanifold_edges, r.boundary_edges, r.closed),
            (1, 6, false),
            "{r}"
        );
        // Two triangles that both run 0→1: misoriented.
        let r = validate(&mesh(vec![0, 1, 2, 0, 1, 3]));
        assert_eq!(r.misoriented_edges, 1, "{r}");
        // A repeated vertex and a zero-area triangle.
        let r = validate(&mesh(vec![0, 0, 1, 0, 1, 5, 0, 5, 5]));
        let collinear = validate(&Mesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            indices: vec![0, 1, 2],
            ..Default::default()
        });
        assert_eq!(r.degenerate_triangles, 2, "{r}");
        assert_eq!(collinear.degenerate_triangles, 1, "{collinear}");
        assert!(!collinear.closed);
    }
}
