//! Lesson 08, depth bounds and scissor: the light's range sphere on screen
//! and in depth, and the depth-bounds test emulated with a stencil bit.

pub mod bounds_test;
pub mod costs;
pub mod count_bits;
pub mod exercise_bounds;
pub mod range_sphere;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_08.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_08.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_08.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_08.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_08.rs"]
pub mod solutions;
