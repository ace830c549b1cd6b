//! Lesson 10's exercises, the starter code: both are WGSL functions in
//! `shaders/lesson_10/exercises.wgsl`, appended to the lesson's shader. The
//! variants `exercise_off_axis_radius` and `exercise_elliptic_footprint`
//! run PCSS with its search and filter disks from one of them, in a shader
//! module whose `pcss` calls it (`exercise_shaders.rs`). With `--features
//! solutions` the build also holds `solutions/lesson_10.rs` and runs it
//! (`WORKBOOK_EXERCISES` picks the set).

/// `exercise_off_axis_radius(s, d_r, d_b)` and
/// `exercise_footprint(s, d_r, d_b)`, to fill in.
pub const EXERCISES_WGSL: &str = include_str!("../../shaders/lesson_10/exercises.wgsl");
