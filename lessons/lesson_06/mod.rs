//! Lesson 06, z-fail with caps: counting behind the surface, the caps that
//! close the volumes, a plan that uses z-fail only where it must, and how
//! far to extrude under a finite far plane.

pub mod caps;
pub mod plan;
pub mod reach;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_06.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_06.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_06.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_06.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_06.rs"]
pub mod solutions;
