//! Lesson 05's exercises: the starter code. Each function compiles and
//! runs, and gives a wrong but harmless answer until you write it. Grade
//! with `cargo run --release --bin grade -- lesson_05`; the chapter's
//! "Exercises" section says what each one asks.

use common::glam::DVec3;

use super::adjacency::Adjacency;
use super::silhouette::{LightDir, SilhouetteEdge};

// ANCHOR: silhouette_edges
/// Exercise 1: the silhouette edges of a caster for one light (object
/// space), the edges the CPU path extrudes into the volume's sides.
///
/// A face faces the light when its unnormalised normal `n`
/// (`adj.face_normals`) points towards it: `n · (p − v0) > 0` for a point
/// light at `p` (`v0` the face's first vertex), `n · (−d) > 0` for a
/// directional light travelling along `d`; exactly 0 is not facing.
/// Walk `adj.edges`: each light-facing face on an edge
/// (`adj.faces_of(edge)`) adds +1 if it runs `v[0] → v[1]`
/// (`forward`), −1 if it runs `v[1] → v[0]`. Emit the edge |sum| times,
/// as `a → b` in the direction of the sum's sign (the way the lit face runs
/// it): the extruded quad then faces outwards.
///
/// Starter: no edges, so no volume has sides and nothing is shadowed.
pub fn silhouette_edges(adj: &Adjacency, light: LightDir) -> Vec<SilhouetteEdge> {
    let _ = (adj, light);
    Vec::new()
}
// ANCHOR_END: silhouette_edges

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
/// - `frustum`: the view frustum's planes `(n, d)`, `|n| = 1`, with
///   `n · x + d ≥ 0` inside (no far plane under `far = "infinite"`).
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
