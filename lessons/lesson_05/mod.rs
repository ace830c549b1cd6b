//! Lesson 05, z-pass stencil shadow volumes: silhouettes, their extrusion
//! to infinity, and counting the volumes in the stencil.

pub mod adjacency;
pub mod extrusion;
pub mod silhouette;
pub mod stencil;
pub mod volumes;
