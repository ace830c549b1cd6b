//! How far lesson 06 extrudes its volumes. Under `far = "infinite"`, to
//! infinity (w = 0), as lesson 05 does. Under a finite far plane, a volume
//! at infinity loses its back cap and far ends to the far clip, and z-fail
//! counts wrong. A point or spot light of finite `range` needs its volumes
//! only out to that range: each caster's volume ends at a finite back cap,
//! its light-facing faces scaled about the light by a factor s (w = 1/s in
//! `project_extruded`, `shaders/lesson_05/volume.wgsl`). That is exact when
//! the whole volume stays inside the far plane; otherwise, and for a
//! directional light, nothing here is exact: [`volume_reach`] says so in
//! one line, pointing to lesson 07 (depth clamp, or far = "infinite").

use anyhow::{bail, Result};
use common::glam::{DMat4, DVec3};
use common::gpu::render::SceneGpu;
use common::scene::{Far, LightKind};

use crate::lesson_05::volumes::VolumeCaster;

/// The volume covers 1 % beyond the light's range.
pub const REACH_MARGIN: f64 = 1.01;

/// The deepest volume vertex must stay this far (relative) inside the far plane.
pub const FAR_MARGIN: f64 = 1e-3;

// ANCHOR: reach_factor
/// The factor s by which a caster's volume is extruded so that it covers
/// every point within `range` of the light. A point P shadowed by the caster
/// lies on a ray from the light L through a caster point X beyond it:
/// P = L + t (X − L) with t ≥ 1. Inside the range, |P − L| ≤ range, so
/// t ≤ range / |X − L| ≤ range / d, with d the caster's distance from the
/// light. Extruding every vertex to L + s (X − L) with s ≥ range / d puts
/// the back cap beyond every such P. (At least 1: a caster beyond the
/// range shadows nothing in it.)
pub fn reach_factor(range: f64, distance: f64) -> f64 {
    REACH_MARGIN * (range / distance).max(1.0)
}
// ANCHOR_END: reach_factor

// ANCHOR: volume_reach
/// `reach[light][caster]`: the w of each caster's extruded vertices (for
/// `ShadowVolumes::set_reach`). 0 (infinity) under `far = "infinite"`;
/// 1/s ([`reach_factor`]) under a finite far plane, when every extruded
/// vertex stays inside it. Otherwise an error: one line naming the light,
/// the caster, and lesson 07.
pub fn volume_reach(scene: &SceneGpu, casters: &[VolumeCaster]) -> Result<Vec<Vec<f32>>> {
    let lights = &scene.scene.lights;
    let far = match scene.scene.camera.far {
        Far::Infinite => return Ok(vec![vec![0.0; casters.len()]; lights.len()]),
        Far::Finite(f) => f,
    };
    let origin = scene.scene.origin();
    let mut reach = Vec::new();
    for (k, light) in lights.iter().enumerate() {
        let (l, range) = match light.kind {
            LightKind::Directional { .. } => bail!(
                "camera.far = {far}: light {k} is directional, so its shadow volumes reach infinity, past the far plane, where z-fail loses their back caps; use far = \"infinite\", or lesson_07 (depth clamp)"
            ),
            LightKind::Point { position, range } | LightKind::Spot { position, range, .. } => {
                (position - origin, range)
            }
        };
        let mut per_caster = Vec::new();
        for c in casters {
            // Origin-relative, like Scene::relative_models, with the origin found once.
            let model = DMat4::from_translation(-origin) * scene.scene.objects[c.object].model;
            let world: Vec<DVec3> = c
                .adjacency
                .positions
                .iter()
                .map(|p| model.transform_point3(p.as_dvec3()))
                .collect();
            let s = caster_reach(scene, far, (k, l, range), c, &world)?;
            per_caster.push((1.0 / s) as f32);
        }
        reach.push(per_caster);
    }
    Ok(reach)
}
// ANCHOR_END: volume_reach

