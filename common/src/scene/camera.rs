//! Camera and light matrices. Everything here is origin-relative
//! (see [`Scene::origin`]): formed in `f64`, handed to the GPU in `f32`.

use glam::dcamera::rh::proj::directx as webgpu;
use glam::dcamera::rh::view::look_at_mat4;
use glam::{DMat4, DVec2, DVec3, Mat4, Vec3};

use crate::scene::{Far, LightKind, Scene};

/// Camera matrices for a `width × height` image, relative to the scene origin.
#[derive(Clone, Copy, Debug)]
pub struct CameraMatrices {
    pub view: Mat4,
    pub proj: Mat4,
    pub view_proj: Mat4,
    /// The camera position, origin-relative.
    pub eye: Vec3,
}

/// Right-handed perspective with depth in [0, 1] (WebGPU's, which glam calls
/// the DirectX convention), or with an infinite far plane.
pub fn perspective(fov_y_deg: f64, aspect: f64, near: f64, far: Far) -> DMat4 {
    match far {
        Far::Finite(f) => webgpu::perspective(fov_y_deg.to_radians(), aspect, near, f),
        Far::Infinite => webgpu::perspective_infinite(fov_y_deg.to_radians(), aspect, near),
    }
}

/// The lens shift `T` of `[camera] shift`, applied after the projection
/// (`T · P`): clip x gains `shift.x · w` and clip y `shift.y · w`, so the
/// image moves by `shift` in NDC (half-widths, half-heights) and depth is
/// untouched. In glam's columns that is a translation by `(sx, sy, 0)`.
pub fn lens_shift(shift: DVec2) -> DMat4 {
    DMat4::from_translation(shift.extend(0.0))
}

pub fn camera_matrices(scene: &Scene, width: u32, height: u32) -> CameraMatrices {
    camera_matrices_with_far(scene, width, height, scene.camera.far)
}

/// The same camera with another far plane (lesson 07 swaps finite and infinite).
pub fn camera_matrices_with_far(
    scene: &Scene,
    width: u32,
    height: u32,
    far: Far,
) -> CameraMatrices {
    let c = &scene.camera;
    let o = scene.origin();
    let view = look_at_mat4(c.eye - o, c.target - o, c.up);
    let proj = perspective(c.fov_y_deg, width as f64 / height as f64, c.near, far);
    let proj = lens_shift(c.shift) * proj;
    CameraMatrices {
        view: view.as_mat4(),
        proj: proj.as_mat4(),
        view_proj: (proj * view).as_mat4(),
        eye: (c.eye - o).as_vec3(),
    }
}

/// An `up` vector that is not parallel to `dir`.
pub fn stable_up(dir: DVec3) -> DVec3 {
    if dir.normalize().y.abs() > 0.99 {
        DVec3::Z
    } else {
        DVec3::Y
    }
}

// ANCHOR: light_view_proj
/// Directional light: an orthographic frustum fitted to the scene bounds.
///
/// The light "camera" sits outside the bounding sphere looking along the light
/// direction; the ortho box is the bounds' eight corners seen from there, so
/// every caster and receiver lands inside the depth map.
pub fn directional_light_view_proj(scene: &Scene, direction: DVec3) -> Mat4 {
    let (view, lo, hi) = directional_light_view(scene, direction);
    let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for i in 0..8 {
        let corner = DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let v = view.transform_point3(corner);
        a = a.min(v);
        b = b.max(v);
    }
    let (a, b) = unflatten(a, b);
    // View space looks down -z: near = -max z, far = -min z.
    let proj = webgpu::orthographic(a.x, b.x, a.y, b.y, -b.z, -a.z);
    (proj * view).as_mat4()
}
// ANCHOR_END: light_view_proj

