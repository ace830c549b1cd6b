//! Lesson 09's exercises, the starter code: two Rust functions,
//! [`practical_splits`] and [`snap_to_texel`]. Grade them with
//! `cargo run --release --bin grade -- lesson_09`. The reference solutions
//! are `solutions/lesson_09.rs` (`--features solutions`).

use common::glam::DVec2;

// ANCHOR: practical_splits
/// Exercise 1: the practical split scheme.
///
/// Return the `k + 1` view depths that bound `k` cascades, from `near` to
/// `far` (both included, increasing): at each `i`, the blend
/// `lambda · log_i + (1 − lambda) · uniform_i` of the logarithmic split
/// `near · (far / near)^(i / k)` and the uniform one
/// `near + (far − near) · i / k`.
pub fn practical_splits(near: f64, far: f64, k: usize, lambda: f64) -> Vec<f64> {
    let _ = lambda;
    // TODO: blend in the logarithmic split. This stub is uniform: the
    // near cascade is as long as the far one, and coarse where it matters.
    (0..=k)
        .map(|i| near + (far - near) * i as f64 / k as f64)
        .collect()
}
// ANCHOR_END: practical_splits

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
