//! The math of cascaded shadow maps (lesson 09), on the CPU in `f64`:
//! where the view frustum splits ([`split_depths`]), the light's
//! orthographic box per cascade ([`fit_sphere`], [`fit_aabb`]), how far
//! it reaches towards the light ([`extend_to_light`]), and the snap that
//! keeps its texel grid still while the camera moves ([`snap`]).
//!
//! Everything is origin-relative (`Scene::origin`), like the GPU's data.

use common::glam::dcamera::rh::proj::directx as webgpu;
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec2, DVec3};
use common::scene::camera::stable_up;

/// How the view depth range [near, far] is cut into cascades.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SplitScheme {
    /// Equal lengths: the near cascade is far too long for what it shows.
    Uniform,
    /// Equal ratios far / near: matches perspective aliasing, but the first
    /// cascade is tiny when near is small.
    Logarithmic,
    /// `lambda · log + (1 − lambda) · uniform` (Zhang et al.'s practical split).
    Practical { lambda: f64 },
}

/// The practical scheme's blend: mostly logarithmic. A tenth of uniform
/// moves the first split from under a metre (pure log, where the camera at
/// eye height sees no ground) out to several metres. Chosen from runs of
/// the default scene at 0.5, 0.75 and 0.9 (0.9 misclassified least); the
/// test `lesson_09_practical_beats_uniform_and_log` keeps it honest.
pub const PRACTICAL_LAMBDA: f64 = 0.9;

/// The receiver's normal offset, in texels of its cascade (`cascade_lookup`).
pub const NORMAL_OFFSET_TEXELS: f32 = 1.0;

// ANCHOR: splits
/// The `k + 1` view depths that bound `k` cascades: `[near, ..., far]`.
/// Cascade `i` covers view depths `[d[i], d[i + 1]]`.
pub fn split_depths(scheme: SplitScheme, near: f64, far: f64, k: usize) -> Vec<f64> {
    let k = k.max(1);
    (0..=k)
        .map(|i| {
            if i == 0 {
                return near;
            }
            if i == k {
                return far; // exact end points, whatever rounding did
            }
            let t = i as f64 / k as f64;
            let uniform = near + (far - near) * t;
            let log = near * (far / near).powf(t);
            match scheme {
                SplitScheme::Uniform => uniform,
                SplitScheme::Logarithmic => log,
                SplitScheme::Practical { lambda } => lambda * log + (1.0 - lambda) * uniform,
            }
        })
        .collect()
}
// ANCHOR_END: splits

/// The camera's view frustum, origin-relative.
#[derive(Clone, Copy, Debug)]
pub struct ViewFrustum {
    pub eye: DVec3,
    /// Unit vectors: the view axis, and the image's right and up.
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    /// tan of half the field of view, vertically and horizontally.
    pub tan_y: f64,
    pub tan_x: f64,
}

impl ViewFrustum {
    pub fn new(eye: DVec3, target: DVec3, up: DVec3, fov_y_deg: f64, aspect: f64) -> Self {
        let forward = (target - eye).normalize();
        let right = forward.cross(up).normalize();
        let tan_y = (fov_y_deg.to_radians() * 0.5).tan();
        ViewFrustum {
            eye,
            forward,
            right,
            up: right.cross(forward),
            tan_y,
            tan_x: tan_y * aspect,
        }
    }

    /// The 8 corners of the slice between view depths `near` and `far`.
    pub fn slice_corners(&self, near: f64, far: f64) -> [DVec3; 8] {
        let mut c = [DVec3::ZERO; 8];
        for (i, c) in c.iter_mut().enumerate() {
            let d = if i < 4 { near } else { far };
            let sx = if i & 1 == 0 { -1.0 } else { 1.0 };
            let sy = if i & 2 == 0 { -1.0 } else { 1.0 };
            *c = self.eye
                + self.forward * d
                + self.right * (sx * d * self.tan_x)
                + self.up * (sy * d * self.tan_y);
        }
        c
    }

