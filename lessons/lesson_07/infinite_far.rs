//! The far plane at infinity (lesson 07): a projection whose third row is
//! the limit of the finite one as far → ∞, pulled in by ε so that a point
//! at infinity (w = 0) lands strictly inside depth 1, and the other depth
//! mappings the precision study compares it with.

use anyhow::Result;
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec4};
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::scene::camera::lens_shift;

/// The ε of an infinite far plane: the point at infinity lands at depth
/// 1 − ε instead of exactly 1, so f32 rounding cannot push it past w.
/// 2⁻²² ≈ 2.4e-7 (a few f32 ulps below 1).
pub const INFINITE_EPSILON: f64 = 1.0 / 4_194_304.0;

/// How view distance maps to window depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthMapping {
    /// near → 0, far → 1, test `Less`.
    Standard,
    /// near → 1, far → 0, test `Greater`.
    Reversed,
    /// near → 0, infinity → 1 − ε, test `Less`.
    Infinite,
    /// near → 1, infinity → 0, test `Greater`.
    InfiniteReversed,
}

pub const MAPPINGS: [DepthMapping; 4] = [
    DepthMapping::Standard,
    DepthMapping::Reversed,
    DepthMapping::Infinite,
    DepthMapping::InfiniteReversed,
];

impl DepthMapping {
    pub fn name(self) -> &'static str {
        match self {
            DepthMapping::Standard => "standard",
            DepthMapping::Reversed => "reversed",
            DepthMapping::Infinite => "infinite",
            DepthMapping::InfiniteReversed => "infinite_reversed",
        }
    }

    pub fn reversed(self) -> bool {
        matches!(
            self,
            DepthMapping::Reversed | DepthMapping::InfiniteReversed
        )
    }

    // ANCHOR: depth_rows
    /// The projection's z and w rows as `(zz, tz, zw, tw)`: for a view-space
    /// point with z = −d, clip z = zz·(−d) + tz and clip w = zw·(−d) + tw.
    pub fn rows(self, near: f64, far: f64) -> [f64; 4] {
        let e = INFINITE_EPSILON;
        let (zz, tz) = match self {
            DepthMapping::Standard => (far / (near - far), near * far / (near - far)),
            DepthMapping::Reversed => (near / (far - near), near * far / (far - near)),
            // f → ∞ in the standard rows gives (−1, −n); ε pulls ∞ to 1 − ε.
            DepthMapping::Infinite => (-(1.0 - e), -near * (1.0 - e)),
            DepthMapping::InfiniteReversed => (0.0, near),
        };
        [zz, tz, -1.0, 0.0]
    }
    // ANCHOR_END: depth_rows

    pub fn compare(self) -> wgpu::CompareFunction {
        if self.reversed() {
            wgpu::CompareFunction::Greater
        } else {
            wgpu::CompareFunction::Less
        }
    }

    /// The depth the buffer is cleared to (the farthest value).
    pub fn clear_depth(self) -> f32 {
        if self.reversed() {
            0.0
        } else {
            1.0
        }
    }
}

// ANCHOR: infinite_perspective
/// Right-handed perspective for WebGPU's [0, 1] depth with the far plane at
/// infinity (Everitt & Kilgard 2002, adapted): the third row is the limit
/// f → ∞ of the finite one, times (1 − ε), so a point at infinity
/// (x, y, z, 0) lands at depth 1 − ε < 1 and is never clipped.
pub fn infinite_perspective(fov_y_rad: f64, aspect: f64, near: f64, eps: f64) -> DMat4 {
    let h = 1.0 / (0.5 * fov_y_rad).tan();
    DMat4::from_cols(
        DVec4::new(h / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, h, 0.0, 0.0),
        DVec4::new(0.0, 0.0, -(1.0 - eps), -1.0),
        DVec4::new(0.0, 0.0, -near * (1.0 - eps), 0.0),
    )
}
// ANCHOR_END: infinite_perspective

// ANCHOR: infinite_camera
/// The scene's camera with its far plane moved to infinity (with ε).
/// A second `SceneGpu` holds it: its own camera uniform, the same objects.
pub fn infinite_scene(gpu: &Gpu, scene: &SceneGpu) -> Result<SceneGpu> {
    projected_scene(gpu, scene, |fov_y, aspect, near| {
        infinite_perspective(fov_y, aspect, near, INFINITE_EPSILON)
    })
}
// ANCHOR_END: infinite_camera

/// A second `SceneGpu` for `scene` whose camera uses the projection
/// `proj(fov_y_rad, aspect, near)` (origin-relative view, as the runner's),
/// moved by the scene's lens shift as the runner moves its own.
pub fn projected_scene(
    gpu: &Gpu,
    scene: &SceneGpu,
    proj: impl Fn(f64, f64, f64) -> DMat4,
) -> Result<SceneGpu> {
    let c = &scene.scene.camera;
    let aspect = scene.width as f64 / scene.height as f64;
    let proj = lens_shift(c.shift) * proj(c.fov_y_deg.to_radians(), aspect, c.near);
    scene_with_projection(gpu, scene, proj)
}

