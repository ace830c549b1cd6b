//! Lesson 05's exercises answered with the nearest code the book prints
//! (`--features chapter_copies`, for `grade --check-copies`): each must
//! fail its grade, or the chapter hands out the answer.

use common::glam::DVec3;

use super::adjacency::Adjacency;
use super::silhouette::{LightDir, SilhouetteEdge};

/// Exercise 1, copied: every silhouette edge, none left out.
pub fn silhouette_edges_in_view(
    adj: &Adjacency,
    light: LightDir,
    view: &[(DVec3, f64)],
) -> Vec<SilhouetteEdge> {
    let _ = view;
    // Chapter 05's listing `silhouette.rs:silhouette_edges`, called as
    // printed: the call of the lesson's own function, in both passes.
    super::silhouette::silhouette_edges(adj, light)
}

/// Exercise 2, copied: chapter 05 prints no caster test; the nearest is
/// chapter 06's, which skips by the frustum only.
pub fn volume_can_matter(
    center: DVec3,
    radius: f64,
    light: LightDir,
    range: Option<f64>,
    frustum: &[(DVec3, f64)],
) -> bool {
    if common::gpu::render::chapter_copy_calls() {
        // Lesson 05 skips no caster; the lessons' own caster test is
        // chapter 08's `range_sphere.rs:caster_reaches` (it takes the
        // scene: its test, on these arguments).
        let _ = frustum;
        return match (light, range) {
            (LightDir::Point(p), Some(r)) => p.as_dvec3().distance(center) <= r + radius,
            _ => true,
        };
    }
    let _ = range;
    // Chapter 06's listing `plan.rs:plan`, its `outside` test, pasted.
    let outside = |(n, d): &(DVec3, f64)| {
        let s = n.dot(center) + d;
        if s + radius >= 0.0 {
            return false;
        }
        // The extrusion must also move away from the plane.
        match light {
            LightDir::Point(p) => s + radius <= n.dot(p.as_dvec3()) + d,
            LightDir::Directional(dir) => n.dot(dir.as_dvec3()) <= 0.0,
        }
    };
    !frustum.iter().any(outside)
}
