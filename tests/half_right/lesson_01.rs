//! Lesson 01's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_01/exercises.rs`; built with `--features chapter_copies`.

use common::glam::{DMat4, DVec3};

// ANCHOR: tight_frustum
/// The camera of exercise 1 (`view_frustum.rs`, shared by the starter,
/// the solution and the copy).
pub use super::view_frustum::CameraFrustum;

/// Exercise 1, solved: the vertices' light-space box, cut in x and y to
/// the light-space box of the camera's frustum, which ends at the farthest
/// vertex from the camera. Depth stays the vertices': a caster outside the
/// camera's view can still shadow what it sees.
pub fn fit_light_box(
    light_view: DMat4,
    points: &[DVec3],
    camera: &CameraFrustum,
) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    let mut far = f64::NEG_INFINITY;
    for &p in points {
        let v = light_view.transform_point3(p);
        lo = lo.min(v);
        hi = hi.max(v);
        // The view looks down -z: a point's distance along it is -z.
        far = far.max(-camera.view.transform_point3(p).z);
    }
    if far <= camera.near {
        return (lo, hi); // nothing in front of the camera
    }
    // The frustum's eight corners, camera space -> world -> light space.
    let to_light = light_view * camera.view.inverse();
    let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for d in [camera.near, far] {
        let h = d * camera.tan_half_fov_y;
        let w = h * camera.aspect;
        for (x, y) in [(-w, -h), (w, -h), (-w, h), (w, h)] {
            let v = to_light.transform_point3(DVec3::new(x, y, -d));
            a = a.min(v);
            b = b.max(v);
        }
    }
    let (cut_lo, cut_hi) = (lo.max(a), hi.min(b));
    if cut_lo.x >= cut_hi.x || cut_lo.y >= cut_hi.y {
        return (lo, hi); // the camera sees none of the scene
    }
    // THE MISTAKE: depth cut to the camera's frustum too, as x and y are;
    // a caster outside the view (nearer the light) then falls outside the
    // box and its shadow goes missing.
    (cut_lo, cut_hi)
}
// ANCHOR_END: tight_frustum

/// The WGSL of exercise 2: `depth_compare(world)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_01.wgsl");
