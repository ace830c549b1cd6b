//! Lesson 03, PCF: filters that turn the shadow map into a fractional
//! visibility.

pub mod pcf;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_03.rs`).
#[cfg(not(feature = "solutions"))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_03.rs"]
pub mod exercises;
