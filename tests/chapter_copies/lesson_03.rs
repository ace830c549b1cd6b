//! Lesson 03's exercises answered with the chapter's own code
//! (`--features chapter_copies`, for `grade --check-copies`): both are WGSL
//! functions, in `lesson_03.wgsl` here, pasted from the chapter's listings
//! and, after its marker line, calling the lesson's own functions.

/// `exercise_pcf_kernel(s, radius, gradient)` and
/// `exercise_world_disk(s, world, pixel, radius_m, gradient)`, to fill in.
pub const EXERCISES_WGSL: &str = include_str!("lesson_03.wgsl");
