//! What a lesson 09 variant is: how many cascades of what size, how the
//! frustum is split and how each box is fitted; and turning the scene's
//! camera into cascades, every frame.

use anyhow::Result;
use common::glam::{DVec2, DVec3, Mat4};
use common::gpu::render::{SceneGpu, SCENE_BUFFER_USAGE};
use common::gpu::Gpu;
use common::scene::{Far, LightKind, Scene};

use super::cascades::{
    self, Cascade, Fit, FitOptions, LightBox, SplitScheme, ViewFrustum, NORMAL_OFFSET_TEXELS,
};
use super::csm::CsmParams;
use super::receivers::LitView;
use crate::lesson_02::bias::SlopeScaledBias;

/// The texels every variant spends: one 2048² map's worth.
pub const TOTAL_TEXELS: u64 = 2048 * 2048;

/// A variant's cascades.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setup {
    pub count: usize,
    /// Each cascade's map is `resolution`² texels.
    pub resolution: u32,
    pub scheme: SplitScheme,
    /// `None`: lesson 01's single map over the scene bounds.
    pub options: Option<FitOptions>,
    /// The blend band, a fraction of each cascade (0: a hard switch).
    pub blend: f32,
    /// The chapter's exercise this variant runs, if any.
    pub exercise: Option<Exercise>,
    /// Each cascade draws only the casters that can shadow its receivers
    /// ([`super::caster_culling`]); false: every caster into every cascade.
    pub cull: bool,
}

/// The chapter's exercises (`exercises.rs`): k4 (exercise 2: k4_aabb) with the
/// student's code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exercise {
    /// `fitted_splits` instead of [`cascades::split_depths`].
    PracticalSplits,
    /// `snap_tight_box` instead of [`cascades::snap`] (on the tight box).
    SnapTightBox,
}

impl Setup {
    /// Lesson 01's one map of `resolution`², fitted to the scene bounds.
    pub fn single(resolution: u32) -> Setup {
        Setup {
            count: 1,
            resolution,
            scheme: SplitScheme::Uniform,
            options: None,
            blend: 0.0,
            exercise: None,
            cull: true,
        }
    }

    /// `count` cascades sharing [`TOTAL_TEXELS`].
    pub fn cascaded(count: usize, scheme: SplitScheme, options: FitOptions) -> Setup {
        Setup {
            count,
            resolution: per_cascade_resolution(count),
            scheme,
            options: Some(options),
            blend: 0.0,
            exercise: None,
            cull: true,
        }
    }

    pub fn with_fit(self, fit: Fit, snap: bool, extend: bool) -> Setup {
        let options = Some(FitOptions { fit, snap, extend });
        Setup { options, ..self }
    }

    /// Light `light`'s cascades for the scene's camera as it is now, for a
    /// `width × height` image, in the scene's box `b`. The single map is
    /// lesson 01's, `single` (the light's own `view_proj`).
    pub fn fit(
        &self,
        scene: &Scene,
        b: &SceneBox,
        single: Mat4,
        (width, height): (u32, u32),
        light: usize,
    ) -> Result<Vec<Cascade>> {
        let Some(LightKind::Directional { direction }) = scene.lights.get(light).map(|l| l.kind)
        else {
            anyhow::bail!("lights[{light}]: lesson_09 cascades directional lights only");
        };
        let view = view_frustum(scene, b.origin, width, height);
        let corners = b.corners;
        let far = match scene.camera.far {
            Far::Finite(f) => Some(f),
            Far::Infinite => None,
        };
        let near = scene.camera.near;
        let reach = cascades::shadow_distance(&view, near, far, &corners);
        let Some(options) = self.options else {
            let m = single.as_dmat4();
            // An orthographic map: 2 NDC units are 2 / |row| metres.
            let side = |r: usize| 2.0 / m.row(r).truncate().length();
            return Ok(vec![Cascade {
                near,
                far: reach,
                width: side(0).max(side(1)),
                origin: None,
                view_proj: m,
            }]);
        };
        let splits = match self.exercise {
            Some(Exercise::PracticalSplits) => {
                let lambda = cascades::PRACTICAL_LAMBDA;
                let (eye, fwd) = (view.eye, view.forward);
                let d = crate::exercise!(lesson_09::fitted_splits(
                    eye, fwd, &corners, near, reach, self.count, lambda
                ));
                check_splits(&d, self.count)?;
                d
            }
            _ => cascades::split_depths(self.scheme, near, reach, self.count),
        };
        let (res, v, d) = (self.resolution, &view, direction);
        Ok(match self.exercise {
            Some(Exercise::SnapTightBox) => {
                cascades::fit_cascades_with(v, d, &splits, options, res, &corners, student_snap)
            }
            _ => cascades::fit_cascades(v, d, &splits, options, res, &corners),
        })
    }

