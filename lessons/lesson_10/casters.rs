//! Which objects `pcss_min_max`'s map leaves out (lesson 10): a flat object
//! with the light and every other object on the same side of its plane
//! hides no point from the light. A ray from the light to a point on that
//! side, or on the plane, meets the plane nowhere before it; and a flat
//! object cannot hide part of itself. So any tap of PCSS that finds such an
//! object in front of a receiver is wrong, and the map is better without
//! it: the ground under a scene is the case. Leaving it out is also what
//! makes the min/max chain useful there: a tilted ground in the map puts
//! depths in front of its own receiver plane in every region that holds it.
//!
//! Lesson 09 leaves out more (casters by cascade and rectangle,
//! `lesson_09::caster_culling`); this lesson's maps have one light each
//! and no cascades, and it takes only lesson 09's flatness test.

use common::glam::DVec3;
use common::scene::{LightKind, Scene};

use crate::lesson_09::caster_culling::flat_plane;
use crate::lesson_09::receivers::Aabb;

/// For light `light` of `scene`, per object: whether it is drawn into the
/// map (it casts a shadow and is not a flat object that hides nothing).
pub fn drawn(scene: &Scene, light: usize) -> Vec<bool> {
    let points: Vec<Vec<DVec3>> = (scene.objects.iter())
        .map(|o| {
            let world = o.mesh.positions.iter();
            world
                .map(|p| o.model.transform_point3(p.as_dvec3()))
                .collect()
        })
        .collect();
    let boxes: Vec<Aabb> = points
        .iter()
        .map(|p| Aabb::around(p.iter().copied()))
        .collect();
    let all = Aabb::around(boxes.iter().flat_map(|b| [b.lo, b.hi]));
    let size = (all.hi - all.lo).length();
    let tolerance = 1e-6 * if size.is_finite() { size.max(1.0) } else { 1.0 };
    let kind = scene.lights[light].kind;
    (scene.objects.iter().enumerate())
        .map(|(i, o)| {
            let hides_nothing = flat_plane(&points[i], &o.mesh.indices).is_some_and(|plane| {
                let others = boxes.iter().enumerate().filter(|&(j, _)| j != i);
                hides_nothing(plane, kind, others.map(|(_, b)| *b), tolerance)
            });
            o.casts_shadow && !hides_nothing
        })
        .collect()
}

/// Whether the plane `n·p + d = 0` has the light strictly on one side and
/// every corner of `others` on that side or on the plane.
fn hides_nothing(
    (n, d): (DVec3, f64),
    kind: LightKind,
    others: impl Iterator<Item = Aabb>,
    tolerance: f64,
) -> bool {
    // Positive on the light's side: its position's height over the plane,
    // or, for a directional light, the height gained walking towards it.
    let side = match kind {
        LightKind::Directional { direction } => -n.dot(direction),
        LightKind::Point { position, .. } | LightKind::Spot { position, .. } => n.dot(position) + d,
    };
    if side.abs() <= tolerance {
        return false;
    }
    let (n, d) = if side > 0.0 { (n, d) } else { (-n, -d) };
    let mut others = others;
    others.all(|b| {
        let corners = (0..8).map(|k| {
            DVec3::new(
                if k & 1 == 0 { b.lo.x } else { b.hi.x },
                if k & 2 == 0 { b.lo.y } else { b.hi.y },
                if k & 4 == 0 { b.lo.z } else { b.hi.z },
            )
        });
        corners.map(|c| n.dot(c) + d).fold(f64::INFINITY, f64::min) >= -tolerance
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box(lo: f64, hi: f64) -> Aabb {
        Aabb {
            lo: DVec3::new(-1.0, lo, -1.0),
            hi: DVec3::new(1.0, hi, 1.0),
        }
    }

    const GROUND: (DVec3, f64) = (DVec3::Y, 0.0);
    const SPOT: LightKind = LightKind::Spot {
        position: DVec3::new(0.0, 4.0, 0.0),
        direction: DVec3::NEG_Y,
        range: 10.0,
        spot_angle_deg: 110.0,
    };

    /// A ground with a box standing on it hides nothing from a light
    /// above; one with a box poking below it, or a light below it, may.
    #[test]
    fn a_ground_with_everything_above_it_hides_nothing() {
        let on = [unit_box(0.0, 1.0)];
        assert!(hides_nothing(GROUND, SPOT, on.into_iter(), 1e-9));
        let sun = LightKind::Directional {
            direction: DVec3::new(0.3, -1.0, 0.2).normalize(),
        };
        assert!(hides_nothing(GROUND, sun, on.into_iter(), 1e-9));
        let through = [unit_box(-0.1, 1.0)];
        assert!(!hides_nothing(GROUND, SPOT, through.into_iter(), 1e-9));
        let below = LightKind::Spot {
            position: DVec3::new(0.0, -4.0, 0.0),
            direction: DVec3::Y,
            range: 10.0,
            spot_angle_deg: 110.0,
        };
        assert!(!hides_nothing(GROUND, below, on.into_iter(), 1e-9));
        let grazing = LightKind::Directional {
            direction: DVec3::X,
        };
        assert!(!hides_nothing(GROUND, grazing, on.into_iter(), 1e-9));
    }
}
