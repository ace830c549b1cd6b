//! Silhouettes (lesson 05): which faces of a caster face the light, the
//! edges between lit and unlit faces, and the light-facing triangles. The
//! sides of a shadow volume are its silhouette edges extruded away from the
//! light; its caps are the light-facing triangles (lesson 06).
//!
//! Everything here works on the mesh *welded by position*
//! ([`Adjacency`]): UV seams and flat-shaded corners duplicate vertices,
//! and a silhouette taken over the unwelded indices would find a false
//! "open" edge along every seam.

use super::adjacency::{validate, Adjacency};
use common::glam::{Mat4, Vec3};
use common::scene::mesh::Mesh;

/// A light, in the mesh's object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightDir {
    /// A point (or spot) light at this position.
    Point(Vec3),
    /// A directional light: the direction the light travels.
    Directional(Vec3),
}

impl LightDir {
    /// Brings a world-space light into object space, given the object's
    /// model matrix (object → world).
    pub fn to_object_space(self, model: Mat4) -> LightDir {
        let world_to_object = model.inverse();
        match self {
            LightDir::Point(p) => LightDir::Point(world_to_object.transform_point3(p)),
            LightDir::Directional(d) => LightDir::Directional(world_to_object.transform_vector3(d)),
        }
    }
}

/// A silhouette edge, oriented like the light-facing face it borders.
/// Seen from outside the volume, the side quad then winds `b → a → a∞ → b∞`
/// counter-clockwise, like the caps (`a → b → b∞ → a∞` winds inward).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SilhouetteEdge {
    pub a: u32,
    pub b: u32,
}

// ANCHOR: face_facing
/// For every face: does it face the light? The test uses the
/// *unnormalised* normal n, so it never divides and never makes a NaN:
///
/// - point light at L: `n · (L − v0) > 0`
/// - directional light travelling along d: `n · (−d) > 0`
///
/// One tie rule for the whole mesh: exactly 0 is *not* facing. So a
/// degenerate face (n = 0) never faces the light, and gives no cap and
/// no silhouette edge.
pub fn face_facing(adj: &Adjacency, light: LightDir) -> Vec<bool> {
    adj.triangles
        .iter()
        .zip(&adj.face_normals)
        .map(|(t, n)| match light {
            LightDir::Point(l) => n.dot(l - adj.positions[t[0] as usize]) > 0.0,
            LightDir::Directional(d) => n.dot(-d) > 0.0,
        })
        .collect()
}
// ANCHOR_END: face_facing

// ANCHOR: silhouette_edges
/// The silhouette edges to extrude into the sides of the shadow volume.
///
/// Each light-facing face contributes its three edges, in its own
/// winding: +1 for each facing face that runs `v[0] → v[1]`, −1 for each
/// that runs back. The edge is emitted |sum| times, oriented by the sign:
/// a manifold edge with one lit face, an open edge whose face is lit, and
/// what is left of a non-manifold edge once opposite lit faces cancel.
/// The result is the boundary of the lit faces, so it is closed loops for
/// any mesh; with caps made of [`light_facing_triangles`] each lit face's
/// volume is closed. (Adding the unlit faces reversed would also be
/// consistent, but doubles every count; we do not.)
pub fn silhouette_edges(adj: &Adjacency, light: LightDir) -> Vec<SilhouetteEdge> {
    silhouette_edges_for(adj, &face_facing(adj, light))
}

/// [`silhouette_edges`] from a `face_facing`
/// result, so one facing test can serve both the sides and the caps.
pub fn silhouette_edges_for(adj: &Adjacency, facing: &[bool]) -> Vec<SilhouetteEdge> {
    let mut out = Vec::new();
    for edge in &adj.edges {
        let sum: i32 = adj
            .faces_of(edge)
            .iter()
            .filter(|f| facing[f.face as usize])
            .map(|f| if f.forward { 1 } else { -1 })
            .sum();
        let [v0, v1] = edge.v;
        let (a, b) = if sum > 0 { (v0, v1) } else { (v1, v0) };
        out.extend(std::iter::repeat_n(
            SilhouetteEdge { a, b },
            sum.unsigned_abs() as usize,
        ));
    }
    out
}
// ANCHOR_END: silhouette_edges

/// The light-facing triangles (welded ids, in their own winding): the
/// front cap, and, extruded to infinity and reversed, the back cap.
pub fn light_facing_triangles(adj: &Adjacency, light: LightDir) -> Vec<[u32; 3]> {
    light_facing_triangles_for(adj, &face_facing(adj, light))
}

