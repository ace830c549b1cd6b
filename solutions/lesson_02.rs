//! Lesson 02's exercises, the reference solutions (`solutions/lesson_02.wgsl`):
//! the same items as the starter, `lessons/lesson_02/exercises.rs`.

/// The WGSL of the exercises: `slope_bias(world, n)` (exercise 1) and
/// `grazing_bias(world, n)` (exercise 2), solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_02.wgsl");
