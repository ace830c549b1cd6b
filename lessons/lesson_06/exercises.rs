//! Lesson 06's exercises: the starter code. Each function compiles and
//! runs, and gives a wrong but harmless answer until you write it. Grade
//! with `cargo run --release --bin grade -- lesson_06`; the chapter's
//! "Exercises" section says what each one asks.

use common::glam::DVec3;

use crate::lesson_05::adjacency::Adjacency;
use crate::lesson_05::silhouette::LightDir;

// ANCHOR: needs_zfail
/// Exercise 1: must this caster be counted with z-fail for this light?
/// It must when its shadow volume can contain a point of the near-plane
/// rectangle (then z-pass misses an "enter"); otherwise z-pass counts the
/// same, for fewer stencil updates. The lesson answers from the caster's
/// bounding sphere; answer from the caster itself, its vertices `points`,
/// so that a long thin caster beside the occlusion pyramid is not counted
/// with z-fail because its sphere reaches in.
///
/// - `points`: the caster's vertices (its convex hull holds the caster);
/// - `light`: a point light's position, or the direction a directional
///   light travels;
/// - `near_rect`: the four corners of the near-plane rectangle, in order
///   around it.
///
/// All in world space, relative to the scene's origin. Answer `true` when
/// unsure: z-fail is always right, only dearer.
///
/// Starter: never, so z-pass everywhere, wrong wherever the eye is in a
/// shadow.
pub fn needs_zfail(points: &[DVec3], light: LightDir, near_rect: &[DVec3; 4]) -> bool {
    let _ = (points, light, near_rect);
    false
}
// ANCHOR_END: needs_zfail

// ANCHOR: volume_caps
/// Exercise 2: the caps that close a caster's shadow volume for one light
/// (object space): `(front, back)`, as welded vertex ids of `adj`.
///
/// The front cap is the light-facing triangles (`adj.triangles` whose
/// normal `adj.face_normals` points to the light: `n · (p − v0) > 0` for
/// a point light at `p`, `n · (−d) > 0` for a directional light travelling
/// along `d`), in their own winding: they face out of the volume, towards
/// the light. The back cap is the same triangles moved to infinity (the
/// caller does that), where they must face out of the volume too, away
/// from the light.
///
/// Starter: no caps, so z-fail's count leaks.
pub fn volume_caps(adj: &Adjacency, light: LightDir) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
    let _ = (adj, light);
    (Vec::new(), Vec::new())
}
// ANCHOR_END: volume_caps
