//! Lesson 04, cube-map point shadows: six faces, two ways to store depth,
//! and culling what the light cannot see.

pub mod bevy_card;
pub mod costs;
pub mod cross;
pub mod cube_map;
pub mod culling;
pub mod faces;
pub mod peers;
pub mod port_cards;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_04.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_04.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_04.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_04.rs"]
pub mod exercises;
