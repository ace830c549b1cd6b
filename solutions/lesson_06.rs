//! Lesson 06's exercises: the reference solutions (`--features solutions`).
//! The same items as `lessons/lesson_06/exercises.rs`.

use common::glam::DVec3;

use crate::lesson_05::adjacency::Adjacency;
use crate::lesson_05::silhouette::LightDir;
use crate::lesson_06::plan::occlusion_pyramid;

// ANCHOR: needs_zfail
/// Exercise 1: a caster shadows a point q of the near-plane rectangle only
/// if it meets the segment from q to the light; those segments fill the
/// lesson's occlusion pyramid. The caster lies in the convex hull of its
/// vertices, so it misses the pyramid when all of them lie outside one of
/// its faces: z-pass then counts the same.
pub fn needs_zfail(points: &[DVec3], light: LightDir, near_rect: &[DVec3; 4]) -> bool {
    let (point, dir) = match light {
        LightDir::Point(p) => (Some(p.as_dvec3()), None),
        LightDir::Directional(d) => (None, Some(d.as_dvec3())),
    };
    let Some(planes) = occlusion_pyramid(near_rect, point, dir) else {
        return true; // degenerate: be safe
    };
    // z-pass only if one face has every vertex strictly outside it.
    !planes
        .iter()
        .any(|(n, d)| points.iter().all(|p| n.dot(*p) + d < 0.0))
}
// ANCHOR_END: needs_zfail

// ANCHOR: volume_caps
/// Exercise 2: the front cap is the light-facing triangles as they are;
/// the back cap the same triangles reversed, so that at infinity they face
/// away from the light, out of the volume.
pub fn volume_caps(adj: &Adjacency, light: LightDir) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
    let mut front = Vec::new();
    for (t, n) in adj.triangles.iter().zip(&adj.face_normals) {
        let facing = match light {
            LightDir::Point(p) => n.dot(p - adj.positions[t[0] as usize]) > 0.0,
            LightDir::Directional(d) => n.dot(-d) > 0.0,
        };
        if facing {
            front.push(*t);
        }
    }
    let back = front.iter().map(|&[a, b, c]| [a, c, b]).collect();
    (front, back)
}
// ANCHOR_END: volume_caps
