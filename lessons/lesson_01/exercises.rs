//! Lesson 01's exercises, the starter code. Exercise 1 is a Rust function,
//! [`fit_light_box`]; exercise 2 a WGSL function, `depth_compare` in
//! `shaders/lesson_01/exercises.wgsl`. Grade them with
//! `cargo run --release --bin grade -- lesson_01`. The reference solutions
//! are `solutions/lesson_01.rs` (`--features solutions`).

use common::glam::{DMat4, DVec3};

// ANCHOR: tight_frustum
/// The camera of exercise 1 (`view_frustum.rs`, shared by the starter,
/// the solution and the copy).
pub use super::view_frustum::CameraFrustum;

/// Exercise 1: fit the directional light's orthographic box to what the
/// camera sees.
///
/// `light_view` is the light's view matrix (world → light view space: the
/// light looks down −z, so points in front of it have negative z).
/// `points` are every vertex of every object (casters and receivers), in
/// origin-relative world space; `camera` is the camera's frustum, whose far
/// plane is not given: it ends where the scene does. Return the box's two
/// corners in light view space, `(min, max)`: the caller builds the
/// projection from them as `orthographic(min.x, max.x, min.y, max.y,
/// -max.z, -min.z)` (left, right, bottom, top, near, far). Every point the
/// camera sees must be inside the box, and in depth every point that can
/// shadow one; the smaller the box's x and y sides, the smaller each of
/// the map's texels.
pub fn fit_light_box(
    light_view: DMat4,
    points: &[DVec3],
    camera: &CameraFrustum,
) -> (DVec3, DVec3) {
    let _ = (light_view, points, camera);
    // TODO: the points' box, cut in x and y to the camera's frustum. This
    // stub is a fixed box, 100 m wide and 500 m deep, whatever the scene.
    (
        DVec3::new(-50.0, -50.0, -500.0),
        DVec3::new(50.0, 50.0, 0.0),
    )
}
// ANCHOR_END: tight_frustum

/// The WGSL of exercise 2: `depth_compare(world)`, with a stub body.
pub const EXERCISES_WGSL: &str = include_str!("../../shaders/lesson_01/exercises.wgsl");
