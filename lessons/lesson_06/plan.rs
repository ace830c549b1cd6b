//! Leaving out work (lesson 06): per light and caster, skip a caster whose
//! volume cannot reach the view frustum; use z-fail (with caps) only where
//! the caster can shadow the near-plane rectangle (the occlusion pyramid of
//! the 2005 article), else z-pass without caps. The counts, and so the
//! pixels, are the same as with z-fail everywhere.

use common::glam::{DMat4, DVec3};
use common::gpu::render::SceneGpu;

use super::caps::zfail;
pub use crate::lesson_05::cull::frustum_planes;
use crate::lesson_05::extrusion::world_light;
use crate::lesson_05::silhouette::LightDir;
use crate::lesson_05::volumes::{CasterDraw, ShadowVolumes, VolumeCaster};

// ANCHOR: plan
/// Which casters need z-fail, which z-pass, and which can be skipped,
/// for light `light` (see the module doc). The counts are the same as
/// with z-fail everywhere.
pub fn plan(volumes: &ShadowVolumes, scene: &SceneGpu, light: usize) -> Vec<CasterDraw> {
    let view_proj = scene.camera.view_proj.as_dmat4();
    let near_rect = near_rectangle(view_proj);
    let (l_point, l_dir) = match world_light(scene, light) {
        LightDir::Point(l) => (Some(l.as_dvec3()), None),
        LightDir::Directional(dir) => (None, Some(dir.as_dvec3())),
    };
    let pyramid = occlusion_pyramid(&near_rect, l_point, l_dir);
    // A plane (q, h) holds x inside when q·x + h ≥ 0.
    let reaches_near = |center: DVec3, radius: f64| match &pyramid {
        Some(planes) => !planes.iter().any(|(q, h)| q.dot(center) + h < -radius),
        None => true, // degenerate pyramid: be safe
    };
    plan_with(volumes, scene, light, |c| reaches_near(c.center, c.radius))
}
// ANCHOR_END: plan

// ANCHOR: plan_with
/// [`plan`] with the choice of z-fail made by `needs_zfail(caster)`: skip
/// the casters whose volume cannot reach the view frustum, and draw the
/// others with z-fail or z-pass as `needs_zfail` says.
pub fn plan_with(
    volumes: &ShadowVolumes,
    scene: &SceneGpu,
    light: usize,
    needs_zfail: impl Fn(&VolumeCaster) -> bool,
) -> Vec<CasterDraw> {
    let frustum = frustum_planes(scene.camera.view_proj.as_dmat4());
    let (l_point, l_dir) = match world_light(scene, light) {
        LightDir::Point(l) => (Some(l.as_dvec3()), None),
        LightDir::Directional(dir) => (None, Some(dir.as_dvec3())),
    };
    let mut out = Vec::new();
    for c in &volumes.casters {
        let outside = |(q, h): &(DVec3, f64)| {
            let s = q.dot(c.center) + h;
            if s + c.radius >= 0.0 {
                return false;
            }
            // The extrusion must also move away from the plane.
            match (l_point, l_dir) {
                (Some(l), _) => s + c.radius <= q.dot(l) + h,
                (_, Some(dir)) => q.dot(dir) <= 0.0,
                _ => false,
            }
        };
        if frustum.iter().any(outside) {
            continue; // its volume cannot reach the view: skipped
        }
        if needs_zfail(c) {
            out.push(zfail(c.object));
        } else {
            out.push(CasterDraw::zpass(c.object));
        }
    }
    out
}
// ANCHOR_END: plan_with

/// The four world corners of the near-plane rectangle.
pub fn near_rectangle(vp: DMat4) -> [DVec3; 4] {
    let inv = vp.inverse();
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| inv.project_point3(DVec3::new(x, y, 0.0)))
}

// ANCHOR: occlusion_pyramid
/// The region whose casters can shadow the near-plane rectangle: the
/// pyramid from a point light to the rectangle, or the rectangle swept
/// towards a directional light. Planes face inward; `None` when the region
/// is degenerate (light on the near plane, or travelling along it).
pub fn occlusion_pyramid(
    rect: &[DVec3; 4],
    point: Option<DVec3>,
    dir: Option<DVec3>,
) -> Option<Vec<(DVec3, f64)>> {
    let centre = rect.iter().sum::<DVec3>() / 4.0;
    let near_n = (rect[1] - rect[0]).cross(rect[3] - rect[0]).normalize();
    let (towards_light, interior) = match (point, dir) {
        (Some(l), _) => (l - centre, (l + centre) * 0.5),
        (_, Some(dir)) => (-dir, centre - dir),
        _ => return None,
    };
    let size = (rect[2] - rect[0]).length();
    if near_n.dot(towards_light).abs() < 1e-9 * size.max(towards_light.length()) {
        return None;
    }
    let mut planes = Vec::new();
    let mut add = |normal: DVec3, p: DVec3| {
        let q = normal.normalize();
        let h = -q.dot(p);
        // Orient towards the interior point.
        if q.dot(interior) + h < 0.0 {
            planes.push((-q, -h));
        } else {
            planes.push((q, h));
        }
    };
    add(near_n, centre);
    for i in 0..4 {
        let (a, b) = (rect[i], rect[(i + 1) % 4]);
        let side = match (point, dir) {
            (Some(l), _) => (a - l).cross(b - l),
            (_, Some(dir)) => (b - a).cross(dir),
            _ => unreachable!(),
        };
        add(side, a);
    }
    if planes.iter().any(|(q, _)| !q.is_finite()) {
        return None;
    }
    Some(planes)
}
// ANCHOR_END: occlusion_pyramid
