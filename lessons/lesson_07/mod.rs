//! Lesson 07, depth clamp and infinite extrusion: the far plane at
//! infinity, and what each choice costs in depth precision.

pub mod exercise_cameras;
pub mod infinite_far;
pub mod precision_study;
pub mod precision_table;
pub mod reversed_z;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_07.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_07.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_07.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_07.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_07.rs"]
pub mod solutions;
