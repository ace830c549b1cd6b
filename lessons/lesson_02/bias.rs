//! Bias (lesson 02): moving the depth comparison off the surface so that a
//! surface stops shadowing itself. Two places to do it: in the lit pass, on
//! the receiver ([`ShadowBias`], `shaders/lesson_02/bias.wgsl`), and in the
//! shadow pass, by the rasteriser ([`SlopeScaledBias`]). Lesson 03 keeps
//! the slope-scaled one.

use common::camera::light_view_proj;
use common::glam::DVec3;
use common::gpu::Gpu;
use common::scene::{LightKind, Scene};

use crate::lesson_01::shadow_map::ShadowPassState;

/// The receiver-side bias of `bias.wgsl` (its `ShadowBias`). Lengths are in
/// shadow-map texels at the receiver, measured along its depth gradient
/// (`shadow_texel_size`), so a setting fits any scene size, map resolution,
/// texel aspect and light type: a receiver at θ needs tan θ / 2 of them.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ShadowBias {
    /// Subtracted from the receiver's depth, in depth units (the seeds' constant).
    pub depth: f32,
    /// The receiver moves this many texels towards the light.
    pub toward_light: f32,
    /// ... plus `slope · tan θ` texels, at most `slope_max`.
    pub slope: f32,
    pub slope_max: f32,
    /// The receiver moves `normal · (1 − N·L)` texels along its normal.
    pub normal: f32,
    pub _pad: [f32; 3],
}

impl ShadowBias {
    /// No bias at all: lesson 01's comparison.
    pub const NONE: ShadowBias = ShadowBias {
        depth: 0.0,
        toward_light: 0.0,
        slope: 0.0,
        slope_max: 0.0,
        normal: 0.0,
        _pad: [0.0; 3],
    };
}

/// Whether the adapter can clamp the hardware depth bias
/// (`DepthBiasState::clamp`); GL cannot, and a non-zero clamp fails there.
pub fn can_clamp_depth_bias(gpu: &Gpu) -> bool {
    gpu.adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::DEPTH_BIAS_CLAMP)
}

// ANCHOR: slope_scaled_bias
/// The rasteriser's slope-scaled depth bias (`wgpu::DepthBiasState`), with
/// its clamp given in texels: taught in lesson 02, reused in lesson 03.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlopeScaledBias {
    /// Units of the depth format (for `Depth32Float`, 2^(e − 23) with e the
    /// exponent of the triangle's largest depth).
    pub constant: i32,
    /// Times the triangle's depth slope: its largest depth change per texel.
    pub slope_scale: f32,
    /// At most this many texels of depth along the light, a texel being its
    /// larger side at the scene's centre (a clamp has no receiver to measure
    /// a gradient on).
    pub clamp_texels: f32,
}

impl SlopeScaledBias {
    /// What lesson 02 measured best, and what lesson 03 filters with.
    pub const RECOMMENDED: SlopeScaledBias = SlopeScaledBias {
        constant: 8,
        slope_scale: 1.5,
        clamp_texels: 16.0,
    };

    /// The shadow pass's state for `light` and a `map_size` map: the clamp
    /// converted to depth units at the scene's centre, and left out where
    /// the adapter cannot clamp (GL), so there the bias is unclamped.
    pub fn pass_state(
        &self,
        gpu: &Gpu,
        scene: &Scene,
        light: usize,
        map_size: u32,
    ) -> ShadowPassState {
        let clamp = if can_clamp_depth_bias(gpu) {
            (self.clamp_texels as f64 * depth_per_texel(scene, light, map_size)) as f32
        } else {
            0.0
        };
        ShadowPassState {
            cull: None,
            bias: wgpu::DepthBiasState {
                constant: self.constant,
                slope_scale: self.slope_scale,
                clamp,
            },
        }
    }
}
// ANCHOR_END: slope_scaled_bias

/// How much depth one texel-width step along the light's ray is, at the
/// scene's centre (the depth is not linear for a spot light, so only there).
pub fn depth_per_texel(scene: &Scene, light: usize, map_size: u32) -> f64 {
    let Some(m) = light_view_proj(scene, light) else {
        return 0.0;
    };
    let m = m.as_dmat4();
    let centre = DVec3::ZERO; // everything is relative to the scene-bounds centre
    let along = match scene.lights[light].kind {
        LightKind::Directional { direction } => direction.normalize(),
        LightKind::Spot { position, .. } => {
            (centre - (position - scene.origin())).normalize_or(DVec3::NEG_Y)
        }
        LightKind::Point { .. } => return 0.0,
    };
    let row = |i: usize| DVec3::new(m.x_axis[i], m.y_axis[i], m.z_axis[i]).length();
    let w = (m * centre.extend(1.0)).w;
    let texel = 2.0 * w / (map_size as f64 * row(0).min(row(1)));
    (m.project_point3(centre + along * texel).z - m.project_point3(centre).z).abs()
}
