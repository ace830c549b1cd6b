//! Chapter 08's exercises: the starter code. Each function compiles and
//! runs, and gives a wrong answer until you write it (book: chapter 08,
//! "Exercises"; grade with `cargo run --release --bin grade -- lesson_08`).

use common::glam::{DMat4, DVec3};

use crate::lesson_08::range_sphere::Scissor;

// ANCHOR: scissor_rect
/// Exercise 1 (`--variant exercise_scissor_rect`): the pixel rectangle that
/// holds the image of a light's range sphere, centre `centre_view` (view
/// space: the camera at the origin looking down −z) and radius `r`, on a
/// `w × h` target (x right, y down, from the top-left pixel). `proj` is the
/// camera's projection: a view point (x, y, z) lands at NDC
/// (proj.x_axis.x · x / −z, proj.y_axis.y · y / −z), pixels
/// ((ndc_x + 1)/2 · w, (1 − ndc_y)/2 · h). Return `None` when the sphere
/// lies wholly on the camera's side of the near plane (every z > −near)
/// or off screen; the full screen when the camera is inside it. Round
/// outwards, stay on screen. Widen `r` by `r · range_sphere::SPHERE_MARGIN`
/// first, as the lesson does, so rounding never cuts off a sliver.
/// `Scissor { x, y, width, height }` is in pixels: `x, y` the top-left
/// corner, y down (wgpu's `set_scissor_rect`).
///
/// Starter: the full screen for every light (correct, and saves nothing).
pub fn scissor_rect(
    proj: DMat4,
    near: f64,
    centre_view: DVec3,
    r: f64,
    w: u32,
    h: u32,
) -> Option<Scissor> {
    let _ = (proj, near, centre_view, r);
    Some(Scissor::full(w, h))
}
// ANCHOR_END: scissor_rect

// ANCHOR: depth_bounds
/// Exercise 2 (`--variant exercise_depth_bounds`): the window-depth
/// interval (zmin, zmax) of the same sphere, for the emulated depth-bounds
/// test. The sphere spans view distances d = −z from −c.z − r to −c.z + r
/// (never nearer than `near`); window depth is z_clip / w_clip of
/// `proj * (0, 0, −d, 1)`, monotonic in d. Return `None` when the sphere is
/// wholly behind the near plane, else the two depths widened by
/// `range_sphere::DEPTH_MARGIN` (and r by `SPHERE_MARGIN`) and clamped to
/// [0, 1].
///
/// Starter: [0, 1], every stored depth in bounds (correct, saves nothing).
pub fn depth_bounds(proj: DMat4, near: f64, centre_view: DVec3, r: f64) -> Option<(f32, f32)> {
    let _ = (proj, near, centre_view, r);
    Some((0.0, 1.0))
}
// ANCHOR_END: depth_bounds
