//! Lesson 03, PCF: filters that turn the shadow map into a fractional
//! visibility; [`knobs`]: their kernels' sizes, as the window's widgets and
//! `--knob`.

pub mod pcf;

pub mod knobs;

pub mod port_cards;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_03.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_03.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_03.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_03.rs"]
pub mod exercises;
