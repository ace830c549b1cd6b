//! Lesson 04, cube-map point shadows: six faces, two ways to store depth,
//! and culling what the light cannot see.

pub mod bevy_card;
pub mod costs;
pub mod cross;
pub mod cube_map;
pub mod culling;
pub mod face_rects;
pub mod faces;
pub mod footprint;
pub mod peers;
pub mod port_cards;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_04.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_04.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_04.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_04.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_04.rs"]
pub mod solutions;
