//! Lesson 10's exercises answered with the nearest code the chapter prints
//! (`lesson_10.wgsl` here): `grade --check-copies` must see each fail.

/// `exercise_blocker_search` and `exercise_filter_radius`, as copies.
pub const EXERCISES_WGSL: &str = include_str!("lesson_10.wgsl");
