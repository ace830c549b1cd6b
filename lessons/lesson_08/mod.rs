//! Lesson 08, depth bounds and scissor: the light's range sphere on screen
//! and in depth, and the depth-bounds test emulated with a stencil bit.

pub mod bounds_test;
pub mod costs;
pub mod count_bits;
pub mod exercise_bounds;
pub mod range_sphere;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_08.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_08.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_08.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_08.rs"]
pub mod exercises;
