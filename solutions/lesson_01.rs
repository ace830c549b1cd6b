//! Lesson 01's exercises, the reference solutions: the same items as the
//! starter, `lessons/lesson_01/exercises.rs` (and `solutions/lesson_01.wgsl`).

use common::glam::{DMat4, DVec3};

// ANCHOR: tight_frustum
/// Exercise 1, solved: the light-space bounds of every vertex.
pub fn fit_light_box(light_view: DMat4, points: &[DVec3]) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for &p in points {
        let v = light_view.transform_point3(p);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (lo, hi)
}
// ANCHOR_END: tight_frustum

/// The WGSL of exercise 2: `depth_compare(world)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_01.wgsl");
