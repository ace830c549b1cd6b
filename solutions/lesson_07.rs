//! Chapter 07's exercises: the reference solutions (same items as
//! `lessons/lesson_07/exercises.rs`; built with `--features solutions`).

use common::glam::{DVec3, Mat4, Vec4};

use crate::lesson_07::infinite_far::INFINITE_EPSILON;

// ANCHOR: infinite_projection
/// Exercise 1: the finite z row (f/(n − f), n·f/(n − f)) tends to (−1, −n)
/// as f → ∞; times (1 − ε) it puts w = 0 at depth 1 − ε.
pub fn infinite_projection(fov_y_rad: f32, aspect: f32, near: f32) -> Mat4 {
    let h = 1.0 / (0.5 * fov_y_rad).tan();
    let k = 1.0 - INFINITE_EPSILON as f32;
    Mat4::from_cols(
        Vec4::new(h / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, h, 0.0, 0.0),
        Vec4::new(0.0, 0.0, -k, -1.0),
        Vec4::new(0.0, 0.0, -near * k, 0.0),
    )
}
// ANCHOR_END: infinite_projection

// ANCHOR: adaptive_near
/// Exercise 2: view depth is linear in p, so its minimum over the box is
/// at one of the eight corners.
pub fn adaptive_near(eye: DVec3, forward: DVec3, lo: DVec3, hi: DVec3, near: f64) -> f64 {
    let nearest = (0..8)
        .map(|i| {
            let pick = |bit: usize, a: f64, b: f64| if i & bit == 0 { a } else { b };
            let p = DVec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            );
            (p - eye).dot(forward)
        })
        .fold(f64::INFINITY, f64::min);
    (0.99 * nearest).max(near)
}
// ANCHOR_END: adaptive_near
