//! Chapter 07's exercises answered with the nearest code the chapter
//! prints (`--features chapter_copies`): `grade --check-copies` must see
//! every one fail.

use common::glam::{DVec3, Mat4};

use crate::lesson_07::infinite_far::{infinite_perspective, INFINITE_EPSILON};

// ANCHOR: infinite_projection
/// Exercise 1, copied: the chapter's `infinite_perspective` listing.
pub fn infinite_projection(fov_y_rad: f32, aspect: f32, near: f32) -> Mat4 {
    let (fov, aspect, near) = (fov_y_rad as f64, aspect as f64, near as f64);
    infinite_perspective(fov, aspect, near, INFINITE_EPSILON).as_mat4() // listing `infinite_perspective`
}
// ANCHOR_END: infinite_projection

// ANCHOR: adaptive_near
/// Exercise 2, copied: the chapter prints no fitted near plane; its
/// `infinite_camera` listing keeps the scene file's near distance.
pub fn adaptive_near(eye: DVec3, forward: DVec3, lo: DVec3, hi: DVec3, near: f64) -> f64 {
    let _ = (eye, forward, lo, hi);
    near // listing `infinite_camera` (infinite_far.rs)
}
// ANCHOR_END: adaptive_near
