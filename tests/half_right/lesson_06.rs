//! Lesson 06's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_06/exercises.rs`; built with `--features chapter_copies`.

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
        // THE MISTAKE: one vertex outside a face taken for the whole caster.
        .any(|(n, d)| points.iter().any(|p| n.dot(*p) + d < 0.0))
}
// ANCHOR_END: needs_zfail

// ANCHOR: volume_caps
/// Exercise 2: the light-facing triangles, each kept in the front cap
/// unless one plane has all three vertices outside, and in the back cap
/// (reversed) unless one plane has all three rays away from the light
/// outside: a ray from `p` along `p − l` stays outside the plane when `p`
/// is outside and the ray does not turn towards it (`n · (p − l) ≤ 0`).
pub fn volume_caps(
    adj: &Adjacency,
    light: LightDir,
    view: &[(DVec3, f64)],
) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
    let p = |i: u32| adj.positions[i as usize].as_dvec3();
    let outside = |i: u32, (n, d): (DVec3, f64)| n.dot(p(i)) + d < 0.0;
    let (mut front, mut back) = (Vec::new(), Vec::new());
    for (t, n) in adj.triangles.iter().zip(&adj.face_normals) {
        let facing = match light {
            LightDir::Point(l) => n.dot(l - adj.positions[t[0] as usize]) > 0.0,
            LightDir::Directional(d) => n.dot(-d) > 0.0,
        };
        if !facing {
            continue;
        }
        let front_out = view.iter().any(|&pl| t.iter().all(|&i| outside(i, pl)));
        if !front_out {
            front.push(*t);
        }
        // A directional light's back cap is never drawn.
        if let LightDir::Point(l) = light {
            let l = l.as_dvec3();
            let ray_out = |i: u32, pl: (DVec3, f64)| outside(i, pl) && pl.0.dot(p(i) - l) <= 0.0;
            // THE MISTAKE: the back cap culled like the front one, by its
            // vertices; it lies at infinity, along the rays.
            let _ = ray_out;
            if !front_out {
                back.push([t[0], t[2], t[1]]);
            }
        }
    }
    (front, back)
}
// ANCHOR_END: volume_caps