    /// The view depth (distance along the view axis) of point `p`.
    pub fn depth_of(&self, p: DVec3) -> f64 {
        (p - self.eye).dot(self.forward)
    }
}

/// The light's view for direction `direction`: a rotation only, the same
/// for every cascade and every frame (its texel grid must not turn).
pub fn light_view(direction: DVec3) -> DMat4 {
    look_at_mat4(DVec3::ZERO, direction, stable_up(direction))
}

/// An orthographic box in light space (the light looks down −z: larger z
/// is nearer the light).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBox {
    pub min: DVec3,
    pub max: DVec3,
}

impl LightBox {
    /// Its width across the light (x; boxes here are square).
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }

    /// World (origin-relative) → the box's clip space, depth in [0, 1].
    pub fn view_proj(&self, light: DMat4) -> DMat4 {
        let (a, b) = (self.min, self.max);
        webgpu::orthographic(a.x, b.x, a.y, b.y, -b.z, -a.z) * light
    }
}

// ANCHOR: fit_sphere
/// The bounding sphere of the slice [near, far] of `view`: its centre on
/// the view axis, its radius a function of near, far and the field of view
/// only, so it does not change when the camera turns (the box keeps its
/// size, and so its texel size, from frame to frame).
pub fn fit_sphere(view: &ViewFrustum, near: f64, far: f64) -> (DVec3, f64) {
    // A corner at depth z is z·k from the axis. The centre c on the axis is
    // equally far from the near and far corners; past `far` it stops there.
    let k2 = view.tan_x * view.tan_x + view.tan_y * view.tan_y;
    let c = ((far + near) * (1.0 + k2) * 0.5).min(far);
    let radius = ((far - c).powi(2) + far * far * k2).sqrt();
    (view.eye + view.forward * c, radius)
}

/// The light box around that sphere: a square `2r` wide.
pub fn sphere_box(light: DMat4, centre: DVec3, radius: f64) -> LightBox {
    let c = light.transform_point3(centre);
    LightBox {
        min: c - DVec3::splat(radius),
        max: c + DVec3::splat(radius),
    }
}
// ANCHOR_END: fit_sphere

// ANCHOR: fit_aabb
/// The tightest light-space box around `corners`, made square (the larger
/// side) so texels stay square. Tighter than the sphere, but its size
/// follows the camera's rotation, and with it the texel size.
pub fn fit_aabb(light: DMat4, corners: &[DVec3]) -> LightBox {
    let mut min = DVec3::splat(f64::INFINITY);
    let mut max = DVec3::splat(f64::NEG_INFINITY);
    for &p in corners {
        let q = light.transform_point3(p);
        min = min.min(q);
        max = max.max(q);
    }
    let side = (max.x - min.x).max(max.y - min.y);
    let centre = (min + max) * 0.5;
    LightBox {
        min: DVec3::new(centre.x - side * 0.5, centre.y - side * 0.5, min.z),
        max: DVec3::new(centre.x + side * 0.5, centre.y + side * 0.5, max.z),
    }
}
// ANCHOR_END: fit_aabb

// ANCHOR: extend_to_light
/// Pulls the box's near plane (its max z) back to the scene's extent along
/// the light: a caster outside the view slice, between it and the light,
/// still lands in the map. `scene` holds the scene bounds' 8 corners.
pub fn extend_to_light(b: LightBox, light: DMat4, scene: &[DVec3]) -> LightBox {
    let top = scene
        .iter()
        .map(|&p| light.transform_point3(p).z)
        .fold(b.max.z, f64::max);
    LightBox {
        max: DVec3::new(b.max.x, b.max.y, top),
        ..b
    }
}
// ANCHOR_END: extend_to_light

