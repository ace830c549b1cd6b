//! Lesson 05's exercises: the reference solutions (`--features solutions`).
//! The same items as `lessons/lesson_05/exercises.rs`.

use common::glam::DVec3;

use super::adjacency::Adjacency;
use super::silhouette::{LightDir, SilhouetteEdge};

// ANCHOR: silhouette_edges
/// Exercise 1: the silhouette edges of a caster for one light (object
/// space), each oriented the way its light-facing face runs it.
pub fn silhouette_edges(adj: &Adjacency, light: LightDir) -> Vec<SilhouetteEdge> {
    let facing: Vec<bool> = adj
        .triangles
        .iter()
        .zip(&adj.face_normals)
        .map(|(t, n)| match light {
            LightDir::Point(p) => n.dot(p - adj.positions[t[0] as usize]) > 0.0,
            LightDir::Directional(d) => n.dot(-d) > 0.0,
        })
        .collect();
    let mut out = Vec::new();
    for edge in &adj.edges {
        // +1 per lit face running v[0] → v[1], −1 per lit face running back.
        let sum: i32 = adj
            .faces_of(edge)
            .iter()
            .filter(|f| facing[f.face as usize])
            .map(|f| if f.forward { 1 } else { -1 })
            .sum();
        let [v0, v1] = edge.v;
        let e = if sum > 0 {
            SilhouetteEdge { a: v0, b: v1 }
        } else {
            SilhouetteEdge { a: v1, b: v0 }
        };
        for _ in 0..sum.unsigned_abs() {
            out.push(e);
        }
    }
    out
}
// ANCHOR_END: silhouette_edges

// ANCHOR: volume_can_matter
/// Exercise 2: a caster's volume cannot matter when every point of it is
/// beyond the light's range, or when it lies outside one frustum plane and
/// its extrusion moves away from that plane.
pub fn volume_can_matter(
    center: DVec3,
    radius: f64,
    light: LightDir,
    range: Option<f64>,
    frustum: &[(DVec3, f64)],
) -> bool {
    // The volume's points lie beyond the caster, seen from a point light:
    // no nearer to it than the caster's nearest point.
    if let (LightDir::Point(p), Some(range)) = (light, range) {
        if center.distance(p.as_dvec3()) - radius > range {
            return false;
        }
    }
    for &(n, d) in frustum {
        let farthest_inside = n.dot(center) + d + radius;
        if farthest_inside >= 0.0 {
            continue; // the caster itself reaches this plane's inside
        }
        let moves_away = match light {
            // P = L + t (X − L), t ≥ 1: its distance to the plane is
            // dist(L) + t (dist(X) − dist(L)), falling when dist(X) ≤ dist(L).
            LightDir::Point(p) => n.dot(p.as_dvec3()) + d >= farthest_inside,
            LightDir::Directional(dir) => n.dot(dir.as_dvec3()) <= 0.0,
        };
        if moves_away {
            return false;
        }
    }
    true
}
// ANCHOR_END: volume_can_matter
