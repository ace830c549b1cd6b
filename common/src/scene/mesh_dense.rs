//! The dense built-in meshes: large enough to time volume extrusion on,
//! and (`holed_sphere`) open, so that it casts as a two-sided surface.
//! [`crate::scene::mesh::builtin`] knows them by name, like the small ones; they
//! have no `assets/*.obj` copy (they are megabytes).
//!
//! | name | shape | vertices | triangles |
//! |---|---|---|---|
//! | `holed_sphere` | the `sphere` (radius 0.5, smooth normals) at 256 segments × 100 stacks, with five round holes of radius 0.03 punched through it (the triangles whose centroid lies within 0.03 of a hole's centre are left out, and so are the vertices no triangle uses). Open: every hole's rim is a loop of boundary edges. The holes are centred on the unit directions in [`HOLE_DIRECTIONS`] | 25 264 | 50 400 |
//! | `dense_knot` | the `knot` at 768 × 64 segments (instead of 192 × 16). Closed | 49 152 | 98 304 |

use glam::DVec3;

use crate::scene::mesh::{knot, sphere, Mesh};

/// The dense built-ins, in the order their docs list them.
pub const DENSE_BUILTIN_NAMES: [&str; 2] = ["holed_sphere", "dense_knot"];

/// Where `holed_sphere`'s holes are: directions from its centre (not
/// normalised here; [`holed_sphere`] normalises them). One faces up, so a
/// light above sees into the sphere through it.
pub const HOLE_DIRECTIONS: [[f64; 3]; 5] = [
    [0.2, 1.0, 0.1],
    [1.0, 0.3, 0.4],
    [-0.7, 0.5, 0.8],
    [-0.3, -0.2, -1.0],
    [0.6, -0.9, -0.2],
];

/// Any built-in mesh by name, small ([`crate::scene::mesh::builtin`]) or dense:
/// what a scene's `mesh = "..."` names. An unknown name is one line that
/// lists every known one.
pub fn any_builtin(name: &str) -> anyhow::Result<Mesh> {
    match dense_builtin(name) {
        Some(mut mesh) => {
            mesh.name = name.to_string();
            Ok(mesh)
        }
        None => crate::scene::mesh::builtin(name).map_err(|_| {
            anyhow::anyhow!(
                "unknown built-in mesh {name:?} (known: {}, {}; or give a path ending in .obj)",
                crate::scene::mesh::BUILTIN_NAMES.join(", "),
                DENSE_BUILTIN_NAMES.join(", ")
            )
        }),
    }
}

/// A dense built-in by name, or `None` if `name` is not one.
pub fn dense_builtin(name: &str) -> Option<Mesh> {
    match name {
        "holed_sphere" => Some(holed_sphere()),
        "dense_knot" => Some(knot(0.28, 0.14, 0.07, 768, 64)),
        _ => None,
    }
}

/// The dense sphere with [`HOLE_DIRECTIONS`]' holes, radius 0.03 each.
fn holed_sphere() -> Mesh {
    let full = sphere(0.5, 256, 100);
    let centres: Vec<DVec3> = HOLE_DIRECTIONS
        .iter()
        .map(|d| 0.5 * DVec3::from_array(*d).normalize())
        .collect();
    let at = |i: u32| full.positions[i as usize].as_dvec3();
    let kept: Vec<[u32; 3]> = full
        .triangles()
        .filter(|t| {
            let centroid = (at(t[0]) + at(t[1]) + at(t[2])) / 3.0;
            centres.iter().all(|c| centroid.distance(*c) > 0.03)
        })
        .collect();
    // Keep only the vertices a kept triangle uses, in their old order.
    let mut new_id = vec![u32::MAX; full.positions.len()];
    let mut mesh = Mesh::default();
    for t in &kept {
        for &i in t {
            if new_id[i as usize] == u32::MAX {
                new_id[i as usize] = mesh.positions.len() as u32;
                mesh.positions.push(full.positions[i as usize]);
                mesh.normals.push(full.normals[i as usize]);
            }
        }
    }
    mesh.indices = kept
        .iter()
        .flat_map(|t| t.map(|i| new_id[i as usize]))
        .collect();
    mesh
}

