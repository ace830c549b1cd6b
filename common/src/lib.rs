//! `common`: the workbook's plumbing, which no chapter teaches. Every
//! technique lives with its lesson, in `lessons/lesson_NN/`.
//!
//! One folder a concern, so that a reader finds (say) the timing protocol
//! without opening the others:
//! - [`run`]: a lesson's `main`, its command line, the [`run::lesson::Lesson`]
//!   trait, the headless runner and the window.
//! - [`gpu`]: adapter and device selection, the scene on the GPU, render
//!   targets, bindings and readback.
//! - [`scene`]: the TOML scene format, meshes (built-in and OBJ), camera and
//!   light matrices, camera paths.
//! - [`reference`](mod@reference): the exact CPU ray-cast reference, its BVH,
//!   and the error metrics against it.
//! - [`measure`]: timing (per pass, the protocol), counters, the no-shadow
//!   baseline and the report.
//! - [`ports`]: the card each port of another renderer's default keeps of
//!   its source (file, commit, lines, constants), which its test checks.

pub mod gpu;
pub mod measure;
pub mod ports;
pub mod reference;
pub mod run;
pub mod scene;

pub use anyhow::{self, Context, Result};
pub use glam;
pub use wgpu;
