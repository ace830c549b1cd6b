//! Lesson 09, cascaded shadow maps: the view frustum split by depth, one
//! fitted, snapped map per slice, all in one depth texture array;
//! [`knobs`]: the cascade count and the split's λ, as the window's widgets
//! and `--knob`.

pub mod cascades;

pub mod csm;

pub mod extras;

pub mod knobs;

pub mod setup;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_09.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_09.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_09.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_09.rs"]
pub mod exercises;
