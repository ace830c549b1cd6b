//! Lesson 06, z-fail with caps: counting behind the surface, the caps that
//! close the volumes, a plan that uses z-fail only where it must, and how
//! far to extrude under a finite far plane.

pub mod caps;
pub mod plan;
pub mod reach;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_06.rs`).
#[cfg(not(feature = "solutions"))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_06.rs"]
pub mod exercises;
