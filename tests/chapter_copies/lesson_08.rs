//! Chapter 08's exercises answered with the nearest code the chapter
//! prints (`--features chapter_copies`): `grade --check-copies` must see
//! every one fail.

use common::glam::{DMat4, DVec3};

use crate::lesson_08::range_sphere::sphere_depth_bounds;

// ANCHOR: cone_sphere
/// Exercise 1, copied: the chapter's `light_bounds` listing bounds a spot
/// light by its range sphere, centre `position`, radius `range` (the
/// sphere is its data, not a function's: the same in both passes).
pub fn cone_sphere(position: DVec3, direction: DVec3, range: f64, half_angle: f64) -> (DVec3, f64) {
    let _ = (direction, half_angle);
    (position, range) // listing `light_bounds` (range_sphere.rs)
}
// ANCHOR_END: cone_sphere

// ANCHOR: cone_depth_bounds
/// Exercise 2, copied: the range sphere's interval, the chapter's
/// `sphere_depth_bounds` listing: the lesson's own function, called, in
/// both passes of the check.
pub fn cone_depth_bounds(
    proj: DMat4,
    near: f64,
    apex: DVec3,
    axis: DVec3,
    range: f64,
    half_angle: f64,
) -> Option<(f32, f32)> {
    let _ = (axis, half_angle);
    sphere_depth_bounds(proj, near, apex, range) // listing `sphere_depth_bounds`
}
// ANCHOR_END: cone_depth_bounds
