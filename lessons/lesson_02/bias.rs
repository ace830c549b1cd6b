//! Bias (lesson 02): moving the depth comparison off the surface so that a
//! surface stops shadowing itself. Two places to do it: in the lit pass, on
//! the receiver ([`ShadowBias`], `shaders/lesson_02/bias.wgsl`), and in the
//! shadow pass, by the rasteriser ([`SlopeScaledBias`]). Lesson 03 keeps
//! the slope-scaled one.

use common::glam::DVec3;
use common::gpu::Gpu;
use common::scene::camera::light_view_proj;
use common::scene::{LightKind, Scene};

use crate::lesson_01::shadow_map::ShadowPassState;

/// The receiver-side bias of `bias.wgsl` (its `ShadowBias`). Lengths are in
/// shadow-map texels at the receiver, measured along its depth gradient
/// (`shadow_texel_size`), so a setting fits any scene size, map resolution,
/// texel aspect and light type: a receiver at θ needs tan θ / 2 of them.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ShadowBias {
    /// Subtracted from the receiver's depth, in depth units (the lwjgl
    /// book's constant); with `depth_slope`, the least that is subtracted.
    pub depth: f32,
    /// The receiver moves this many texels towards the light.
    pub toward_light: f32,
    /// ... plus `slope · tan θ` texels, at most `slope_max`.
    pub slope: f32,
    pub slope_max: f32,
    /// The receiver moves `normal · (1 − cos θ)` texels along its normal.
    pub normal: f32,
    /// LearnOpenGL's: `max(depth_slope · (1 − cos θ), depth)` depth units are
    /// subtracted instead of `depth`.
    pub depth_slope: f32,
    /// Bevy's depth bias: the receiver moves this far towards the light, in
    /// world units (metres, whatever the map).
    pub toward_light_world: f32,
    /// Bevy's normal bias: the receiver moves this many texels along its
    /// normal (a texel: the map texel's larger side, Bevy's `texel_size`).
    pub normal_flat: f32,
}

impl ShadowBias {
    /// No bias at all: lesson 01's comparison.
    pub const NONE: ShadowBias = ShadowBias {
        depth: 0.0,
        toward_light: 0.0,
        slope: 0.0,
        slope_max: 0.0,
        normal: 0.0,
        depth_slope: 0.0,
        toward_light_world: 0.0,
        normal_flat: 0.0,
    };

    // ANCHOR: peer_biases
    /// LearnOpenGL's "Shadow Mapping": `max(0.05 * (1.0 - dot(normal,
    /// lightDir)), 0.005)`, subtracted from the receiver's depth. Its units
    /// are the depth of ITS light frustum, an orthographic near 1, far 7.5:
    /// 0.005 there is 3.25 cm, 0.05 is 32.5 cm. Applied verbatim to our
    /// depth, whose range is the light's fit to the scene, the same numbers
    /// are (our range / 6.5) times as long. Its source lines:
    /// `port_cards::LEARNOPENGL`.
    pub const LEARNOPENGL: ShadowBias = ShadowBias {
        depth: 0.005,
        depth_slope: 0.05,
        ..ShadowBias::NONE
    };

    /// Bevy's `DirectionalLight` defaults (`DEFAULT_SHADOW_DEPTH_BIAS =
    /// 0.02`, `DEFAULT_SHADOW_NORMAL_BIAS = 1.8`), applied as its
    /// `sample_directional_cascade` does: the receiver moves 0.02 world
    /// units towards the light, and `1.8 · √2` texels (the √2 from
    /// `extract_lights`: "worst-case diagonal offset") along its normal.
    /// Its source lines: `port_cards::BEVY_BIAS`.
    pub const BEVY: ShadowBias = ShadowBias {
        toward_light_world: 0.02,
        normal_flat: 1.8 * std::f32::consts::SQRT_2,
        ..ShadowBias::NONE
    };
    // ANCHOR_END: peer_biases
}

/// The wgpu shadow example's map: `SHADOW_SIZE`, 512² texels.
pub const WGPU_EXAMPLE_MAP_SIZE: u32 = 512;
/// The faces the wgpu example's shadow pass culls.
pub const WGPU_EXAMPLE_CULL: wgpu::Face = wgpu::Face::Back;
/// Bevy's `DirectionalLightShadowMap::default()`: 2048² texels a cascade.
pub const BEVY_MAP_SIZE: u32 = 2048;

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
}
// ANCHOR_END: slope_scaled_bias

impl SlopeScaledBias {
    /// The wgpu shadow example's (its `shadow_pass` pipeline's
    /// `depth_stencil`): `DepthBiasState { constant: 2, // corresponds to
    /// bilinear filtering`, `slope_scale: 2.0, clamp: 0.0 }`. A clamp of 0
    /// is no clamp. Its source lines: `port_cards::WGPU_EXAMPLE`.
    pub const WGPU_EXAMPLE: SlopeScaledBias = SlopeScaledBias {
        constant: 2,
        slope_scale: 2.0,
        clamp_texels: 0.0,
    };
}

// ANCHOR: pass_state
impl SlopeScaledBias {
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
        let clamp = if can_clamp_depth_bias(gpu) && self.clamp_texels > 0.0 {
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
// ANCHOR_END: pass_state

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
