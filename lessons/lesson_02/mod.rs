//! Lesson 02, bias: receiver-side bias in the lit pass, slope-scaled bias
//! in the shadow pass; [`knobs`]: their sizes, as the window's widgets and
//! `--knob`.

pub mod bias;

pub mod knobs;

pub mod port_cards;

pub mod exercise_pass;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_02.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_02.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_02.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_02.rs"]
pub mod exercises;
