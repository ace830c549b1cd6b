//! Lesson 05, z-pass stencil shadow volumes: silhouettes, their extrusion
//! to infinity, and counting the volumes in the stencil; [`count_view`]
//! shows that count as a picture, and [`stencil_lesson`] is the frame
//! lessons 05 and 06 draw, with the counts their harnesses report.

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
pub mod stencil_lesson;
pub mod volumes;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_05.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_05.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_05.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_05.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_05.rs"]
pub mod solutions;
