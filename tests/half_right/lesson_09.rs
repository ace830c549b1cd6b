//! Lesson 09's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_09/exercises.rs`; built with `--features chapter_copies`.

use common::glam::{DVec2, DVec3};

// ANCHOR: fitted_splits
/// Exercise 1, solved: view depth is linear in p, so over the box it is
/// smallest at a corner; the practical split runs from there.
pub fn fitted_splits(
    eye: DVec3,
    forward: DVec3,
    scene: &[DVec3],
    near: f64,
    far: f64,
    k: usize,
    lambda: f64,
) -> Vec<f64> {
    // THE MISTAKE: the nearest corner's distance from the eye, not its
    // depth along the view: the first split starts too far away.
    let _ = forward;
    let nearest = scene
        .iter()
        .map(|&p| (p - eye).length())
        .fold(f64::INFINITY, f64::min);
    let start = if nearest > near && nearest < far {
        nearest
    } else {
        near
    };
    (0..=k)
        .map(|i| {
            let t = i as f64 / k as f64;
            let log = start * (far / start).powf(t);
            let uniform = start + (far - start) * t;
            match i {
                0 => start,
                _ if i == k => far,
                _ => lambda * log + (1.0 - lambda) * uniform,
            }
        })
        .collect()
}
// ANCHOR_END: fitted_splits

// ANCHOR: snap_tight_box
/// Exercise 2, solved: the width rounded up to a ladder of fixed sizes,
/// four to an octave (a power of 2^(1/4) metres), with a texel to spare;
/// the corner floored to that width's grid.
pub fn snap_tight_box(min: DVec2, max: DVec2, resolution: u32) -> (DVec2, f64) {
    let n = resolution as f64;
    // Flooring the corner moves it down by less than a texel: with one
    // texel to spare, the box still reaches max.
    let need = (max - min).max_element() * n / (n - 1.0);
    // THE MISTAKE: the tight box's own width, snapped to a grid of it: the
    // grid changes with the width every frame.
    let w = need;
    let texel = w / n;
    ((min / texel).floor() * texel, w)
}
// ANCHOR_END: snap_tight_box
