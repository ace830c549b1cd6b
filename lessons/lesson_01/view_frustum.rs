//! The camera of lesson 01's exercise 1, as the student's `fit_light_box`
//! receives it: one type for the starter, the solution and the chapter
//! copy, which the exercises module swaps (`exercises.rs`).

use common::glam::DMat4;

// ANCHOR: camera_frustum
/// The camera of exercise 1, in origin-relative world space.
#[derive(Clone, Copy, Debug)]
pub struct CameraFrustum {
    /// World → camera view space (the camera looks down −z).
    pub view: DMat4,
    /// tan(fov_y / 2): at view distance d the image is 2·d·tan_half_fov_y tall.
    pub tan_half_fov_y: f64,
    /// Width / height of the image.
    pub aspect: f64,
    /// The near plane's distance. The far plane is left to you.
    pub near: f64,
}
// ANCHOR_END: camera_frustum
