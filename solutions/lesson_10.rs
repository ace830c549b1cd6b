//! Lesson 10's exercises, the reference solutions
//! (`lessons/lesson_10/exercises.rs` is the starter).

/// `exercise_off_axis_radius(s, d_r, d_b)` and
/// `exercise_footprint(s, d_r, d_b)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_10.wgsl");