/// A second `SceneGpu` for `scene` whose camera uses `proj` as it is
/// (origin-relative view, as the runner's).
pub fn scene_with_projection(gpu: &Gpu, scene: &SceneGpu, proj: DMat4) -> Result<SceneGpu> {
    let mut s = SceneGpu::new(gpu, scene.scene.clone(), scene.width, scene.height)?;
    let c = &s.scene.camera;
    let o = s.scene.origin();
    let view = look_at_mat4(c.eye - o, c.target - o, c.up);
    s.camera.proj = proj.as_mat4();
    s.camera.view_proj = (proj * view).as_mat4();
    s.upload_uniforms(gpu);
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn mappings_put_near_and_far_where_they_belong() {
        let (n, f) = (0.1, 1000.0);
        let z = |m: DepthMapping, d: f64| {
            let [zz, tz, zw, tw] = m.rows(n, f);
            (zz * -d + tz) / (zw * -d + tw)
        };
        assert!(
            (z(DepthMapping::Standard, n)).abs() < 1e-12
                && (z(DepthMapping::Standard, f) - 1.0).abs() < 1e-12
        );
        assert!(
            (z(DepthMapping::Reversed, n) - 1.0).abs() < 1e-12
                && z(DepthMapping::Reversed, f).abs() < 1e-12
        );
        assert!(z(DepthMapping::Infinite, n).abs() < 1e-12);
        assert!((z(DepthMapping::Infinite, 1e30) - (1.0 - INFINITE_EPSILON)).abs() < 1e-12);
        assert!((z(DepthMapping::InfiniteReversed, n) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_point_at_infinity_lands_inside_the_infinite_frustum() {
        let p = infinite_perspective(1.0, 1.5, 0.1, INFINITE_EPSILON);
        // (x, y, z, 0): a direction, here straight ahead and a little off axis.
        let c = p * DVec4::new(0.2, -0.1, -1.0, 0.0);
        let depth = c.z / c.w;
        assert!(depth < 1.0 && depth > 1.0 - 1e-6, "depth {depth}");
        // The same point in f32, as the GPU computes it, is still below 1.
        let c32 = p.as_mat4() * glam::Vec4::new(0.2, -0.1, -1.0, 0.0);
        assert!(c32.z < c32.w, "{c32:?}");
        // Without ε the point sits exactly on the far plane.
        let p0 = infinite_perspective(1.0, 1.5, 0.1, 0.0) * DVec4::new(0.0, 0.0, -1.0, 0.0);
        assert_eq!(p0.z / p0.w, 1.0);
    }

    /// ε must survive the f32 matrix the GPU gets: with it, every direction
    /// in front of a tilted camera has clip z < w in f32; with ε = 0, or an
    /// ε below f32's resolution at 1 (1 − 1e-9 rounds to 1), z = w to the
    /// bit (the z and w rows agree), on the clip boundary with no margin.
    #[test]
    fn epsilon_keeps_every_point_at_infinity_strictly_inside_in_f32() {
        let view = look_at_mat4(
            common::glam::DVec3::new(4.2, 4.6, 6.4),
            common::glam::DVec3::new(0.0, 0.3, -0.4),
            common::glam::DVec3::Y,
        );
        let on_boundary = |eps: f64| {
            let vp = (infinite_perspective(0.8, 1.7, 0.1, eps) * view).as_mat4();
            let mut equal = 0;
            for i in 0..400 {
                let (a, b) = (i as f32 * 0.37, i as f32 * 0.11);
                // Directions around the view direction (world space, w = 0).
                let dir = glam::Vec3::new(-0.5 + a.sin() * 0.3, -0.5 + b.cos() * 0.2, -0.7);
                let c = vp * dir.extend(0.0);
                assert!(c.w > 0.0 && c.z <= c.w, "eps {eps}: {c:?} outside");
                equal += usize::from(c.z == c.w);
            }
            equal
        };
        assert_eq!(on_boundary(INFINITE_EPSILON), 0, "ε = 2⁻²² leaves a margin");
        assert_eq!(on_boundary(0.0), 400, "ε = 0: on the boundary");
        assert_eq!(on_boundary(1e-9), 400, "ε below f32's step at 1 vanishes");
    }

    /// The volume shader's margin for exact infinite projections is this
    /// lesson's ε, not another number that would override it.
    #[test]
    fn volume_shader_margin_is_this_lessons_epsilon() {
        let wgsl = include_str!("../../shaders/lesson_05/volume.wgsl");
        let line = wgsl
            .lines()
            .find(|l| l.starts_with("const INFINITE_EPSILON: f32 = "))
            .expect("volume.wgsl declares INFINITE_EPSILON");
        let value: f32 = line
            .trim_start_matches("const INFINITE_EPSILON: f32 = ")
            .trim_end_matches(';')
            .parse()
            .expect("a number");
        assert_eq!(value, INFINITE_EPSILON as f32);
    }
}
