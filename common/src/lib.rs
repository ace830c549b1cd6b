//! `common`: the workbook's plumbing, which no chapter teaches. Every
//! technique lives with its lesson, in `lessons/lesson_NN/`.
//!
//! Running a lesson:
//! - [`app`]: a lesson's `main`: the command line, then headless or the window.
//! - [`cli`]: the command line every lesson shares (INTERFACES.md).
//! - [`lesson`]: the [`lesson::Lesson`] trait and its typed variants.
//! - [`headless`]: the headless runner that writes the outputs of INTERFACES.md.
//! - [`window`]: the interactive window (winit).
//!
//! The GPU and what is drawn:
//! - [`gpu`]: adapter and device selection (Vulkan/lavapipe, GL/llvmpipe, real GPUs).
//! - [`render`]: the scene on the GPU, the shader prelude, the base pass.
//! - [`lit`]: the lit pass that adds one light.
//! - [`bindings`]: bind group layouts and groups (textures, samplers, uniforms).
//! - [`targets`]: the frame's render targets and texture helpers.
//! - [`fullscreen`]: the full-screen triangle (blits, readback, markers).
//! - [`readback`]: buffers, textures and query results back to the CPU.
//!
//! Scenes, meshes and camera math:
//! - [`scene`]: the TOML scene format of INTERFACES.md, loaded and validated.
//! - [`scene_file`]: the scene TOML as written, before validation.
//! - [`limits`]: the magnitudes a scene may have, and numbers in messages.
//! - [`mesh`]: the mesh type, built-in unit meshes, welding, smooth normals.
//! - [`mesh_dense`]: the dense built-ins (`holed_sphere`, `dense_knot`).
//! - [`obj`]: OBJ files, read through tobj and written for `gen_assets`.
//! - [`camera`]: camera and light matrices.
//! - [`camera_path`]: a scene's `[camera_path]` (pan, dolly) and its shimmer.
//!
//! Measurement:
//! - [`reference`](mod@reference): the exact CPU ray-cast reference (multi-threaded).
//! - [`bvh`]: the bounding-volume hierarchy the reference casts against.
//! - [`metrics`]: error of a GPU visibility image against the reference.
//! - [`timing`]: GPU timestamp queries per pass, with a labelled CPU fallback.
//! - [`counters`]: deterministic cost counters (fragments rasterised).
//! - [`depth_probe`]: what a depth format really stores (24-bit unorm or float).
//! - [`baseline`]: the no-shadow baseline frame every lesson is timed against.
//! - [`report`]: `report.json` and the terminal table.

pub mod app;
pub mod baseline;
pub mod bindings;
pub mod bvh;
pub mod camera;
pub mod camera_path;
pub mod cli;
pub mod counters;
pub mod depth_probe;
pub mod fullscreen;
pub mod gpu;
pub mod headless;
pub mod lesson;
pub mod limits;
pub mod lit;
pub mod mesh;
pub mod mesh_dense;
pub mod metrics;
pub mod obj;
pub mod readback;
pub mod reference;
pub mod render;
pub mod report;
pub mod scene;
pub mod scene_file;
pub mod targets;
pub mod timing;
pub mod window;

pub use anyhow::{self, Context, Result};
pub use glam;
pub use wgpu;
