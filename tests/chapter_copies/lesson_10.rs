//! Lesson 10's exercises answered with the nearest code the chapter prints
//! (`lesson_10.wgsl` here): `grade --check-copies` must see each fail.

/// `exercise_off_axis_radius` and `exercise_footprint`, as copies.
pub const EXERCISES_WGSL: &str = include_str!("lesson_10.wgsl");
