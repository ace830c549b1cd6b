//! `common`: everything the workbook has taught once and needs again.
//!
//! - [`gpu`]: adapter and device selection (Vulkan/lavapipe, GL/llvmpipe, real GPUs).
//! - [`scene`]: the TOML scene format of INTERFACES.md, loaded and validated.
//! - [`mesh`]: built-in unit meshes, OBJ loading, welding, validation, adjacency.
//! - [`reference`]: the exact CPU ray-cast reference (BVH, multi-threaded).
//! - [`metrics`]: error of a GPU visibility image against the reference.
//! - [`timing`]: GPU timestamp queries per pass, with a labelled CPU fallback.
//! - [`report`]: `report.json` and the terminal table.
//! - [`render`]: scene upload, frame targets, the shared passes, readback.
//! - [`app`]: the command line, the headless runner and the window runner.

pub mod adjacency;
pub mod app;
pub mod bvh;
pub mod camera;
pub mod cli;
pub mod cube_shadow;
pub mod depth_bounds;
pub mod depth_precision;
pub mod gpu;
pub mod mesh;
pub mod metrics;
pub mod reference;
pub mod render;
pub mod report;
pub mod scene;
pub mod shadow_map;
pub mod shadow_volume;
pub mod timing;
pub mod window;

pub use anyhow::{self, Context, Result};
pub use glam;
pub use wgpu;