// ANCHOR: caster_reach
/// The factor *s* of caster `c` (its vertices `world`) for light `k` at
/// `l` of range `range`: its volume covers the range, and its deepest
/// vertex stays inside the far plane `far`, or an error says why not.
fn caster_reach(
    scene: &SceneGpu,
    far: f64,
    (k, l, range): (usize, DVec3, f64),
    c: &VolumeCaster,
    world: &[DVec3],
) -> Result<f64> {
    let d = c
        .adjacency
        .triangles
        .iter()
        .map(|t| point_triangle_distance(l, t.map(|i| world[i as usize])))
        .fold(f64::INFINITY, f64::min);
    if d <= 0.0 {
        bail!(
                "camera.far = {far}: light {k} touches object {} ({}), so its shadow volume must reach infinity, past the far plane; use far = \"infinite\", or lesson_07 (depth clamp)",
                c.object,
                scene.scene.objects[c.object].mesh_name,
            );
    }
    let s = reach_factor(range, d);
    // Depth is affine along the extrusion: the deepest point of the
    // volume is a vertex of its back cap (or of the caster).
    let view = scene.camera.view.as_dmat4();
    let deepest = world
        .iter()
        .map(|x| view_depth(view, l + (*x - l) * s).max(view_depth(view, *x)))
        .fold(f64::NEG_INFINITY, f64::max);
    if !(s.is_finite() && deepest <= far * (1.0 - FAR_MARGIN)) {
        bail!(
                "camera.far = {far}: the shadow volume of object {} ({}) for light {k}, extruded to cover the light's range ({range} / distance {} = {}x), reaches depth {}, past the far plane (and to infinity it is clipped too); use far = \"infinite\", or lesson_07 (depth clamp)",
                c.object,
                scene.scene.objects[c.object].mesh_name,
                short(d),
                short(s),
                short(deepest),
            );
    }
    Ok(s)
}
// ANCHOR_END: caster_reach

/// A number for a message: 3 decimals, or 4 significant digits in e-form
/// when very large or small.
fn short(x: f64) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) {
        format!("{x:.3}")
    } else {
        format!("{x:.3e}")
    }
}

/// Distance in front of the eye (right-handed view space looks down −z).
fn view_depth(view: DMat4, p: DVec3) -> f64 {
    -view.transform_point3(p).z
}

/// Distance from `p` to a triangle (its interior, else its nearest edge);
/// a degenerate triangle is its edges.
pub fn point_triangle_distance(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let segment = |u: DVec3, v: DVec3| {
        let e = v - u;
        let t = if e.length_squared() > 0.0 {
            ((p - u).dot(e) / e.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(u + e * t)
    };
    let n = (b - a).cross(c - a);
    if n.length_squared() > 0.0 {
        let q = p - n * ((p - a).dot(n) / n.length_squared());
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| n.dot((v - u).cross(q - u)) >= 0.0);
        if inside {
            return p.distance(q);
        }
    }
    segment(a, b).min(segment(b, c)).min(segment(c, a))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_a_triangle() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        // Above the interior: the plane distance.
        let d = point_triangle_distance(DVec3::new(0.2, 0.2, 0.3), t);
        assert!((d - 0.3).abs() < 1e-12);
        // Beside an edge: the edge distance, not the plane's (0).
        let d = point_triangle_distance(DVec3::new(0.5, -2.0, 0.0), t);
        assert!((d - 2.0).abs() < 1e-12);
        // Degenerate: its edges.
        let d =
            point_triangle_distance(DVec3::new(0.0, 1.0, 0.0), [DVec3::ZERO, DVec3::X, DVec3::X]);
        assert!((d - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_factor_covers_the_range() {
        // Light 0.3 from the caster, range 10: 10 / 0.3 ≈ 33.3, plus margin.
        let s = reach_factor(10.0, 0.3);
        assert!(s * 0.3 >= 10.0 && s < 34.0, "{s}");
        // A caster beyond the range is not extruded inward.
        assert_eq!(reach_factor(5.0, 8.0), REACH_MARGIN);
    }
}
