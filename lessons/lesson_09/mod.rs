//! Lesson 09, cascaded shadow maps: the view frustum split by depth, one
//! fitted, snapped map per slice, all in one depth texture array.

pub mod cascades;

pub mod csm;

pub mod extras;

pub mod setup;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_09.rs`).
#[cfg(not(feature = "solutions"))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_09.rs"]
pub mod exercises;
