//! The point-shadow lookups of renderers people use, as lesson 04 variants:
//! LearnOpenGL's 20-tap disk and Bevy's point-light defaults
//! (`shaders/lesson_04/peers.wgsl`), on this lesson's cube and scene.

/// A renderer's lookup, in place of the lesson's `visibility`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Peer {
    /// The lesson's own lookup.
    None,
    /// LearnOpenGL "Point Shadows", soft (JoeyDeVries/LearnOpenGL, commit
    /// f844f7c, src/5.advanced_lighting/3.2.2.point_shadows_soft/
    /// 3.2.2.point_shadows.fs lines 21-27 and 61-73): 20 nearest taps at
    /// `fragToLight + gridSamplingDisk[i] * diskRadius`, `diskRadius = (1.0 +
    /// (viewDistance / far_plane)) / 25.0` world units, each compared with
    /// the receiver's distance less the bias (`bias = 0.15`, the variant's
    /// `bias_world`). Its far_plane (25) is our light's range.
    LearnOpenGlDisk,
    /// Bevy's point light (bevyengine/bevy, crates/bevy_light/src/
    /// point_light.rs: `DEFAULT_SHADOW_DEPTH_BIAS = 0.08`,
    /// `DEFAULT_SHADOW_NORMAL_BIAS = 0.6`), applied as crates/bevy_pbr/src/
    /// render/shadows.wgsl (commit e85a706) `fetch_point_shadow` does: the receiver moves
    /// 0.6 · (2 / N) · √2 × its major-axis distance along its normal
    /// (render/light.rs `extract_lights`) and 0.08 world units towards the
    /// light (the variant's `bias_world`), is compared in hardware depth
    /// along the major axis, and filtered by its default
    /// (`ShadowFilteringMethod::Gaussian`: shadow_sampling.wgsl, commit 3971912,
    /// `sample_shadow_cubemap_gaussian`, 8 bilinear taps of the D3D 8×MSAA
    /// pattern, Gaussian weights, `POINT_SHADOW_SCALE = 0.003` × distance).
    BevyPoint,
}

/// LearnOpenGL's disk: `(1 + viewDistance / far_plane) / 25` world units.
const LEARNOPENGL_DISK_DIVISOR: f32 = 25.0;
/// Bevy's `PointLight::DEFAULT_SHADOW_NORMAL_BIAS`.
const BEVY_POINT_NORMAL_BIAS: f32 = 0.6;

impl Peer {
    /// `LitKey::peer` and `CubeParams::peer_scale` for a cube of `size` texels a face.
    pub fn params(self, size: u32) -> (u32, f32) {
        match self {
            Peer::None => (0, 0.0),
            Peer::LearnOpenGlDisk => (1, 1.0 / LEARNOPENGL_DISK_DIVISOR),
            // Bevy: "the normal bias here is already scaled by the texel size
            // at 1 world unit from the light" (2 / N), × √2 "for the
            // worst-case diagonal offset".
            Peer::BevyPoint => (
                2,
                BEVY_POINT_NORMAL_BIAS * 2.0 / size as f32 * std::f32::consts::SQRT_2,
            ),
        }
    }

    /// Depth comparisons per pixel and light; `None` for the lesson's own.
    pub fn taps(self) -> Option<u64> {
        match self {
            Peer::None => None,
            Peer::LearnOpenGlDisk => Some(20),
            Peer::BevyPoint => Some(8),
        }
    }

    /// Bevy's taps blend 2×2 texels (a linear comparison sampler);
    /// LearnOpenGL's cube is `GL_NEAREST`.
    pub fn linear(self) -> bool {
        self == Peer::BevyPoint
    }
}
