//! Lesson 05's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_05/exercises.rs`; built with `--features chapter_copies`.

use common::glam::DVec3;

use super::adjacency::Adjacency;
use super::silhouette::{silhouette_edges, LightDir, SilhouetteEdge};

// ANCHOR: edges_in_view
/// Exercise 1: the lesson's silhouette, less the edges whose quad lies
/// wholly outside one frustum plane. The quad's finite corners are `a`
/// and `b`; its corners at infinity are the homogeneous points
/// `(a − L, 0)`, `(b − L, 0)` (point light) or `(d, 0)` (directional),
/// whose value for the plane is `n · (a − L)`, `n · (b − L)` or `n · d`.
pub fn silhouette_edges_in_view(
    adj: &Adjacency,
    light: LightDir,
    view: &[(DVec3, f64)],
) -> Vec<SilhouetteEdge> {
    let p = |i: u32| adj.positions[i as usize].as_dvec3();
    let quad_outside = |e: &SilhouetteEdge, &(n, d): &(DVec3, f64)| {
        let (a, b) = (p(e.a), p(e.b));
        let finite_out = n.dot(a) + d < 0.0 && n.dot(b) + d < 0.0;
        let infinite_out = match light {
            LightDir::Point(l) => {
                let l = l.as_dvec3();
                n.dot(a - l) <= 0.0 && n.dot(b - l) <= 0.0
            }
            LightDir::Directional(dir) => n.dot(dir.as_dvec3()) <= 0.0,
        };
        // THE MISTAKE: only the edge's own ends tested; the quad's corners at
        // infinity can come back into the view.
        let _ = infinite_out;
        finite_out
    };
    silhouette_edges(adj, light)
        .into_iter()
        .filter(|e| !view.iter().any(|plane| quad_outside(e, plane)))
        .collect()
}
// ANCHOR_END: edges_in_view

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
        // THE MISTAKE: the caster's centre against the range, its radius
        // forgotten: a caster whose sphere reaches inside is skipped.
        if center.distance(p.as_dvec3()) > range {
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
        // THE MISTAKE: skipped whichever way its volume extrudes, as if the
        // volume were the caster.
        let _ = moves_away;
        return false;
    }
    true
}
// ANCHOR_END: volume_can_matter
