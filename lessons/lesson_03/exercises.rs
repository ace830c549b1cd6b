//! Lesson 03's exercises, the starter code: both are WGSL functions in
//! `shaders/lesson_03/exercises.wgsl`, appended to the lesson's shader. The
//! variants `exercise_pcf_kernel` and `exercise_world_disk` call them;
//! the lesson's own variants never do. With `--features solutions` the
//! build also holds `solutions/lesson_03.rs` and runs it
//! (`WORKBOOK_EXERCISES` picks the set).

/// `exercise_pcf_kernel(s, radius, gradient)` and
/// `exercise_world_disk(s, world, pixel, radius_m, gradient)`, to fill in.
pub const EXERCISES_WGSL: &str = include_str!("../../shaders/lesson_03/exercises.wgsl");
