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
/// Exercise 2: the caps of a caster's z-fail volume for one light that the
/// view can see (object space): `(front, back)`, as welded vertex ids of
/// `adj`, each wound as the lesson winds it (front: the light-facing
/// triangles as they are; back: the same triangles reversed, moved away
/// from the light by the caller, to infinity or to the light's range).
///
/// A cap triangle that lies wholly outside the view frustum draws no
/// fragment, so leaving it out changes no pixel and saves its work. `view`
/// holds the frustum's planes `(q, h)` in object space (`q · x + h ≥ 0`
/// inside; `q` not of unit length; no far plane under an infinite one).
/// A front-cap triangle is outside when its three vertices are outside one
/// plane. A back-cap vertex can lie anywhere on the ray from the vertex
/// `X` away from the light (`X + t (X − L)`, `t ≥ 0`, for a point light at
/// `L`): a back-cap triangle is outside when, for one plane, all three of
/// its rays stay outside it. For a directional light the caller draws no
/// back cap. Keep a triangle whenever unsure: a missing cap in view leaks
/// the count.
///
/// Starter: no caps, so z-fail's count leaks.
pub fn volume_caps(
    adj: &Adjacency,
    light: LightDir,
    view: &[(DVec3, f64)],
) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
    let _ = (adj, light, view);
    (Vec::new(), Vec::new())
}
// ANCHOR_END: volume_caps
