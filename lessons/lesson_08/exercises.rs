//! Chapter 08's exercises: the starter code. Each function compiles and
//! runs, and gives a wrong answer until you write it (book: chapter 08,
//! "Exercises"; grade with `cargo run --release --bin grade -- lesson_08`).

use common::glam::{DMat4, DVec3};

// ANCHOR: cone_sphere
/// Exercise 1 (`--variant exercise_scissor_rect`): the smallest sphere
/// that holds a spot light's lit cone, as `(centre, radius)`. The cone has
/// its apex at the light's `position`, its axis along the unit `direction`,
/// the half angle `half_angle` (radians, below 90°), and ends at distance
/// `range` from the apex: every lit point p has |p − position| ≤ range and
/// an angle to the axis ≤ half_angle. The exercise variant scissors each
/// spot light's volumes to this sphere's rectangle (the lesson's
/// `sphere_scissor`) instead of the range sphere's.
///
/// Starter: the range sphere itself (correct, and no tighter than the
/// lesson's `scissor` variant).
pub fn cone_sphere(position: DVec3, direction: DVec3, range: f64, half_angle: f64) -> (DVec3, f64) {
    let _ = (direction, half_angle);
    (position, range)
}
// ANCHOR_END: cone_sphere

// ANCHOR: cone_depth_bounds
/// Exercise 2 (`--variant exercise_depth_bounds`): the window-depth
/// interval (zmin, zmax) of a spot light's lit cone, for the emulated
/// depth-bounds test. `apex` (view space: the camera at the origin looking
/// down −z) is the light's position, `axis` the unit cone axis in view
/// space, `half_angle` (radians, below 90°) and `range` as in exercise 1.
/// View distance is d = −z; window depth is z_clip / w_clip of
/// `proj * (0, 0, −d, 1)`, monotonic in d. Return `None` when the cone
/// lies wholly on the camera's side of the near plane (every d ≤ `near`),
/// else the depths of its nearest and farthest view distance (the nearest
/// no nearer than `near`), widened by `range_sphere::DEPTH_MARGIN` (and
/// `range` by `range_sphere::SPHERE_MARGIN`), clamped to [0, 1].
///
/// Starter: the range sphere's interval, the lesson's
/// `sphere_depth_bounds` (correct, and no tighter than the lesson's
/// `depth_bounds` variant).
pub fn cone_depth_bounds(
    proj: DMat4,
    near: f64,
    apex: DVec3,
    axis: DVec3,
    range: f64,
    half_angle: f64,
) -> Option<(f32, f32)> {
    let _ = (axis, half_angle);
    crate::lesson_08::range_sphere::sphere_depth_bounds(proj, near, apex, range)
}
// ANCHOR_END: cone_depth_bounds
