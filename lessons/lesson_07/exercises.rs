//! Chapter 07's exercises: the starter code. Each function compiles and
//! runs, and gives a wrong answer until you write it (book: chapter 07,
//! "Exercises"; grade with `cargo run --release --bin grade -- lesson_07`).

use common::glam::camera::rh::proj::directx::perspective;
use common::glam::{DVec3, Mat4};

// ANCHOR: infinite_frustum
/// Exercise 1 (`--variant exercise_infinite_projection`): the projection
/// of a general, off-centre frustum with its far plane at infinity. The
/// frustum is given by its near-plane rectangle: `left < right` and
/// `bottom < top` are view-space x and y on the plane z = −`near`
/// (`near` > 0), in a right-handed view space looking down −z; the
/// rectangle's corners must land on NDC x, y = ±1. Depth is WebGPU's
/// [0, 1]: 0 at the near plane, and a point at infinity (w = 0) at
/// 1 − ε with ε = `workbook::lesson_07::infinite_far::INFINITE_EPSILON`.
/// The rectangle need not be centred on the view axis (a lens shift, a
/// stereo eye, a screen tile).
///
/// Starter: the symmetric perspective with the rectangle's size, and a
/// finite far plane at 100: the image is centred where the rectangle is
/// not, and the far plane clips the shadow volumes' far ends.
pub fn infinite_frustum(left: f32, right: f32, bottom: f32, top: f32, near: f32) -> Mat4 {
    let fov_y = 2.0 * ((top - bottom) / (2.0 * near)).atan();
    perspective(fov_y, (right - left) / (top - bottom), near, 100.0)
}
// ANCHOR_END: infinite_frustum

// ANCHOR: adaptive_near
/// Exercise 2 (`--variant exercise_adaptive_near`): the largest near
/// distance that clips nothing of the scene. `eye` is the camera position,
/// `forward` its unit view direction, `lo` and `hi` the corners of the
/// scene's bounding box (all in the same space); `near` is the scene file's
/// near distance, the smallest allowed answer. Return the smallest view
/// depth d = (p − eye)·forward over the box, pulled a little towards the
/// camera (d·0.99, say), or `near` when that is not larger (the camera is
/// inside or beside the box). The exercise variant puts it into the
/// lesson's infinite projection (`infinite_perspective`).
///
/// Starter: the scene's own near distance, unchanged.
pub fn adaptive_near(eye: DVec3, forward: DVec3, lo: DVec3, hi: DVec3, near: f64) -> f64 {
    let _ = (eye, forward, lo, hi);
    near
}
// ANCHOR_END: adaptive_near
