//! Lesson 09's exercises, the starter code: two Rust functions,
//! [`fitted_splits`] and [`snap_tight_box`]. Grade them with
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

// ANCHOR: snap_tight_box
/// Exercise 2: snap a tight box, so that it stops shimmering.
///
/// `min` and `max` are the light-space x/y corners of a cascade's tight
/// box (`fit_aabb`'s square; its side changes as the camera turns), and
/// `resolution` its map's texels across. Return the snapped box as its
/// lower corner and its width `w` (the box is `[origin, origin + w]` in x
/// and y; a texel is `w / resolution`), such that:
///
/// - the box holds `[min, max]`;
/// - `w` depends on the size of `[min, max]` only, changes only when that
///   size crosses one of a few fixed steps (not every frame the camera
///   turns), and is less than twice the size (the box stays tight);
/// - `origin` lies on its texel grid: both coordinates whole multiples of
///   `w / resolution`.
pub fn snap_tight_box(min: DVec2, max: DVec2, resolution: u32) -> (DVec2, f64) {
    let _ = resolution;
    // TODO: a width that holds still, and a corner on its grid. This stub
    // is the tight box unsnapped: its width, and so its texel size,
    // follows the camera every frame, and its edges crawl.
    (min, (max - min).max_element())
}
// ANCHOR_END: snap_tight_box
