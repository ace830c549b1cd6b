//! What the diagrams' tests compare them with: the cube of
//! `scenes/lesson_05.toml` and its silhouette, computed here from the
//! scene's mesh and light alone, in `f64`, without lesson 05's adjacency,
//! facing or silhouette code (which the drawings use).

use std::collections::BTreeMap;

use common::glam::DVec3;
use common::scene::{LightKind, Scene};

/// The default scene, as the drawings load it.
pub(super) fn scene() -> Scene {
    let root = &crate::repo_root();
    Scene::load(&root.join("scenes/lesson_05.toml")).expect("scenes/lesson_05.toml")
}

/// The scene's point light (world space).
pub(super) fn point_light(scene: &Scene) -> DVec3 {
    scene
        .lights
        .iter()
        .find_map(|l| match l.kind {
            LightKind::Point { position, .. } => Some(position),
            _ => None,
        })
        .expect("a point light")
}

/// The scene's directional light's direction of travel.
pub(super) fn direction(scene: &Scene) -> DVec3 {
    scene
        .lights
        .iter()
        .find_map(|l| match l.kind {
            LightKind::Directional { direction } => Some(direction),
            _ => None,
        })
        .expect("a directional light")
}

/// The cube's triangles in world space.
pub(super) fn cube_triangles(scene: &Scene) -> Vec<[DVec3; 3]> {
    let cube = scene.objects.iter().find(|o| o.mesh_name == "cube");
    let cube = cube.expect("a cube");
    let p = |i: u32| {
        cube.model
            .transform_point3(cube.mesh.positions[i as usize].as_dvec3())
    };
    cube.mesh
        .indices
        .chunks_exact(3)
        .map(|t| [p(t[0]), p(t[1]), p(t[2])])
        .collect()
}

/// Does the triangle face a point light at `l`: its normal, by its
/// winding, points to the light's side of its plane?
pub(super) fn faces_point(t: &[DVec3; 3], l: DVec3) -> bool {
    (t[1] - t[0]).cross(t[2] - t[0]).dot(l - t[0]) > 0.0
}

/// A position as a key, to weld the mesh's duplicated vertices.
fn key(p: DVec3) -> [i64; 3] {
    (p * 1e5).round().as_i64vec3().to_array()
}

/// An edge by its ends' keys, lower first: its ends, and whether each
/// triangle along it is lit.
type Edges = BTreeMap<([i64; 3], [i64; 3]), (DVec3, DVec3, Vec<bool>)>;

/// The edges between a lit and an unlit triangle of a closed mesh, each
/// as its two end points (in no particular order).
pub(super) fn silhouette(tris: &[[DVec3; 3]], lit: &[bool]) -> Vec<(DVec3, DVec3)> {
    let mut edges = Edges::new();
    for (t, &l) in tris.iter().zip(lit) {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let id = if key(a) < key(b) {
                (key(a), key(b))
            } else {
                (key(b), key(a))
            };
            edges.entry(id).or_insert((a, b, Vec::new())).2.push(l);
        }
    }
    edges
        .into_values()
        .inspect(|(_, _, faces)| assert_eq!(faces.len(), 2, "the cube is closed"))
        .filter(|(_, _, faces)| faces[0] != faces[1])
        .map(|(a, b, _)| (a, b))
        .collect()
}

/// Two points of the page, equal to two hundredths of a pixel (the SVG prints two decimals).
pub(super) fn near(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() < 0.02 && (a.1 - b.1).abs() < 0.02
}

/// The points of a `points="x,y x,y …"` attribute.
pub(super) fn points(attr: &str) -> Vec<(f64, f64)> {
    attr.split_whitespace()
        .map(|xy| {
            let (x, y) = xy.split_once(',').expect("x,y");
            (x.parse().expect("x"), y.parse().expect("y"))
        })
        .collect()
}
