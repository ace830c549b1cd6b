//! Leaving out what the light cannot see (lesson 04): casters past the
//! light's range, and per face, casters whose bounding sphere misses the
//! face's frustum. The unculled frame must come out the same.

use common::glam::DVec3;
use common::gpu::render::SceneGpu;
use common::scene::Scene;

use super::face_rects::Bounds;
use super::faces::CUBE_FACES;

/// A bounding sphere, origin-relative, around the world-space box of
/// half extents `half` (the chapter's exercise tests the box).
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    pub centre: DVec3,
    pub radius: f64,
    pub half: DVec3,
}

impl Sphere {
    /// The box inside the sphere: the object's bounds as a receiver.
    pub fn bounds(&self) -> Bounds {
        Bounds {
            lo: self.centre - self.half,
            hi: self.centre + self.half,
        }
    }
}

/// Each object's bounding sphere: around its world-space bounding box.
pub fn bounding_spheres(scene: &Scene) -> Vec<Sphere> {
    let o = scene.origin();
    scene
        .objects
        .iter()
        .map(|obj| {
            let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            for p in &obj.mesh.positions {
                let w = obj.model.transform_point3(p.as_dvec3()) - o;
                lo = lo.min(w);
                hi = hi.max(w);
            }
            Sphere {
                centre: (lo + hi) * 0.5,
                radius: (hi - lo).length() * 0.5,
                half: (hi - lo) * 0.5,
            }
        })
        .collect()
}

// ANCHOR: sphere_in_face
/// Whether a sphere (centre relative to the light) can touch face `face`'s
/// frustum. Face +X holds the directions with x ≥ |y| and x ≥ |z|: four
/// planes through the light, with normals (1, ∓1, 0)/√2 and (1, 0, ∓1)/√2.
pub fn sphere_touches_face(centre: DVec3, radius: f64, face: usize) -> bool {
    let (axis, up) = CUBE_FACES[face];
    let side = axis.cross(up);
    let m = centre.dot(axis);
    let (a, b) = (centre.dot(up), centre.dot(side));
    // The signed distance to each side plane must be > -radius.
    (m - a.abs()) / 2f64.sqrt() > -radius && (m - b.abs()) / 2f64.sqrt() > -radius
}
// ANCHOR_END: sphere_in_face

/// Whether a caster (its bounding sphere's centre relative to the light,
/// radius, and the half extents of the box inside it) can touch a face.
pub type FaceTest = fn(DVec3, f64, DVec3, usize) -> bool;

// ANCHOR: face_casters
/// The casters drawn into face `face` of the light at `pos` (origin-relative)
/// with this `range`. With `cull`, what the light cannot see is left out:
/// casters past its range, and casters whose bounding sphere misses the
/// face's frustum (`touches`).
pub fn face_casters(
    scene: &SceneGpu,
    spheres: &[Sphere],
    (pos, range): (DVec3, f64),
    cull: Option<FaceTest>,
    face: usize,
) -> Vec<usize> {
    (0..spheres.len())
        .filter(|&o| scene.casts_shadow(o))
        .filter(|&o| {
            let c = spheres[o].centre - pos;
            let (r, half) = (spheres[o].radius, spheres[o].half);
            cull.is_none_or(|touches| c.length() - r < range && touches(c, r, half, face))
        })
        .collect()
}
// ANCHOR_END: face_casters