    /// The lit pass's parameters for `fit`.
    pub fn params(
        &self,
        scene: &Scene,
        b: &SceneBox,
        (width, height): (u32, u32),
        fit: &[Cascade],
    ) -> CsmParams {
        let forward = view_frustum(scene, b.origin, width, height).forward;
        CsmParams::new(
            fit,
            self.resolution,
            forward,
            self.blend,
            NORMAL_OFFSET_TEXELS,
        )
    }
}

/// The student's `snap_tight_box`, applied to a box as [`cascades::snap`] is.
fn student_snap(b: LightBox, resolution: u32) -> LightBox {
    let xy = |v: common::glam::DVec3| DVec2::new(v.x, v.y);
    let (min, w) = crate::exercise!(lesson_09::snap_tight_box(xy(b.min), xy(b.max), resolution));
    LightBox {
        min: min.extend(b.min.z),
        max: (min + DVec2::splat(w)).extend(b.max.z),
    }
}

/// The student's splits must be `k + 1` finite depths that increase.
fn check_splits(d: &[f64], k: usize) -> Result<()> {
    if d.len() != k + 1 {
        anyhow::bail!(
            "exercise_practical_splits: fitted_splits returned {} depths for {k} cascades (expected {})",
            d.len(),
            k + 1
        );
    }
    if !d.iter().all(|x| x.is_finite()) || d.windows(2).any(|w| w[1] <= w[0]) {
        anyhow::bail!("exercise_practical_splits: the depths must be finite and increase: {d:?}");
    }
    Ok(())
}

/// The side of each of `count` square maps that together hold about
/// [`TOTAL_TEXELS`]: 2048, 1448, 1182, 1024.
pub fn per_cascade_resolution(count: usize) -> u32 {
    (TOTAL_TEXELS as f64 / count.max(1) as f64).sqrt().floor() as u32
}

/// What every fit reads of the scene besides the camera: its origin and
/// the corners of its bounds (origin-relative). Found once: each is a pass
/// over every vertex, and objects do not move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneBox {
    pub origin: DVec3,
    pub corners: [DVec3; 8],
}

impl SceneBox {
    pub fn new(scene: &Scene) -> SceneBox {
        let o = scene.origin();
        let (lo, hi) = scene.bounds();
        SceneBox {
            origin: o,
            corners: cascades::box_corners(lo - o, hi - o),
        }
    }
}

/// The scene camera's frustum, relative to `o` (the scene's origin).
pub fn view_frustum(scene: &Scene, o: DVec3, width: u32, height: u32) -> ViewFrustum {
    let c = &scene.camera;
    let aspect = width as f64 / height as f64;
    ViewFrustum::new(c.eye - o, c.target - o, c.up, c.fov_y_deg, aspect)
}

/// What the lit pass sees now ([`LitView`]): the camera as the scene's
/// uniforms hold it (moved by the runner's jitter, or the frame before's
/// in its world-locked probe), and the view axis the cascades are split
/// along, from the scene's camera.
pub fn lit_view(scene: &SceneGpu, origin: DVec3) -> LitView {
    let (w, h) = (scene.width, scene.height);
    LitView {
        view_proj: scene.camera.view_proj.as_dmat4(),
        eye: scene.camera.eye.as_dvec3(),
        forward: view_frustum(&scene.scene, origin, w, h).forward,
    }
}

/// The cascade a pixel at view depth `d` samples, as `select_cascade` in
/// `csm.wgsl` picks it: the first whose far split lies beyond `d`; past
/// the last split, or where nothing is seen (NaN), the last.
pub fn cascade_of(fit: &[Cascade], d: f64) -> usize {
    let last = fit.len().saturating_sub(1);
    if d.is_nan() {
        return last;
    }
    fit.iter().position(|c| d < c.far).unwrap_or(last).min(last)
}

/// Refuses every light but a directional one: a cascade is an
/// orthographic box, for a light whose rays are parallel. One line names
/// the light and the lesson that shadows it.
pub fn refuse_non_directional(scene: &Scene, lesson: &str) -> Result<()> {
    for (k, l) in scene.lights.iter().enumerate() {
        let other = match l.kind {
            LightKind::Directional { .. } => continue,
            LightKind::Point { .. } => "point lights are lesson_04",
            LightKind::Spot { .. } => "spot lights are lesson_01 to lesson_03",
        };
        anyhow::bail!("lights[{k}]: {lesson} cascades directional lights only; {other}");
    }
    Ok(())
}

/// The shadow pass's bias: lesson 02's slope-scaled bias, unclamped (its
/// clamp is in texels of one map over the scene; a cascade's texels differ,
/// and the slope term already scales with each cascade's own texels).
pub fn shadow_pass_bias() -> wgpu::DepthBiasState {
    let b = SlopeScaledBias::RECOMMENDED;
    wgpu::DepthBiasState {
        constant: b.constant,
        slope_scale: b.slope_scale,
        clamp: 0.0,
    }
}

/// The buffer of one light's [`CsmParams`].
pub fn params_buffer(gpu: &Gpu) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("cascade parameters"),
        size: std::mem::size_of::<CsmParams>() as u64,
        usage: SCENE_BUFFER_USAGE,
        mapped_at_creation: false,
    })
}
