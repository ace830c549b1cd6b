//! Chapter 07's exercises answered with the nearest code the chapter
//! prints (`--features chapter_copies`): `grade --check-copies` must see
//! every one fail.

use common::glam::{DVec3, Mat4};

use crate::lesson_07::infinite_far::{infinite_perspective, INFINITE_EPSILON};

// ANCHOR: infinite_frustum
/// Exercise 1, copied: the chapter's `infinite_perspective` listing, with
/// the field of view and aspect the rectangle implies: the lesson's own
/// function, called, in both passes of the check.
pub fn infinite_frustum(left: f32, right: f32, bottom: f32, top: f32, near: f32) -> Mat4 {
    let (w, h, n) = ((right - left) as f64, (top - bottom) as f64, near as f64);
    let fov_y = 2.0 * (h / (2.0 * n)).atan();
    infinite_perspective(fov_y, w / h, n, INFINITE_EPSILON).as_mat4() // listing `infinite_perspective`
}
// ANCHOR_END: infinite_frustum

// ANCHOR: adaptive_near
/// Exercise 2, copied: the chapter prints no fitted near plane; its
/// `infinite_camera` listing keeps the scene file's near distance (no
/// function computes one: the same answer in both passes of the check).
pub fn adaptive_near(eye: DVec3, forward: DVec3, lo: DVec3, hi: DVec3, near: f64) -> f64 {
    let _ = (eye, forward, lo, hi);
    near // listing `infinite_camera` (infinite_far.rs)
}
// ANCHOR_END: adaptive_near
