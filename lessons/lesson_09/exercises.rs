//! Lesson 09's exercises, the starter code: two Rust functions,
//! [`fitted_splits`] and [`snap_to_texel`]. Grade them with
//! `cargo run --release --bin grade -- lesson_09`. The reference solutions
//! are `solutions/lesson_09.rs` (`--features solutions`).

use common::glam::{DVec2, DVec3};

use crate::lesson_09::cascades::{split_depths, SplitScheme};

// ANCHOR: fitted_splits
/// Exercise 1: splits fitted to where the scene begins.
///
/// Return the `k + 1` view depths that bound `k` cascades (increasing, the
/// last one `far`): the lesson's practical split with this `lambda`, but
/// starting at the nearest view depth the scene can have instead of the
/// camera's `near`. The scene lies inside the box whose 8 corners are
/// `scene`; view depth is `(p − eye) · forward` (`forward` a unit vector).
/// Start at the smallest depth over the corners when it is larger than
/// `near` (and smaller than `far`), else at `near`: a camera inside the
/// box, or beside it, may see something just past its near plane.
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
    // TODO: start where the scene starts. This stub is the lesson's split
    // from the near plane: a camera far from the scene spends its first
    // cascades on empty air.
    split_depths(SplitScheme::Practical { lambda }, near, far, k)
}
// ANCHOR_END: fitted_splits

// ANCHOR: snap_to_texel
/// Exercise 2: snap a cascade's light-space origin to whole texels.
///
/// `min` is the box's min x/y in light space, `width` its width in metres,
/// `resolution` its map's texels across. Return the origin moved down to
/// the nearest whole number of texels (a texel is `width / resolution`),
/// so that the box moves by whole texels only as the camera moves.
pub fn snap_to_texel(min: DVec2, width: f64, resolution: u32) -> DVec2 {
    let _ = (width, resolution);
    // TODO: round to the texel grid. This stub leaves the box where the
    // fit put it: the shadows' edges crawl as the camera moves.
    min
}
// ANCHOR_END: snap_to_texel