/// A box `a..b` with no side thinner than a thousandth of its widest. A
/// flat scene seen face-on or edge-on (a lone floor lit from straight
/// above) has no depth or no width, and its projection would divide by
/// zero; any other box is returned as it is.
fn unflatten(a: DVec3, b: DVec3) -> (DVec3, DVec3) {
    let size = (b - a).max_element().max(1e-6);
    let flat = (b - a).cmple(DVec3::splat(1e-9 * size));
    let pad = DVec3::splat(1e-3 * size);
    (
        DVec3::select(flat, a - pad, a),
        DVec3::select(flat, b + pad, b),
    )
}

/// A directional light's view (origin-relative): from outside the scene's
/// bounding sphere, looking along `direction` at its centre. Also the
/// origin-relative bounds `(lo, hi)` it was fitted to.
pub fn directional_light_view(scene: &Scene, direction: DVec3) -> (DMat4, DVec3, DVec3) {
    let o = scene.origin();
    let (lo, hi) = scene.bounds();
    let (lo, hi) = (lo - o, hi - o);
    let centre = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-6);
    let eye = centre - direction.normalize() * radius * 2.0;
    (look_at_mat4(eye, centre, stable_up(direction)), lo, hi)
}

/// Spot light: a perspective frustum along the spot direction with the cone's
/// full angle and the light's range as the far plane.
pub fn spot_light_view_proj(
    scene: &Scene,
    position: DVec3,
    direction: DVec3,
    range: f64,
    angle_deg: f64,
) -> Mat4 {
    let p = position - scene.origin();
    let view = look_at_mat4(p, p + direction, stable_up(direction));
    let near = (range * 1e-3).max(1e-4);
    let proj = webgpu::perspective(angle_deg.to_radians(), 1.0, near, range);
    (proj * view).as_mat4()
}

/// The light's view-projection for a directional or spot light
/// (point lights use six cube faces: see lesson 04).
pub fn light_view_proj(scene: &Scene, light: usize) -> Option<Mat4> {
    match scene.lights[light].kind {
        LightKind::Directional { direction } => Some(directional_light_view_proj(scene, direction)),
        LightKind::Spot {
            position,
            direction,
            range,
            spot_angle_deg,
        } => Some(spot_light_view_proj(
            scene,
            position,
            direction,
            range,
            spot_angle_deg,
        )),
        LightKind::Point { .. } => None,
    }
}

/// Light data as the shaders see it (origin-relative).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LightUniform {
    pub view_proj: [[f32; 4]; 4],
    /// xyz: position (point/spot) or the direction light travels (directional); w: kind 0/1/2.
    pub position_or_dir: [f32; 4],
    /// xyz: spot direction; w: cos(half angle).
    pub spot: [f32; 4],
    /// rgb: colour; w: range (0 for directional).
    pub color_range: [f32; 4],
}

