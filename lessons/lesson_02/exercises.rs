//! Lesson 02's exercises, the starter code: both are WGSL functions, in
//! `shaders/lesson_02/exercises.wgsl` (`slope_bias`, `grazing_bias`). Edit
//! them there, then run `cargo run --release --bin grade -- lesson_02`.
//! The reference solutions are `solutions/lesson_02.rs` (`--features solutions`).

/// The WGSL of the exercises: `slope_bias(world, n)` (exercise 1) and
/// `grazing_bias(world, n)` (exercise 2), each with a stub body.
pub const EXERCISES_WGSL: &str = include_str!("../../shaders/lesson_02/exercises.wgsl");
