//! Lesson 03's exercises, the reference solutions
//! (`lessons/lesson_03/exercises.rs` is the starter).

/// `exercise_pcf_kernel(s, radius, gradient)` and
/// `exercise_world_disk(s, world, pixel, radius_m, gradient)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_03.wgsl");
