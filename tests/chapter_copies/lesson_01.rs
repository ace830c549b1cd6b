//! Lesson 01's exercises answered with the nearest code the chapter
//! prints (`--features chapter_copies`): `grade --check-copies` must see
//! each one fail. The same items as `lessons/lesson_01/exercises.rs`.

use common::glam::{DMat4, DVec3};

// ANCHOR: tight_frustum
/// The camera of exercise 1 (`view_frustum.rs`, shared by the starter,
/// the solution and the copy).
pub use super::view_frustum::CameraFrustum;

/// Exercise 1: fit the directional light's orthographic box to what the
/// camera sees.
///
/// `light_view` is the light's view matrix (world → light view space: the
/// light looks down −z, so points in front of it have negative z).
/// `points` are every vertex of every object (casters and receivers), in
/// origin-relative world space; `camera` is the camera's frustum, whose far
/// plane is not given: it ends where the scene does. Return the box's two
/// corners in light view space, `(min, max)`: the caller builds the
/// projection from them as `orthographic(min.x, max.x, min.y, max.y,
/// -max.z, -min.z)` (left, right, bottom, top, near, far). Every point the
/// camera sees must be inside the box, and in depth every point that can
/// shadow one; the smaller the box's x and y sides, the smaller each of
/// the map's texels.
pub fn fit_light_box(
    light_view: DMat4,
    points: &[DVec3],
    camera: &CameraFrustum,
) -> (DVec3, DVec3) {
    let _ = camera;
    if common::gpu::render::chapter_copy_calls() {
        // Calls the nearest function a lesson has: chapter 09's
        // `cascades.rs:fit_aabb`, the light-space box around the points.
        let b = crate::lesson_09::cascades::fit_aabb(light_view, points);
        return (b.min, b.max);
    }
    // Copies the chapter's `light_view_proj` listing: the eight corners of
    // the scene's bounding box, seen from the light.
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &p in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for i in 0..8 {
        let corner = DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let v = light_view.transform_point3(corner);
        a = a.min(v);
        b = b.max(v);
    }
    (a, b)
}
// ANCHOR_END: tight_frustum

/// The WGSL of exercise 2: `depth_compare(world)`, with a stub body.
pub const EXERCISES_WGSL: &str = include_str!("lesson_01.wgsl");
