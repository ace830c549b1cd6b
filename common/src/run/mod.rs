//! Running a lesson.
//!
//! - [`app`]: a lesson's `main`: the command line, then headless or the window.
//! - [`cli`]: the command line every lesson shares (appendix "Interfaces").
//! - [`lesson`]: the [`lesson::Lesson`] trait, a lesson's technique, and its
//!   typed variants.
//! - [`instruments`]: the [`instruments::Instruments`] trait, what a lesson
//!   measures and shows besides its image (a lesson's `harness.rs`).
//! - [`per_variant`]: one value per variant, indexed by the variant.
//! - [`knobs`]: a technique's parameters, set by the window's widgets and `--knob`.
//! - [`headless`]: the headless runner and its outputs (appendix "Interfaces").
//! - [`files`]: its PNGs and `report.json`, written.
//! - [`camera_walk`]: its frames along a scene's camera path (shimmer).
//! - [`jittered`]: its `--fragile` frames, the camera, maps and lights moved.
//! - [`times_only`]: its `--times-only` runs, the times and nothing else.
//! - [`view`]: what the window shows (frame, visibility, diff, buffer).
//! - [`window`]: the interactive window (winit), a workbench.
//! - [`display`]: a private Xvfb for the window's tests and screenshots.
//! - [`runner`]: a lesson binary run from outside, headless, and its
//!   report read back (the book's generator, the grader and the tests).
//! - [`web`]: a lesson in a web page (the web build): the window on its canvas.

pub mod app;
pub mod camera_walk;
pub mod cli;
pub mod display;
pub mod files;
pub mod headless;
pub mod instruments;
pub mod jittered;
pub mod knobs;
pub mod lesson;
pub mod per_variant;
#[cfg(not(target_arch = "wasm32"))]
pub mod runner;
pub mod times_only;
pub mod view;
#[cfg(target_arch = "wasm32")]
pub mod web;
pub mod window;
