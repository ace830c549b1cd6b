//! Lesson 05, z-pass stencil shadow volumes: silhouettes, their extrusion
//! to infinity, and counting the volumes in the stencil; [`count_view`]
//! shows that count as a picture.

pub mod adjacency;
pub mod compute;
pub mod count_view;
pub mod cull;
pub mod extrusion;
pub mod fit;
pub mod frustum;
pub mod quads;
pub mod silhouette;
pub mod stencil;
pub mod volumes;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_05.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_05.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_05.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_05.rs"]
pub mod exercises;