/// [`light_facing_triangles`] from a
/// `face_facing` result.
pub fn light_facing_triangles_for(adj: &Adjacency, facing: &[bool]) -> Vec<[u32; 3]> {
    adj.triangles
        .iter()
        .zip(facing)
        .filter(|(_, f)| **f)
        .map(|(t, _)| *t)
        .collect()
}

// ANCHOR: caster_adjacency
/// The adjacency a caster's volumes are built from. A closed, consistently
/// wound mesh casts from its light-facing faces only. An open (or
/// non-manifold, or misoriented) mesh is a two-sided surface: a single quad
/// lit from behind must cast too. It gets each triangle twice, once
/// reversed, so that for any light one copy of every face faces it.
pub fn caster_adjacency(mesh: &Mesh) -> Adjacency {
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
pub fn casts_two_sided(mesh: &Mesh) -> bool {
    let v = validate(mesh);
    !(v.closed && v.misoriented_edges == 0)
}
// ANCHOR_END: caster_adjacency

/// Light `k` as the volumes see it: origin-relative world space. Spot
/// lights cast like point lights (the cone is applied in the lit pass).
/// Finds the scene's origin, a pass over every vertex: per frame, use
/// [`light_relative_to`] with the origin found once.
pub fn world_light(scene: &common::gpu::render::SceneGpu, k: usize) -> LightDir {
    light_relative_to(&scene.scene, scene.scene.origin(), k)
}

/// [`world_light`], relative to `origin` ([`Scene::origin`](common::scene::Scene::origin)).
pub fn light_relative_to(
    scene: &common::scene::Scene,
    o: common::glam::DVec3,
    k: usize,
) -> LightDir {
    match scene.lights[k].kind {
        common::scene::LightKind::Directional { direction } => {
            LightDir::Directional(direction.as_vec3())
        }
        common::scene::LightKind::Point { position, .. }
        | common::scene::LightKind::Spot { position, .. } => {
            LightDir::Point((position - o).as_vec3())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::scene::mesh::builtin;
    use std::collections::HashMap;
    fn from(positions: &[Vec3], indices: &[u32]) -> Adjacency {
        Adjacency::from_triangles(positions, indices)
    }

    /// In-degree minus out-degree at every vertex that is not balanced.
    fn unbalanced(edges: &[SilhouetteEdge]) -> Vec<(u32, i32)> {
        let mut degree: HashMap<u32, i32> = HashMap::new();
        for e in edges {
            *degree.entry(e.a).or_default() -= 1;
            *degree.entry(e.b).or_default() += 1;
        }
        degree.into_iter().filter(|(_, d)| *d != 0).collect()
    }

    fn lights() -> Vec<LightDir> {
        let mut lights = vec![
            LightDir::Point(Vec3::new(0.0, 3.0, 0.0)),
            LightDir::Point(Vec3::new(2.0, 3.0, 1.0)),
            LightDir::Point(Vec3::ZERO), // inside the closed meshes
            LightDir::Point(Vec3::new(0.5, 0.7, 0.5)), // on the cube's face planes
            LightDir::Point(Vec3::new(1e4, -2e4, 3e4)),
            LightDir::Directional(Vec3::new(-0.4, -1.0, -0.3)),
            LightDir::Directional(Vec3::X), // grazing the cube's sides
            LightDir::Directional(Vec3::ZERO), // nothing faces
        ];
        for k in 0..20 {
            let a = k as f32 * 2.399_963; // golden angle
            let d = Vec3::new(a.cos(), (k as f32 / 10.0) - 1.0, a.sin());
            lights.push(LightDir::Directional(d));
            lights.push(LightDir::Point(d * 0.6));
        }
        lights
    }

    #[test]
    fn cube_lit_from_above_has_a_loop_of_four() {
        let cube = builtin("cube").unwrap();
        let adj = Adjacency::new(&cube);
        assert_eq!(adj.positions.len(), 8, "24 cube vertices weld to 8");
        let edges = silhouette_edges(&adj, LightDir::Point(Vec3::new(0.0, 3.0, 0.0)));
        assert_eq!(edges.len(), 4, "{edges:?}");
        // Every vertex appears an even number of times (here: twice).
        let mut seen: HashMap<u32, u32> = HashMap::new();
        for e in &edges {
            *seen.entry(e.a).or_default() += 1;
            *seen.entry(e.b).or_default() += 1;
        }
        assert!(seen.values().all(|n| n % 2 == 0), "{seen:?}");
        // The edges chain a → b → … back to the start.
        let mut at = edges[0].b;
        for _ in 1..4 {
            at = edges.iter().find(|e| e.a == at).expect("a chained edge").b;
        }
        assert_eq!(at, edges[0].a);
        // All on the top face, wound counter-clockwise seen from the light.
        for e in &edges {
            let (a, b) = (adj.positions[e.a as usize], adj.positions[e.b as usize]);
            assert_eq!((a.y, b.y), (0.5, 0.5));
            assert!(a.cross(b).y > 0.0, "{a} → {b} winds clockwise from above");
        }
    }

    #[test]
    fn cube_lit_from_a_corner_has_a_loop_of_six() {
        let adj = Adjacency::new(&builtin("cube").unwrap());
        let edges = silhouette_edges(&adj, LightDir::Point(Vec3::new(2.0, 3.0, 1.0)));
        assert_eq!(edges.len(), 6);
        assert!(unbalanced(&edges).is_empty());
        assert_eq!(
            light_facing_triangles(&adj, LightDir::Point(Vec3::new(2.0, 3.0, 1.0))).len(),
            6
        );
    }

    #[test]
    fn single_quad_casts_only_when_lit() {
        let p = [
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, -1.0),
        ];
        let adj = from(&p, &[0, 1, 2, 0, 2, 3]);
        let lit = silhouette_edges(&adj, LightDir::Directional(Vec3::NEG_Y));
        let mut lit_sorted: Vec<_> = lit.iter().map(|e| (e.a, e.b)).collect();
        lit_sorted.sort();
        // The four rim edges, in the quad's own winding; not the diagonal.
        assert_eq!(lit_sorted, [(0, 1), (1, 2), (2, 3), (3, 0)]);
        assert!(silhouette_edges(&adj, LightDir::Directional(Vec3::Y)).is_empty());
        assert!(silhouette_edges(&adj, LightDir::Point(Vec3::new(0.0, -2.0, 0.0))).is_empty());
        assert_eq!(
            light_facing_triangles(&adj, LightDir::Point(Vec3::new(0.3, 2.0, 0.0))).len(),
            2
        );
    }

    /// Three quads (pages) sharing the spine 0–1 on the Y axis, each page
    /// two triangles. Pages to +X and −X run the spine 0 → 1, the page to
    /// +Z runs it 1 → 0.
    fn book() -> Adjacency {
        let p = [
            Vec3::ZERO,
            Vec3::Y,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(-1.0, 0.0, 0.0),
        ];
        #[rustfmt::skip]
        let indices = [
            0, 1, 2,  0, 2, 3, // +X page, normal −Z, runs 0 → 1
            1, 0, 5,  1, 5, 4, // +Z page, normal −X, runs 1 → 0
            0, 1, 6,  0, 6, 7, // −X page, normal +Z, runs 0 → 1
        ];
        from(&p, &indices)
    }

    fn spine(edges: &[SilhouetteEdge]) -> Vec<(u32, u32)> {
        edges
            .iter()
            .filter(|e| e.a.max(e.b) == 1 && e.a.min(e.b) == 0)
            .map(|e| (e.a, e.b))
            .collect()
    }

    #[test]
    fn nonmanifold_book_sums_its_faces() {
        let adj = book();
        let spine_edge = adj.edges.iter().find(|e| e.v == [0, 1]).unwrap();
        assert_eq!(adj.faces_of(spine_edge).len(), 3);

        // Light from −Z and −X: the +X page (0 → 1) and the +Z page (1 → 0)
        // face it and cancel on the spine; the −X page does not face it.
        let light = LightDir::Point(Vec3::new(-0.5, 0.5, -3.0));
        assert_eq!(
            face_facing(&adj, light),
            [true, true, true, true, false, false]
        );
        let edges = silhouette_edges(&adj, light);
        assert!(spine(&edges).is_empty(), "{edges:?}");
        assert_eq!(edges.len(), 6, "the two lit pages' outer rims: {edges:?}");
        assert!(unbalanced(&edges).is_empty());

        // Light from +X: only the −X page (normal +Z, runs 0 → 1) faces it.
        let light = LightDir::Point(Vec3::new(3.0, 0.5, 0.2));
        assert_eq!(
            face_facing(&adj, light),
            [false, false, false, false, true, true]
        );
        assert_eq!(spine(&silhouette_edges(&adj, light)), [(0, 1)]);

        // Travelling +Z: only the +X page (normal −Z, runs 0 → 1) faces it;
        // the +Z page is edge-on (a tie: not facing).
        let light = LightDir::Directional(Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(
            face_facing(&adj, light),
            [true, true, false, false, false, false]
        );
        assert_eq!(spine(&silhouette_edges(&adj, light)), [(0, 1)]);

        // Travelling −Z and a bit +X: the +Z page (runs 1 → 0) and the −X
        // page (runs 0 → 1) face it and cancel on the spine.
        let light = LightDir::Directional(Vec3::new(0.5, 0.0, -1.0));
        assert_eq!(
            face_facing(&adj, light),
            [false, false, true, true, true, true]
        );
        let edges = silhouette_edges(&adj, light);
        assert!(spine(&edges).is_empty(), "{edges:?}");
        assert!(unbalanced(&edges).is_empty());
    }

    #[test]
    fn misoriented_edge_lit_on_both_sides_counts_twice() {
        // Two lit faces that both run 0 → 1: the edge is a side of both
        // faces' volumes, so it is emitted twice, the same way.
        let p = [
            Vec3::ZERO,
            Vec3::Y,
            Vec3::new(1.0, 0.5, 0.0),
            Vec3::new(-1.0, 0.5, -1.0),
        ];
        let adj = from(&p, &[0, 1, 2, 0, 1, 3]);
        let light = LightDir::Directional(Vec3::new(1.0, 0.0, 0.5));
        assert_eq!(face_facing(&adj, light), [true, true]);
        let edges = silhouette_edges(&adj, light);
        assert_eq!(spine(&edges), [(0, 1), (0, 1)]);
        assert_eq!(edges.len(), 6);
        assert!(unbalanced(&edges).is_empty());
    }

    #[test]
    fn degenerate_faces_give_no_nan_and_no_silhouette() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0, Vec3::Y];
        // A zero-area sliver and a face with a repeated vertex.
        let adj = from(&p, &[0, 1, 2, 0, 0, 3]);
        assert!(adj.face_normals.iter().all(|n| *n == Vec3::ZERO));
        for light in lights() {
            assert_eq!(face_facing(&adj, light), [false, false]);
            assert!(silhouette_edges(&adj, light).is_empty());
            assert!(light_facing_triangles(&adj, light).is_empty());
        }
        // A NaN light is not facing either: comparisons with NaN are false.
        assert_eq!(
            face_facing(&adj, LightDir::Point(Vec3::NAN)),
            [false, false]
        );
        let triangle = from(&[Vec3::ZERO, Vec3::X, Vec3::Z], &[0, 2, 1]);
        assert_eq!(face_facing(&triangle, LightDir::Point(Vec3::NAN)), [false]);
    }

    #[test]
    fn silhouettes_are_balanced_for_every_light() {
        let mut meshes: Vec<(String, Adjacency)> = ["cube", "sphere", "torus", "knot", "plane"]
            .iter()
            .map(|n| (n.to_string(), Adjacency::new(&builtin(n).unwrap())))
            .collect();
        meshes.push(("book".into(), book()));
        for (name, adj) in &meshes {
            for light in lights() {
                let edges = silhouette_edges(adj, light);
                assert!(
                    unbalanced(&edges).is_empty(),
                    "{name}, {light:?}: {:?}",
                    unbalanced(&edges)
                );
            }
        }
    }

    #[test]
    fn silhouettes_follow_the_lit_face() {
        // On a closed mesh, each silhouette edge a → b is run a → b by a
        // lit face, and b → a by an unlit one.
        let adj = Adjacency::new(&builtin("knot").unwrap());
        for light in lights() {
            let facing = face_facing(&adj, light);
            for e in silhouette_edges_for(&adj, &facing) {
                let edge = adj
                    .edges
                    .iter()
                    .find(|x| x.v == [e.a.min(e.b), e.a.max(e.b)])
                    .unwrap();
                for f in adj.faces_of(edge) {
                    let runs_a_to_b = f.forward == (e.a < e.b);
                    assert_eq!(runs_a_to_b, facing[f.face as usize], "{light:?}");
                }
            }
        }
    }

    #[test]
    fn light_moves_into_object_space() {
        let model = Mat4::from_scale_rotation_translation(
            Vec3::splat(2.0),
            glam::Quat::IDENTITY,
            Vec3::new(0.0, 5.0, 0.0),
        );
        let p = LightDir::Point(Vec3::new(0.0, 7.0, 0.0)).to_object_space(model);
        assert_eq!(p, LightDir::Point(Vec3::new(0.0, 1.0, 0.0)));
        let LightDir::Directional(d) = LightDir::Directional(Vec3::NEG_Y).to_object_space(model)
        else {
            panic!()
        };
        assert!(d.normalize().abs_diff_eq(Vec3::NEG_Y, 1e-6));
    }
}