pub fn light_uniform(scene: &Scene, light: usize) -> LightUniform {
    let l = &scene.lights[light];
    let o = scene.origin();
    let vp = light_view_proj(scene, light).unwrap_or(Mat4::IDENTITY);
    let (pd, spot, range) = match l.kind {
        LightKind::Directional { direction } => {
            (direction.as_vec3().extend(0.0), [0.0, 0.0, 0.0, -1.0], 0.0)
        }
        LightKind::Point { position, range } => (
            (position - o).as_vec3().extend(1.0),
            [0.0, 0.0, 0.0, -1.0],
            range,
        ),
        LightKind::Spot {
            position,
            direction,
            range,
            spot_angle_deg,
        } => {
            let c = (spot_angle_deg.to_radians() * 0.5).cos() as f32;
            let d = direction.as_vec3();
            (
                (position - o).as_vec3().extend(2.0),
                [d.x, d.y, d.z, c],
                range,
            )
        }
    };
    LightUniform {
        view_proj: vp.to_cols_array_2d(),
        position_or_dir: pd.to_array(),
        spot,
        color_range: l.color.extend(range as f32).to_array(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    const SCENE: &str = r#"
[camera]
eye = [0.0, 2.0, 5.0]
target = [0.0, 0.0, 0.0]
fov_y_deg = 60.0
near = 0.5
far = 50.0
[[lights]]
type = "directional"
direction = [0.3, -1.0, 0.2]
[[objects]]
mesh = "cube"
translate = [10000.0, 0.5, -10000.0]
"#;

    fn scene() -> Scene {
        Scene::parse(SCENE, "test", std::path::Path::new(".")).unwrap()
    }

    #[test]
    fn camera_maps_target_to_screen_centre_and_depth_range() {
        let s = scene();
        let m = camera_matrices(&s, 320, 180);
        let o = s.origin();
        let target = (s.camera.target - o).as_vec3();
        let c = m.view_proj * target.extend(1.0);
        let ndc = c.truncate() / c.w;
        assert!(
            ndc.x.abs() < 1e-4 && ndc.y.abs() < 1e-4,
            "target at the centre: {ndc}"
        );
        // A point on the near plane maps to depth 0, on the far plane to 1.
        let fwd = (s.camera.target - s.camera.eye).normalize();
        for (d, want) in [(0.5, 0.0), (50.0, 1.0)] {
            let p = (s.camera.eye + fwd * d - o).as_vec3();
            let c = m.view_proj * p.extend(1.0);
            assert!(
                (c.z / c.w - want).abs() < 1e-4,
                "depth at {d}: {}",
                c.z / c.w
            );
        }
    }

    #[test]
    fn lens_shift_moves_the_image_and_keeps_depth() {
        let mut s = scene();
        let plain = camera_matrices(&s, 320, 180);
        s.camera.shift = DVec2::new(0.4, -0.2);
        let shifted = camera_matrices(&s, 320, 180);
        let p = glam::Vec4::new(0.3, -0.2, -3.0, 1.0);
        let (a, b) = (plain.view_proj * p, shifted.view_proj * p);
        let (a, b) = (a.truncate() / a.w, b.truncate() / b.w);
        let moved = b - a;
        assert!(
            (moved.x - 0.4).abs() < 1e-5 && (moved.y + 0.2).abs() < 1e-5 && moved.z.abs() < 1e-6,
            "moved by {moved}"
        );
    }

    #[test]
    fn infinite_far_maps_points_at_infinity_inside_depth_range() {
        let s = scene();
        let m = camera_matrices_with_far(&s, 320, 180, Far::Infinite);
        let dir = (s.camera.target - s.camera.eye).normalize().as_vec3();
        let c = m.view_proj * dir.extend(0.0); // w = 0: a point at infinity
        assert!(
            c.w > 0.0 && (c.z / c.w) <= 1.0 && (c.z / c.w) > 0.99,
            "z/w = {}",
            c.z / c.w
        );
    }

    #[test]
    fn directional_light_frustum_contains_the_scene_far_from_origin() {
        let s = scene();
        let vp = directional_light_view_proj(&s, DVec3::new(0.3, -1.0, 0.2));
        for (tri, _) in s.world_triangles() {
            for p in tri {
                let c = vp * p.extend(1.0);
                let n = c.truncate() / c.w;
                assert!(
                    n.x.abs() <= 1.0001 && n.y.abs() <= 1.0001 && (-1e-4..=1.0001).contains(&n.z),
                    "outside the light frustum: {n}"
                );
            }
        }
    }

    #[test]
    fn origin_relative_positions_keep_millimetres_10km_out() {
        // The cube sits 10 km out; relative to the origin its corners are exact to f32 precision.
        let s = scene();
        let tris = s.world_triangles();
        let max = tris
            .iter()
            .flat_map(|(t, _)| t.iter())
            .map(|p| p.abs().max_element())
            .fold(0.0, f32::max);
        assert!(
            max <= 0.5 + 1e-6,
            "origin-relative coordinates stay small: {max}"
        );
    }
}
