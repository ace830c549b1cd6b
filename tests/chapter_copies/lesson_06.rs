//! Lesson 06's exercises answered with the nearest code the book prints
//! (`--features chapter_copies`, for `grade --check-copies`): each must
//! fail its grade, or the chapter hands out the answer.

use common::glam::DVec3;

use crate::lesson_05::adjacency::Adjacency;
use crate::lesson_05::silhouette::LightDir;

/// Exercise 1, copied: the lesson's occlusion pyramid and its sphere test,
/// on the sphere around the points.
pub fn needs_zfail(points: &[DVec3], light: LightDir, near_rect: &[DVec3; 4]) -> bool {
    let (lo, hi) = points
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), p| {
            (a.min(*p), b.max(*p))
        });
    let center = (lo + hi) * 0.5;
    let radius = points
        .iter()
        .map(|p| p.distance(center))
        .fold(0.0, f64::max);
    // Chapter 06's listings `plan.rs:plan` (`reaches_near`) and
    // `plan.rs:occlusion_pyramid`, called as printed: the lesson's own
    // functions, in both passes of the check.
    let (point, dir) = match light {
        LightDir::Point(p) => (Some(p.as_dvec3()), None),
        LightDir::Directional(d) => (None, Some(d.as_dvec3())),
    };
    match super::plan::occlusion_pyramid(near_rect, point, dir) {
        Some(planes) => !planes.iter().any(|(n, d)| n.dot(center) + d < -radius),
        None => true,
    }
}

/// Exercise 2, copied: the caps `cpu_volume` builds.
pub fn volume_caps(
    adj: &Adjacency,
    light: LightDir,
    _view: &[(DVec3, f64)],
) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
    // Chapter 06's listing `extrusion.rs:cpu_volume` (from lesson 05), its
    // caps: the lesson's own function, called, in both passes of the check.
    let lit = crate::lesson_05::silhouette::light_facing_triangles(adj, light);
    let back = lit.iter().map(|t| [t[0], t[2], t[1]]).collect();
    (lit, back)
}
