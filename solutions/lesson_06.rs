//! Lesson 06's exercises: the reference solutions (`--features solutions`).
//! The same items as `lessons/lesson_06/exercises.rs`.

use common::glam::DVec3;

use crate::lesson_05::adjacency::Adjacency;
use crate::lesson_05::silhouette::LightDir;

// ANCHOR: needs_zfail
/// Exercise 1: a caster shadows a point q of the near-plane rectangle only
/// if it meets the segment from q to the light. All those segments fill
/// the pyramid from a point light to the rectangle (or, for a directional
/// light, the rectangle swept towards the light): z-fail unless the
/// bounding sphere lies wholly outside one of its faces.
pub fn needs_zfail(center: DVec3, radius: f64, light: LightDir, near_rect: &[DVec3; 4]) -> bool {
    let mid = near_rect.iter().sum::<DVec3>() / 4.0;
    let size = (near_rect[2] - near_rect[0]).length();
    let (towards_light, inside) = match light {
        LightDir::Point(p) => (p.as_dvec3() - mid, (p.as_dvec3() + mid) * 0.5),
        LightDir::Directional(d) => {
            let d = d.as_dvec3().normalize_or_zero();
            (-d, mid - d * size)
        }
    };
    let near_n = (near_rect[1] - near_rect[0]).cross(near_rect[3] - near_rect[0]);
    if near_n
        .normalize_or_zero()
        .dot(towards_light.normalize_or_zero())
        .abs()
        < 1e-9
    {
        return true; // the light on the near plane: no pyramid, be safe
    }
    // The faces: the rectangle, and one through each of its edges.
    let mut faces = vec![(near_n, mid)];
    for i in 0..4 {
        let (a, b) = (near_rect[i], near_rect[(i + 1) % 4]);
        let n = match light {
            LightDir::Point(p) => (a - p.as_dvec3()).cross(b - p.as_dvec3()),
            LightDir::Directional(d) => (b - a).cross(d.as_dvec3()),
        };
        faces.push((n, a));
    }
    for (n, on_face) in faces {
        let n = n.normalize_or_zero();
        if n == DVec3::ZERO {
            return true;
        }
        // Orient the face's normal towards the inside.
        let n = if n.dot(inside - on_face) < 0.0 { -n } else { n };
        if n.dot(center - on_face) < -radius {
            return false; // wholly outside this face
        }
    }
    true
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
