//! Lesson 09, cascaded shadow maps: the view frustum split by depth, one
//! fitted, snapped map per slice, all in one depth texture array;
//! [`caster_culling`]: each cascade draws only the casters that can shadow
//! its [`receivers`], where they can; [`pipelines`]: a lit pipeline per
//! cascade count and blend; [`knobs`]: the cascade count and the split's
//! λ, as the window's widgets and `--knob`.

pub mod cascades;

pub mod caster_culling;

pub mod csm;

pub mod extras;

pub mod knobs;

pub mod pipelines;

pub mod receivers;

pub mod setup;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_09.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_09.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_09.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_09.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_09.rs"]
pub mod solutions;
