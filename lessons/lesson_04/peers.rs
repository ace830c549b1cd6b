//! The point shadows of renderers people use, as lesson 04 variants:
//! LearnOpenGL's one tap and its 20-tap disk, Bevy's point-light defaults
//! (`shaders/lesson_04/peers.wgsl`), on this lesson's cube and scene. Each
//! takes its renderer's cube, not the lesson's: its near plane and its
//! clipping, its far plane, its storage, its bias ([`Port`]). Their source
//! lines are on their cards (`super::port_cards`), which
//! `tests/port_cards.rs` checks these constants against.

use super::cube_map::Storage;

/// A renderer's lookup, in place of the lesson's `visibility`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Peer {
    /// The lesson's own lookup: one nearest tap, or 3D PCF.
    None,
    /// LearnOpenGL "Point Shadows", soft: 20 nearest taps at
    /// `fragToLight + gridSamplingDisk[i] * diskRadius`, `diskRadius = (1.0 +
    /// (viewDistance / far_plane)) / 25.0` world units, each compared with
    /// the receiver's distance less the bias (`bias = 0.15`, the port's
    /// `bias_world`).
    LearnOpenGlDisk,
    /// Bevy's `fetch_point_shadow`: the receiver moves 0.6 · (2 / N) · √2 ×
    /// its major-axis distance along its normal and 0.08 world units towards
    /// the light (the port's `bias_world`), is compared in hardware depth
    /// along the major axis, and filtered by Bevy's default
    /// (`ShadowFilteringMethod::Gaussian`: 8 bilinear taps of the D3D 8×MSAA
    /// pattern, Gaussian weights, `POINT_SHADOW_SCALE = 0.003` × distance).
    BevyPoint,
}

/// LearnOpenGL's disk: `(1 + viewDistance / far_plane) / 25` world units.
pub const LEARNOPENGL_DISK_DIVISOR: f32 = 25.0;
/// Bevy's `PointLight::DEFAULT_SHADOW_NORMAL_BIAS`, in texels.
pub const BEVY_POINT_NORMAL_BIAS: f32 = 0.6;

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

// ANCHOR: port
/// What a renderer's point shadow is made of, as lesson 04 runs it: its
/// cube (size, storage, near and far planes, clipping), its bias and its
/// lookup. `main.rs` turns each into the variant's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Port {
    /// Texels per cube face.
    pub size: u32,
    pub storage: Storage,
    /// The faces' near plane, in metres.
    pub near: f64,
    /// The faces' far plane, in metres, and for linear storage what the
    /// distance is divided by; `None`: the light's range.
    pub far: Option<f64>,
    /// Casters nearer than `near` are clipped away (no depth clip control).
    pub clipped: bool,
    /// World units off the receiver's distance (LearnOpenGL) or towards the
    /// light (Bevy).
    pub bias_world: f32,
    /// Receivers past `far` compare at 1.0 (lit) instead of behind the
    /// cleared cube (shadowed).
    pub clamp_range: bool,
    pub lookup: Peer,
}
// ANCHOR_END: port

// ANCHOR: ports
/// LearnOpenGL "Point Shadows" (`learnopengl_1tap`): 1024² faces of
/// distance / far_plane, near 1 and far 25 clipped, one `GL_NEAREST` tap,
/// `bias = 0.05` world units.
pub const LEARNOPENGL_1TAP: Port = Port {
    size: 1024,
    storage: Storage::Linear,
    near: 1.0,
    far: Some(25.0),
    clipped: true,
    bias_world: 0.05,
    // A receiver past far_plane compares with the cleared 1.0: shadowed.
    clamp_range: false,
    lookup: Peer::None,
};

/// LearnOpenGL's soft version (`learnopengl_pcf20`): the same cube, its
/// 20-tap disk, `bias = 0.15`.
pub const LEARNOPENGL_PCF20: Port = Port {
    bias_world: 0.15,
    lookup: Peer::LearnOpenGlDisk,
    ..LEARNOPENGL_1TAP
};

/// Bevy's point light (`bevy_point`): 1024² faces of hardware depth, near
/// 0.1 clipped, depth bias 0.08 world units, its normal bias and Gaussian
/// lookup. Its projection has no far plane; here the far plane is the
/// light's range, beyond which Bevy lights nothing either.
pub const BEVY_POINT: Port = Port {
    size: 1024,
    storage: Storage::Depth,
    near: 0.1,
    far: None,
    clipped: true,
    bias_world: 0.08,
    clamp_range: true,
    lookup: Peer::BevyPoint,
};
// ANCHOR_END: ports
