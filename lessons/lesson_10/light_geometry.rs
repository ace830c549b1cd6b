//! What a light's shadow map needs to turn the light's size into map units
//! (lesson 10): its projection (orthographic or perspective), its depth
//! range, its size, the nearest caster, and map units per world unit or per
//! radian.

use common::scene::camera::light_view_proj;
use common::scene::{LightKind, LightSize, Scene};
use glam::{Mat4, Vec3, Vec4, Vec4Swizzles};

// ANCHOR: light_geometry
/// What the shader needs of a light to turn its size into map units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightGeometry {
    pub perspective: bool,
    /// Orthographic: 0 and the depth range's length, world units;
    /// perspective: the near and far planes.
    pub near: f32,
    pub far: f32,
    /// tan(angular radius), or the emitter's radius.
    pub size: f32,
    /// The nearest caster's distance from the light, as `near`, `far`.
    pub nearest_caster: f32,
    /// Map units per world unit (orthographic, u and v) or per radian.
    pub uv_per: [f32; 2],
}
// ANCHOR_END: light_geometry

// ANCHOR: light_geometry_new
impl LightGeometry {
    /// Light `k`'s geometry (a directional or spot light; the lesson
    /// refuses point lights).
    pub fn new(scene: &Scene, k: usize) -> Option<LightGeometry> {
        let m = light_view_proj(scene, k)?;
        let light = &scene.lights[k];
        // The casters' vertices that the light's frustum holds, in its clip
        // space: the nearest of them bounds the blocker search (a floor's
        // corners out of the light's view would pull it to the light).
        let inside = |c: &Vec4| {
            c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w && (0.0..=c.w).contains(&c.z)
        };
        let clip: Vec<Vec4> = (scene.world_triangles().into_iter())
            .filter(|(_, o)| scene.objects[*o as usize].casts_shadow)
            .flat_map(|(t, _)| t)
            .map(|p| m * p.extend(1.0))
            .filter(inside)
            .collect();
        let size = match light.size {
            LightSize::Radius(r) => r as f32,
            LightSize::AngularRadiusDeg(a) => a.to_radians().tan() as f32,
        };
        match light.kind {
            LightKind::Directional { .. } => Some(directional(m, &clip, size)),
            LightKind::Spot { spot_angle_deg, .. } => Some(spot(m, &clip, size, spot_angle_deg)),
            LightKind::Point { .. } => None,
        }
    }
}
// ANCHOR_END: light_geometry_new

// ANCHOR: light_kinds
/// A directional light's orthographic map: depth linear in the distance.
fn directional(m: Mat4, clip: &[Vec4], size: f32) -> LightGeometry {
    let row = |i: usize| m.row(i).xyz();
    // z = row 2 · p + m₂₃: one unit of depth is 1 / |row 2| long.
    let far = 1.0 / row(2).length();
    let nearest = clip
        .iter()
        .map(|c| c.z / c.w)
        .fold(1.0f32, f32::min)
        .max(0.0);
    LightGeometry {
        perspective: false,
        near: 0.0,
        far,
        size,
        nearest_caster: nearest * far,
        uv_per: [0.5 * row(0).length(), 0.5 * row(1).length()],
    }
}

/// A spot's perspective map: map units per radian from its cone.
fn spot(m: Mat4, clip: &[Vec4], size: f32, spot_angle_deg: f64) -> LightGeometry {
    let (near, far) = perspective_planes(m);
    // clip.w is the distance along the light's axis.
    let nearest = clip.iter().map(|c| c.w).fold(far, f32::min).max(near);
    let per = 0.5 / (0.5 * spot_angle_deg).to_radians().tan() as f32;
    LightGeometry {
        perspective: true,
        near,
        far,
        size,
        nearest_caster: nearest,
        uv_per: [per, per],
    }
}
// ANCHOR_END: light_kinds

// ANCHOR: perspective_planes
/// The near and far planes of webgpu's perspective `m` (depth
/// z = A − B / d of the distance d along the axis): from two points on the
/// axis, `n = B / A`, `f = B / (A − 1)`.
fn perspective_planes(m: Mat4) -> (f32, f32) {
    let inv = m.inverse();
    // Two depths on the axis, their distances: the clip w.
    let at = |z: f32| {
        let p = inv * Vec4::new(0.0, 0.0, z, 1.0);
        let p: Vec3 = p.xyz() / p.w;
        (m * p.extend(1.0)).w
    };
    let (z1, z2) = (0.25f32, 0.75f32);
    let (d1, d2) = (at(z1) as f64, at(z2) as f64);
    // z = A − B / d at both: B = (z2 − z1) / (1/d1 − 1/d2), A = z1 + B / d1.
    let b = (z2 - z1) as f64 / (1.0 / d1 - 1.0 / d2);
    let a = z1 as f64 + b / d1;
    ((b / a) as f32, (b / (a - 1.0)) as f32)
}
// ANCHOR_END: perspective_planes
