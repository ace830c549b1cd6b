//! Lesson 10's exercises, the starter code: both are WGSL functions in
//! `shaders/lesson_10/exercises.wgsl`, appended to the lesson's shader. The
//! variants `exercise_blocker_search` and `exercise_penumbra` run PCSS with
//! one of them in place of the lesson's own, in a shader module without
//! the lesson's own (`exercise_shaders.rs`). With `--features solutions`
//! the build also holds `solutions/lesson_10.rs` and runs it
//! (`WORKBOOK_EXERCISES` picks the set).

/// `exercise_blocker_search(s, radius, angle, gradient)` and
/// `exercise_filter_radius(d_r, d_b)`, to fill in.
pub const EXERCISES_WGSL: &str = include_str!("../../shaders/lesson_10/exercises.wgsl");
