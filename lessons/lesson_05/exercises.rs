//! Lesson 05's exercises: the starter code. Each function compiles and
//! runs, and gives a wrong but harmless answer until you write it. Grade
//! with `cargo run --release --bin grade -- lesson_05`; the chapter's
//! "Exercises" section says what each one asks.

use common::glam::DVec3;

use super::adjacency::Adjacency;
use super::silhouette::{LightDir, SilhouetteEdge};

// ANCHOR: edges_in_view
/// Exercise 1: the silhouette edges of a caster for one light (object
/// space), leaving out each edge whose side of the volume the view
/// cannot see. The lesson's CPU path extrudes every silhouette edge; a
/// big caster half out of view, or one behind the camera, builds quads
/// that the clipper then throws away.
///
/// - `adj`, `light`: as for
///   [`silhouette_edges`](super::silhouette::silhouette_edges), whose
///   edges (each oriented like its lit face) you may start from;
/// - `view`: the view frustum's planes `(q, h)` in the caster's object
///   space, `q · x + h ≥ 0` inside (`q` is not of unit length; there is
///   no far plane under `far = "infinite"`).
///
/// An edge `a → b` extrudes to the quad `a, b, b∞, a∞`. Leave an edge out
/// only when its whole quad, the points at infinity included, lies
/// outside one plane: then it cannot cover a pixel, and the counts, so
/// the image, stay the same.
///
/// Starter: no edges, so no volume has sides and nothing is shadowed.
pub fn silhouette_edges_in_view(
    adj: &Adjacency,
    light: LightDir,
    view: &[(DVec3, f64)],
) -> Vec<SilhouetteEdge> {
    let _ = (adj, light, view);
    Vec::new()
}
// ANCHOR_END: edges_in_view

// ANCHOR: volume_can_matter
/// Exercise 2 (beyond the lesson): can this caster's shadow volume change
/// a pixel the error is measured on? Return `false` only when it surely
/// cannot; the caster is then not drawn for this light.
///
/// - `center`, `radius`: the caster's bounding sphere;
/// - `light`: the light (a point light's position, or the direction a
///   directional light travels);
/// - `range`: a point or spot light's range (`None` for a directional
///   light); pixels beyond it are not lit by it anyway;
/// - `frustum`: the view frustum's planes `(q, h)`, `|q| = 1`, with
///   `q · x + h ≥ 0` inside (no far plane under `far = "infinite"`).
///
/// All in world space, relative to the scene's origin.
///
/// Starter: every caster can matter, so none is skipped.
pub fn volume_can_matter(
    center: DVec3,
    radius: f64,
    light: LightDir,
    range: Option<f64>,
    frustum: &[(DVec3, f64)],
) -> bool {
    let _ = (center, radius, light, range, frustum);
    true
}
// ANCHOR_END: volume_can_matter