// ANCHOR: snap
/// Moves the box's min x/y down to a whole number of texels (a texel is
/// width / resolution) and keeps its width: the box then only ever moves
/// by whole texels, so a static edge falls on the same texels every frame.
/// With the sphere fit the width is constant, so the grid is world-fixed.
pub fn snap(b: LightBox, resolution: u32) -> LightBox {
    let w = b.width();
    let texel = w / resolution as f64;
    let min = DVec2::new(b.min.x, b.min.y);
    let snapped = (min / texel).floor() * texel;
    LightBox {
        min: snapped.extend(b.min.z),
        max: (snapped + DVec2::splat(w)).extend(b.max.z),
    }
}
// ANCHOR_END: snap

/// How each cascade's box is fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fit {
    Sphere,
    Aabb,
}

/// A cascade's box options.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FitOptions {
    pub fit: Fit,
    pub snap: bool,
    pub extend: bool,
}

/// One fitted cascade.
#[derive(Clone, Copy, Debug)]
pub struct Cascade {
    /// The view depths it covers.
    pub near: f64,
    pub far: f64,
    /// The box's width across the light, in metres (texel = width / resolution).
    pub width: f64,
    /// The box's min x/y in light space (`None` for lesson 01's single map).
    pub origin: Option<DVec2>,
    pub view_proj: DMat4,
}

/// Fits one box per slice `[splits[i], splits[i + 1]]` of `view`, for a
/// directional light along `direction`, maps of `resolution`² texels, and
/// a scene whose bounds have the corners `scene`.
pub fn fit_cascades(
    view: &ViewFrustum,
    direction: DVec3,
    splits: &[f64],
    options: FitOptions,
    resolution: u32,
    scene: &[DVec3],
) -> Vec<Cascade> {
    fit_cascades_with(view, direction, splits, options, resolution, scene, snap)
}

/// [`fit_cascades`] with another snap (the chapter's exercise 2).
pub fn fit_cascades_with(
    view: &ViewFrustum,
    direction: DVec3,
    splits: &[f64],
    options: FitOptions,
    resolution: u32,
    scene: &[DVec3],
    snap: impl Fn(LightBox, u32) -> LightBox,
) -> Vec<Cascade> {
    let light = light_view(direction);
    splits
        .windows(2)
        .map(|d| {
            let mut b = match options.fit {
                Fit::Sphere => {
                    let (c, r) = fit_sphere(view, d[0], d[1]);
                    sphere_box(light, c, r)
                }
                Fit::Aabb => fit_aabb(light, &view.slice_corners(d[0], d[1])),
            };
            if options.snap {
                b = snap(b, resolution);
            }
            if options.extend {
                b = extend_to_light(b, light, scene);
            }
            Cascade {
                near: d[0],
                far: d[1],
                width: b.width(),
                origin: Some(DVec2::new(b.min.x, b.min.y)),
                view_proj: b.view_proj(light),
            }
        })
        .collect()
}

/// How far `origin` lies off the texel grid of a `width`-wide box of
/// `resolution` texels, in texels (0 when snapped, up to 0.5).
pub fn off_grid(origin: DVec2, width: f64, resolution: u32) -> f64 {
    let t = origin / (width / resolution as f64);
    (t - t.round()).abs().max_element()
}

/// The 8 corners of the box `(lo, hi)`.
pub fn box_corners(lo: DVec3, hi: DVec3) -> [DVec3; 8] {
    std::array::from_fn(|i| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// How far the cascades reach: the camera's far plane, but no farther
/// than the farthest corner of the scene bounds along the view axis (an
/// infinite or 10 km far plane would otherwise stretch every cascade over
/// empty space). `None` for an infinite far plane means the same.
pub fn shadow_distance(view: &ViewFrustum, near: f64, far: Option<f64>, scene: &[DVec3]) -> f64 {
    let reach = scene
        .iter()
        .map(|&p| view.depth_of(p))
        .fold(f64::NEG_INFINITY, f64::max);
    let far = far.unwrap_or(f64::INFINITY).min(reach);
    far.max(near * 2.0)
}
