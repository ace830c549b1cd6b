//! Lesson 09's exercises, the reference solutions: the same items as the
//! starter, `lessons/lesson_09/exercises.rs`.

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
    let nearest = scene
        .iter()
        .map(|&p| (p - eye).dot(forward))
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

// ANCHOR: snap_to_texel
/// Exercise 2, solved: floor to the texel grid.
pub fn snap_to_texel(min: DVec2, width: f64, resolution: u32) -> DVec2 {
    let texel = width / resolution as f64;
    (min / texel).floor() * texel
}
// ANCHOR_END: snap_to_texel
