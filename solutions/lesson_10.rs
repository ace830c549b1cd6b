//! Lesson 10's exercises, the reference solutions
//! (`lessons/lesson_10/exercises.rs` is the starter).

/// `exercise_blocker_search(s, radius, angle, gradient)` and
/// `exercise_filter_radius(d_r, d_b)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_10.wgsl");
