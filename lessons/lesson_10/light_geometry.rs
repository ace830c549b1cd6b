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
        let view_proj = light_view_proj(scene, k)?;
        let light = &scene.lights[k];
        // The casters' vertices that the light's frustum holds, in its clip
        // space: the nearest of them bounds the blocker search (a floor's
        // corners out of the light's view would pull it to the light).
        let inside = |v: &Vec4| {
            v.w > 0.0 && v.x.abs() <= v.w && v.y.abs() <= v.w && (0.0..=v.w).contains(&v.z)
        };
        let clip: Vec<Vec4> = (scene.world_triangles().into_iter())
            .filter(|(_, o)| scene.objects[*o as usize].casts_shadow)
            .flat_map(|(tri, _)| tri)
            .map(|vertex| view_proj * vertex.extend(1.0))
            .filter(inside)
            .collect();
        let size = match light.size {
            LightSize::Radius(radius) => radius as f32,
            LightSize::AngularRadiusDeg(deg) => deg.to_radians().tan() as f32,
        };
        match light.kind {
            LightKind::Directional { .. } => Some(directional(view_proj, &clip, size)),
            LightKind::Spot { spot_angle_deg, .. } => {
                Some(spot(view_proj, &clip, size, spot_angle_deg))
            }
            LightKind::Point { .. } => None,
        }
    }
}
// ANCHOR_END: light_geometry_new

// ANCHOR: light_kinds
/// A directional light's orthographic map: depth linear in the distance.
fn directional(view_proj: Mat4, clip: &[Vec4], size: f32) -> LightGeometry {
    let row = |i: usize| view_proj.row(i).xyz();
    // depth = row 2 · x + the row's fourth entry: one unit of depth is 1 / |row 2| long.
    let far = 1.0 / row(2).length();
    let nearest = clip
        .iter()
        .map(|v| v.z / v.w)
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
fn spot(view_proj: Mat4, clip: &[Vec4], size: f32, spot_angle_deg: f64) -> LightGeometry {
    let (near, far) = perspective_planes(view_proj);
    // clip.w is the distance along the light's axis.
    let nearest = clip.iter().map(|v| v.w).fold(far, f32::min).max(near);
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
/// The near and far planes of webgpu's perspective `view_proj` (depth
/// = offset − slope / d of the distance d along the axis): from two points
/// on the axis, `n = slope / offset`, `f = slope / (offset − 1)`.
fn perspective_planes(view_proj: Mat4) -> (f32, f32) {
    let inv = view_proj.inverse();
    // Two depths on the axis, their distances: the clip w.
    let at = |depth: f32| {
        let x = inv * Vec4::new(0.0, 0.0, depth, 1.0);
        let x: Vec3 = x.xyz() / x.w;
        (view_proj * x.extend(1.0)).w
    };
    let (depth_near, depth_far) = (0.25f32, 0.75f32);
    let (dist_near, dist_far) = (at(depth_near) as f64, at(depth_far) as f64);
    // depth = offset − slope / d at both points.
    let slope = (depth_far - depth_near) as f64 / (1.0 / dist_near - 1.0 / dist_far);
    let offset = depth_near as f64 + slope / dist_near;
    ((slope / offset) as f32, (slope / (offset - 1.0)) as f32)
}
// ANCHOR_END: perspective_planes
