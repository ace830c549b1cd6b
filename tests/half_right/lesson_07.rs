//! Lesson 07's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_07/exercises.rs`; built with `--features chapter_copies`.

use common::glam::{DVec3, Mat4, Vec4};

use crate::lesson_07::infinite_far::INFINITE_EPSILON;

// ANCHOR: infinite_frustum
/// Exercise 1: x_ndc = (2n·x/d − (r + l)) / (r − l) at view depth d = −z,
/// so clip x = 2n/(r − l)·x + (r + l)/(r − l)·z with w = −z (y alike); the
/// z row is the finite one's limit as f → ∞, (−1, −n), times (1 − ε).
pub fn infinite_frustum(left: f32, right: f32, bottom: f32, top: f32, near: f32) -> Mat4 {
    let (w, h) = (right - left, top - bottom);
    let k = 1.0 - INFINITE_EPSILON as f32;
    Mat4::from_cols(
        Vec4::new(2.0 * near / w, 0.0, 0.0, 0.0),
        Vec4::new(0.0, 2.0 * near / h, 0.0, 0.0),
        // THE MISTAKE: a centred frustum's third column: an off-centre
        // rectangle's (r + l) / (r - l) and (t + b) / (t - b) are left out.
        Vec4::new(0.0, 0.0, -k, -1.0),
        Vec4::new(0.0, 0.0, -near * k, 0.0),
    )
}
// ANCHOR_END: infinite_frustum

// ANCHOR: adaptive_near
/// Exercise 2: view depth is linear in p, so its minimum over the box is
/// at one of the eight corners.
pub fn adaptive_near(eye: DVec3, forward: DVec3, lo: DVec3, hi: DVec3, near: f64) -> f64 {
    // THE MISTAKE: only the box's two extreme corners, lo and hi, not all
    // eight.
    let nearest = [0, 7]
        .into_iter()
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
