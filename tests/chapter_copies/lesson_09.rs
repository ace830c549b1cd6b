//! Lesson 09's exercises answered with the nearest code the chapter
//! prints (`--features chapter_copies`): `grade --check-copies` must see
//! every one fail.

use common::glam::{DVec2, DVec3};

use crate::lesson_09::cascades::{split_depths, SplitScheme};

// ANCHOR: fitted_splits
/// Exercise 1, copied: the lesson's practical split from the near plane.
pub fn fitted_splits(
    eye: DVec3,
    forward: DVec3,
    scene: &[DVec3],
    near: f64,
    far: f64,
    k: usize,
    lambda: f64,
) -> Vec<f64> {
    let _ = (eye, forward, scene);
    split_depths(SplitScheme::Practical { lambda }, near, far, k) // listing `splits`
}
// ANCHOR_END: fitted_splits

// ANCHOR: snap_to_texel
/// Exercise 2, copied: the body of the chapter's `snap` listing.
pub fn snap_to_texel(min: DVec2, width: f64, resolution: u32) -> DVec2 {
    let texel = width / resolution as f64; // listing `snap` (cascades.rs)
    (min / texel).floor() * texel
}
// ANCHOR_END: snap_to_texel
