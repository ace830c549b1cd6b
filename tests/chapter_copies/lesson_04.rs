//! Lesson 04's exercises, the starter code: a face test in Rust
//! ([`faces_touched`], for `exercise_cull_faces`) and a WGSL function in
//! `shaders/lesson_04/exercises.wgsl` (for `exercise_cube_depth`). The
//! lesson's own variants never call them. With `--features solutions` the
//! build reads `solutions/lesson_04.rs` instead.

use common::glam::DVec3;

// ANCHOR: cull_faces
/// Exercise 1: which of the six cube faces, in the order +X, −X, +Y, −Y,
/// +Z, −Z, a caster's bounding sphere can touch, `centre` relative to the
/// light. Face +X sees the directions with x ≥ |y| and x ≥ |z|: its frustum
/// is bounded by four planes through the light with normals
/// (1, −1, 0)/√2, (1, 1, 0)/√2, (1, 0, −1)/√2, (1, 0, 1)/√2. The sphere
/// touches the face when its signed distance to each of the four planes is
/// more than −radius; the other faces likewise with their own axis.
pub fn faces_touched(centre: DVec3, radius: f64) -> [bool; 6] {
    // Starter: every face, so nothing is culled (and nothing is wrong).
    let _ = (centre, radius);
    [true; 6]
}
// ANCHOR_END: cull_faces

/// `exercise_cube_depth(v, d, near, far)`, to fill in.
pub const EXERCISES_WGSL: &str = include_str!("lesson_04.wgsl");
