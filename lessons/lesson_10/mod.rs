//! Lesson 10, soft shadows from area lights: [`soft`], how a variant turns
//! one shadow map into the visible fraction of a light with a size (PCF,
//! PCSS, variance maps, the renderers' defaults); [`light_geometry`], the
//! light as the shader needs it; [`moments`], the variance map's passes;
//! [`min_max`], the map's min/max mip chain that `pcss_min_max` searches,
//! [`casters`], the flat objects its map leaves out, and [`split`], its
//! lit pass in two draws;
//! [`map_sets`], the maps of each size a variant reads; [`peers`], the
//! renderers' ports; [`knobs`], their sizes and taps, as the window's
//! widgets and `--knob`; [`exercise_shaders`], the shader modules, one per
//! exercise, whose PCSS places its taps by the student's footprint.

pub mod casters;
pub mod exercise_shaders;
pub mod knobs;
pub mod light_geometry;
pub mod map_sets;
pub mod min_max;
pub mod moments;
pub mod peers;
pub mod port_cards;
pub mod soft;
pub mod split;

#[cfg(feature = "chapter_copies")]
#[path = "../../tests/chapter_copies/lesson_10.rs"]
pub mod chapter_copies;
/// The chapter's exercises: the starter code a student fills in. A build
/// with `--features solutions` also holds the reference solutions
/// (`solutions/lesson_10.rs`), and CI's `--features chapter_copies` each
/// exercise answered with the nearest code the chapter prints
/// (`tests/chapter_copies/lesson_10.rs`, which `grade --check-copies` must see
/// fail). Which set a run uses: [`crate::exercise_set`]; the lesson calls
/// them through [`crate::exercise!`].
pub mod exercises;
#[cfg(feature = "chapter_copies")]
#[path = "../../tests/half_right/lesson_10.rs"]
pub mod half_right;
#[cfg(feature = "solutions")]
#[path = "../../solutions/lesson_10.rs"]
pub mod solutions;
