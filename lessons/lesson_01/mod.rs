//! Lesson 01, the depth map: the shadow map and the pass that fills it.

pub mod shadow_map;

pub mod tally;

pub mod exercise_pass;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_01.rs`).
#[cfg(not(feature = "solutions"))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_01.rs"]
pub mod exercises;