#[cfg(test)]
mod tests {
    use super::any_builtin as builtin;
    use super::*;
    use glam::Vec3;
    use std::collections::HashMap;

    /// Directed edges used once, in neither direction by another face:
    /// (boundary edges, edges used by more than two faces, misoriented).
    fn edge_report(m: &Mesh) -> (usize, usize, usize) {
        let mut uses: HashMap<[u32; 2], Vec<bool>> = HashMap::new();
        for t in m.triangles() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                uses.entry([a.min(b), a.max(b)]).or_default().push(a < b);
            }
        }
        let open = uses.values().filter(|u| u.len() == 1).count();
        let many = uses.values().filter(|u| u.len() > 2).count();
        let misoriented = uses
            .values()
            .filter(|u| u.len() == 2 && u[0] == u[1])
            .count();
        (open, many, misoriented)
    }

    #[test]
    fn dense_builtins_counts_size_and_edges() {
        for (name, vertices, triangles) in [
            ("holed_sphere", 25_264, 50_400),
            ("dense_knot", 49_152, 98_304),
        ] {
            let m = builtin(name).unwrap();
            assert_eq!(m.name, name);
            assert_eq!(
                (m.positions.len(), m.triangle_count()),
                (vertices, triangles),
                "{name}"
            );
            assert_eq!(m.normals.len(), m.positions.len(), "{name}");
            let lo = m.positions.iter().fold(Vec3::INFINITY, |a, p| a.min(*p));
            let hi = m
                .positions
                .iter()
                .fold(Vec3::NEG_INFINITY, |a, p| a.max(*p));
            assert!(
                lo.cmpge(Vec3::splat(-0.5)).all() && hi.cmple(Vec3::splat(0.5)).all(),
                "{name}: {lo} {hi}"
            );
            assert!((hi - lo).max_element() > 0.85, "{name}: {lo} {hi}");
            assert!(((hi + lo) * 0.5).length() < 0.05, "{name}: off centre");
            // Every index in range, and every vertex used.
            let mut used = vec![false; m.positions.len()];
            for &i in &m.indices {
                used[i as usize] = true;
            }
            assert!(used.iter().all(|u| *u), "{name}: unused vertices");
        }
        let (open, many, mis) = edge_report(&builtin("holed_sphere").unwrap());
        assert!(open > 0, "the holed sphere is open");
        assert_eq!((many, mis), (0, 0), "holed sphere: manifold and oriented");
        assert_eq!(edge_report(&builtin("dense_knot").unwrap()), (0, 0, 0));
    }

    #[test]
    fn every_hole_is_a_few_dozen_triangles() {
        let full = sphere(0.5, 256, 100);
        let holed = builtin("holed_sphere").unwrap();
        let removed = full.triangle_count() - holed.triangle_count();
        let per_hole = removed / HOLE_DIRECTIONS.len();
        assert!((20..=100).contains(&per_hole), "{removed} removed");
        // Each hole removed something: no triangle centroid near a centre.
        for d in HOLE_DIRECTIONS {
            let c = 0.5 * DVec3::from_array(d).normalize();
            let near = holed.triangles().any(|t| {
                let [a, b, cc] = t.map(|i| holed.positions[i as usize].as_dvec3());
                ((a + b + cc) / 3.0).distance(c) <= 0.03
            });
            assert!(!near, "hole at {d:?} not punched");
        }
    }
}

#[cfg(test)]
mod names {
    #[test]
    fn unknown_builtin_lists_every_known_name() {
        let e = super::any_builtin("teapot").unwrap_err().to_string();
        let all = crate::scene::mesh::BUILTIN_NAMES
            .iter()
            .chain(&super::DENSE_BUILTIN_NAMES);
        for name in all {
            assert!(e.contains(name), "{e}");
        }
    }
}
