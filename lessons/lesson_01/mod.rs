//! Lesson 01, the depth map: the shadow map and the pass that fills it.

pub mod shadow_map;

pub mod tally;

pub mod exercise_pass;

pub mod view_frustum;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_01.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_01.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_01.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_01.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_01.rs"]
pub mod solutions;
