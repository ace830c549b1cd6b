//! Lesson 09's exercises answered with the nearest code the chapter
//! prints (`--features chapter_copies`): `grade --check-copies` must see
//! every one fail.

use common::glam::{DVec2, DVec3};

use crate::lesson_09::cascades::{split_depths, SplitScheme};

// ANCHOR: fitted_splits
/// Exercise 1, copied: the lesson's practical split from the near plane:
/// its own function, called, in both passes of the check.
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

// ANCHOR: snap_tight_box
/// Exercise 2, copied: the body of the chapter's `snap` listing, on the
/// tight box (`k4_aabb`).
pub fn snap_tight_box(min: DVec2, max: DVec2, resolution: u32) -> (DVec2, f64) {
    if common::gpu::render::chapter_copy_calls() {
        // Calls the chapter's `snap` listing on the tight box.
        let b = crate::lesson_09::cascades::snap(
            crate::lesson_09::cascades::LightBox {
                min: min.extend(0.0),
                max: max.extend(0.0),
            },
            resolution,
        );
        return (b.min.truncate(), b.width());
    }
    let w = max.x - min.x; // listing `snap` (cascades.rs)
    let texel = w / resolution as f64;
    ((min / texel).floor() * texel, w)
}
// ANCHOR_END: snap_tight_box
