//! Lesson 02, bias: receiver-side bias in the lit pass, slope-scaled bias
//! in the shadow pass.

pub mod bias;

pub mod exercise_pass;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_02.rs`).
#[cfg(not(feature = "solutions"))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_02.rs"]
pub mod exercises;
