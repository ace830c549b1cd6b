//! Lesson 09's exercises, the reference solutions: the same items as the
//! starter, `lessons/lesson_09/exercises.rs`.

use common::glam::DVec2;

// ANCHOR: practical_splits
/// Exercise 1, solved: log and uniform, blended by `lambda`.
pub fn practical_splits(near: f64, far: f64, k: usize, lambda: f64) -> Vec<f64> {
    (0..=k)
        .map(|i| {
            let t = i as f64 / k as f64;
            let log = near * (far / near).powf(t);
            let uniform = near + (far - near) * t;
            lambda * log + (1.0 - lambda) * uniform
        })
        .collect()
}
// ANCHOR_END: practical_splits

// ANCHOR: snap_to_texel
/// Exercise 2, solved: floor to the texel grid.
pub fn snap_to_texel(min: DVec2, width: f64, resolution: u32) -> DVec2 {
    let texel = width / resolution as f64;
    (min / texel).floor() * texel
}
// ANCHOR_END: snap_to_texel
