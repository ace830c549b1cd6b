//! Lesson 02's exercises answered with the chapter's own code
//! (`--features chapter_copies`, for `grade --check-copies`): both are WGSL
//! functions, in `lesson_02.wgsl` here, pasted from the chapter's listings
//! and, after its marker line, calling the lesson's own functions.

/// The WGSL of the exercises: `slope_bias(world, n)` (exercise 1) and
/// `grazing_bias(world, n)` (exercise 2), each with a stub body.
pub const EXERCISES_WGSL: &str = include_str!("lesson_02.wgsl");
