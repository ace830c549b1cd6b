//! Lesson 08, depth bounds and scissor: the light's range sphere on screen
//! and in depth, and the depth-bounds test emulated with a stencil bit.

pub mod bounds_test;
pub mod costs;
pub mod count_bits;
pub mod exercise_bounds;
pub mod range_sphere;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_08.rs`).
#[cfg(not(feature = "solutions"))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_08.rs"]
pub mod exercises;
