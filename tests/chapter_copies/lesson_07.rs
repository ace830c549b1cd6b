//! Chapter 07's exercises: the starter code. Each function compiles and
//! runs, and gives a wrong answer until you write it (book: chapter 07,
//! "Exercises"; grade with `cargo run --release --bin grade -- lesson_07`).

use common::glam::camera::rh::proj::directx::perspective;
use common::glam::{DVec3, Mat4};

// ANCHOR: infinite_projection
/// Exercise 1 (`--variant exercise_infinite_projection`): the right-handed
/// perspective projection for WebGPU's [0, 1] depth with the far plane at
/// infinity. Take the finite matrix's z row, let far → ∞, and scale it by
/// (1 − ε) with ε = `workbook::lesson_07::infinite_far::INFINITE_EPSILON`,
/// so a point at infinity (w = 0) lands at depth 1 − ε, inside the clip
/// volume. `fov_y_rad` is the vertical field of view in radians, `aspect`
/// width / height, `near` the near distance (> 0).
///
/// Starter: a finite far plane at 100, which clips the shadow volumes'
/// far ends (the back caps at infinity).
pub fn infinite_projection(fov_y_rad: f32, aspect: f32, near: f32) -> Mat4 {
    perspective(fov_y_rad, aspect, near, 100.0)
}
// ANCHOR_END: infinite_projection

// ANCHOR: adaptive_near
/// Exercise 2 (`--variant exercise_adaptive_near`): the largest near
/// distance that clips nothing of the scene. `eye` is the camera position,
/// `forward` its unit view direction, `lo` and `hi` the corners of the
/// scene's bounding box (all in the same space); `near` is the scene file's
/// near distance, the smallest allowed answer. Return the smallest view
/// depth d = (p − eye)·forward over the box, pulled a little towards the
/// camera (d·0.99, say), or `near` when that is not larger (the camera is
/// inside or beside the box). The exercise variant puts it into the
/// infinite projection of exercise 1's lesson (`infinite_perspective`).
///
/// Starter: the scene's own near distance, unchanged.
pub fn adaptive_near(eye: DVec3, forward: DVec3, lo: DVec3, hi: DVec3, near: f64) -> f64 {
    let _ = (eye, forward, lo, hi);
    near
}
// ANCHOR_END: adaptive_near
