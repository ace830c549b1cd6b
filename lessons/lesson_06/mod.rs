//! Lesson 06, z-fail with caps: counting behind the surface, the caps that
//! close the volumes, a plan that uses z-fail only where it must, and how
//! far to extrude under a finite far plane.

pub mod caps;
pub mod plan;
pub mod reach;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_06.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_06.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_06.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_06.rs"]
pub mod exercises;
