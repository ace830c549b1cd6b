//! Lesson 04's exercises, the starter code: a face test in Rust
//! ([`faces_touched`], for `exercise_cull_faces`) and a WGSL function in
//! `shaders/lesson_04/exercises.wgsl` (for `exercise_cube_faces`). The
//! lesson's own variants never call them. With `--features solutions` the
//! build also holds `solutions/lesson_04.rs` and runs it
//! (`WORKBOOK_EXERCISES` picks the set).

use common::glam::DVec3;

// ANCHOR: cull_faces
/// Exercise 1: which of the six cube faces, in the order +X, −X, +Y, −Y,
/// +Z, −Z, a caster can touch, tested with its bounding box rather than
/// the lesson's sphere around that box: `centre` is the box's centre
/// relative to the light, `half` its half extents (world axes, each ≥ 0).
/// Face +X sees the directions with x ≥ |y| and x ≥ |z|: four planes
/// through the light, with normals (1, ∓1, 0)/√2 and (1, 0, ∓1)/√2. Drop
/// a face only when the whole box lies outside one of its planes (the
/// box's corner farthest along the normal is behind it); answer `true`
/// when unsure, since a dropped face that the caster reaches loses a
/// shadow.
pub fn faces_touched(centre: DVec3, half: DVec3) -> [bool; 6] {
    // Starter: every face, so nothing is culled (and nothing is wrong).
    let _ = (centre, half);
    [true; 6]
}
// ANCHOR_END: cull_faces

/// `exercise_cube_texel(v)`, to fill in.
pub const EXERCISES_WGSL: &str = include_str!("../../shaders/lesson_04/exercises.wgsl");
