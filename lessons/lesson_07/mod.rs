//! Lesson 07, depth clamp and infinite extrusion: the far plane at
//! infinity, and what each choice costs in depth precision.

pub mod exercise_cameras;
pub mod infinite_far;
pub mod precision_study;
pub mod precision_table;
pub mod reversed_z;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_07.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_07.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_07.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_07.rs"]
pub mod exercises;
