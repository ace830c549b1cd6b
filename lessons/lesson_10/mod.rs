//! Lesson 10, soft shadows from area lights: [`soft`], how a variant turns
//! one shadow map into the visible fraction of a light with a size (PCF,
//! PCSS, variance maps, the renderers' defaults); [`moments`], the variance
//! map's passes; [`knobs`], their sizes and taps, as the window's widgets
//! and `--knob`; [`exercise_shaders`], the shader modules, one per exercise
//! without the lesson's function it asks for.

pub mod exercise_shaders;
pub mod knobs;
pub mod light_geometry;
pub mod moments;
pub mod peers;
pub mod port_cards;
pub mod soft;

/// The chapter's exercises: the starter code a student fills in, or with
/// `--features solutions`, the reference solutions (`solutions/lesson_10.rs`).
#[cfg(not(any(feature = "solutions", feature = "chapter_copies")))]
pub mod exercises;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_10.rs"]
pub mod exercises;
/// With `--features chapter_copies` (CI only): each exercise answered with
/// the nearest code the chapter prints, which the grade must fail
/// (`tests/chapter_copies/lesson_10.rs`, `grade --check-copies`).
#[cfg(all(feature = "chapter_copies", not(feature = "solutions")))]
#[path = "../../tests/chapter_copies/lesson_10.rs"]
pub mod exercises;
