//! Lesson 07, depth clamp and infinite extrusion: the far plane at
//! infinity, and what each choice costs in depth precision.

pub mod exercise_cameras;
pub mod infinite_far;
pub mod precision_study;
pub mod precision_table;
pub mod reversed_z;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_07.rs`).
#[cfg(not(feature = "solutions"))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_07.rs"]
pub mod exercises;
