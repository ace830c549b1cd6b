//! Lesson 03, PCF: filters that turn the shadow map into a fractional
//! visibility; [`knobs`]: their kernels' sizes, as the window's widgets and
//! `--knob`.

pub mod pcf;

pub mod lit_pipelines;

pub mod adaptive_count;

pub mod knobs;

pub mod port_cards;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_03.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_03.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_03.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_03.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_03.rs"]
pub mod solutions;
