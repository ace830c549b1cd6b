//! The soft-shadow defaults of renderers people use, as lesson 10 variants:
//! each port's parameters, as `shaders/lesson_10/peers.wgsl` and the
//! variance map's passes read them. What each takes from its source, with
//! the file, commit and lines, is on its card ([`super::port_cards`]);
//! `tests/port_cards_lesson_10.rs` checks the two against each other.

use super::light_geometry::LightGeometry;
use super::map_sets::MapPass;
pub use super::moments::ThreeVsmBlur;
use super::moments::Variance;
use crate::lesson_02::bias::ShadowBias;

/// A renderer's shadow filter, its default or its soft option, as its
/// source runs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Peer {
    /// Filament's default, `ShadowType::PCF` (`ShadowSample_PCF_Low`):
    /// Castaño's 3×3 from 4 bilinear comparisons.
    FilamentPcf { normal_texels: f32 },
    /// Filament's PCSS (`ShadowType::PCSS`): 16 of its Poisson points to
    /// search and the same 16 to filter, its bulb radius in world units.
    FilamentPcss {
        bulb_radius: f32,
        normal_texels: f32,
    },
    /// Bevy's PCSS on a spot with `soft_shadows_enabled`: 8 D3D points to
    /// search, 8 spiral taps to filter, sized by its light's radius.
    BevyPcss { light_size: f32 },
    /// Bevy's default where soft shadows are off (a directional light's
    /// `soft_shadow_size` is `None` by default): its Gaussian filter,
    /// Castaño's 5×5 (lesson 03's `bevy`), on its own map size.
    BevyCastano,
    /// Godot's default (a light of size 0): its PCF, `taps` Vogel taps of
    /// bilinear comparisons on a disk of `radius` texels.
    GodotPcf {
        taps: u32,
        radius: f32,
        receiver: ShadowBias,
        map: u32,
    },
    /// Godot's soft shadow (a light size above 0), at Soft Low: `taps`
    /// Vogel taps to search and to filter, its soft-shadow size and scale
    /// (`size`, `scale`) in map units.
    GodotSoft {
        taps: u32,
        size: f32,
        scale: f32,
        receiver: ShadowBias,
        map: u32,
    },
    /// three.js's default, `PCFShadowMap` (r182): 5 Vogel taps of bilinear
    /// comparisons on a disk of one texel.
    ThreePcf,
    /// three.js's `PCFSoftShadowMap` (r179; r182 deprecates it and runs
    /// `PCFShadowMap`): a fixed 3×3-texel box, bilinearly smoothed, 16
    /// nearest comparisons.
    ThreePcfSoft,
    /// Filament's VSM, an EVSM ([`filament_evsm`]).
    FilamentEvsm(Variance),
    /// three.js's `VSMShadowMap` ([`threejs_vsm`]): its own blur of the
    /// map's own depth.
    ThreeVsm(Variance, ThreeVsmBlur),
}

/// Filament's `shadowBulbRadius` default (LightManager.java), metres.
pub const FILAMENT_BULB_RADIUS: f32 = 0.02;
/// Filament's default shadow map (`ShadowOptions::mapSize`).
pub const FILAMENT_MAP_SIZE: u32 = 1024;
/// Filament's shadow pass outside VSM: the material's culling (back faces),
/// its polygon offset, slope 2 and constant 0.5 (`polygonOffsetSlope`,
/// `polygonOffsetConstant`). The constant is in units of its DEPTH16 map,
/// 2^-16 of depth: in Depth32Float's units, 2^-24 for depths in [0.5, 1),
/// it is 0.5 × 2^8 = 128.
pub const FILAMENT_PASS: MapPass = MapPass::Renderer {
    cull: Some(wgpu::Face::Back),
    bias: wgpu::DepthBiasState {
        constant: FILAMENT_POLYGON_OFFSET_UNITS,
        slope_scale: 2.0,
        clamp: 0.0,
    },
};
/// Filament's `polygonOffsetConstant` (0.5 of a 16-bit unit) in
/// Depth32Float's units for depths in [0.5, 1).
pub const FILAMENT_POLYGON_OFFSET_UNITS: i32 = 128;
/// Filament's shadow pass for VSM: the material's culling, no offset.
pub const FILAMENT_VSM_PASS: MapPass = MapPass::Renderer {
    cull: Some(wgpu::Face::Back),
    bias: NO_DEPTH_BIAS,
};
/// Filament's `constantBias` outside VSM: 1 mm towards the light (its
/// shadow camera moved along the light's direction).
pub const FILAMENT_RECEIVER: ShadowBias = ShadowBias {
    toward_light_world: 0.001,
    ..ShadowBias::NONE
};
/// Filament's `normalBias` (1.0) outside VSM: texels along the normal,
/// times sin θ; a cascade takes half of it.
pub const FILAMENT_NORMAL_BIAS: f32 = 1.0;

/// Filament's normal offset in texels at the receiver, times sin θ: on a
/// spot `normalBias` texels (`normalBias × wsTexelSizeAtOneMeter × zLight`),
/// on a sun's cascade `0.5 × normalBias`.
pub fn filament_normal_texels(g: &LightGeometry) -> f32 {
    if g.perspective {
        FILAMENT_NORMAL_BIAS
    } else {
        0.5 * FILAMENT_NORMAL_BIAS
    }
}
/// Filament's PCSS taps (`PCSS_SHADOW_BLOCKER_SEARCH_TAP_COUNT`,
/// `PCSS_SHADOW_FILTER_TAP_COUNT`).
pub const FILAMENT_PCSS_TAPS: u32 = 16;
/// Bevy's cascade and spot map side (`DirectionalLightShadowMap::default`:
/// spot maps are layers of the directional texture).
pub const BEVY_DIRECTIONAL_MAP_SIZE: u32 = 2048;
/// Bevy's receiver offsets, a spot's (`SpotLight`) as a sun's
/// (`DirectionalLight`): 0.02 m towards the light, and 1.8 × √2 texels
/// along the normal (lesson 02's `ShadowBias::BEVY`).
pub const BEVY_RECEIVER: ShadowBias = ShadowBias::BEVY;
/// Bevy's shadow pass: the default `StandardMaterial` culls back faces,
/// no hardware depth offset (`material.depth_bias` 0).
pub const BEVY_PASS: MapPass = MapPass::Renderer {
    cull: Some(wgpu::Face::Back),
    bias: NO_DEPTH_BIAS,
};
/// three.js's shadow pass for PCF: a front-sided material's back faces
/// (`shadowSide[FrontSide]` is `BackSide`), no offset.
pub const THREEJS_PCF_PASS: MapPass = MapPass::Renderer {
    cull: Some(wgpu::Face::Front),
    bias: NO_DEPTH_BIAS,
};
/// three.js's shadow pass for VSM: the material's own side (front), no
/// offset.
pub const THREEJS_VSM_PASS: MapPass = MapPass::Renderer {
    cull: Some(wgpu::Face::Back),
    bias: NO_DEPTH_BIAS,
};
const NO_DEPTH_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: 0,
    slope_scale: 0.0,
    clamp: 0.0,
};
/// three.js's `PCFShadowMap` (r182): 5 Vogel taps, `radius` 1 texel.
pub const THREEJS_PCF_TAPS: u32 = 5;
/// Bevy's PCSS taps: eight D3D sample points, eight spiral taps.
pub const BEVY_PCSS_TAPS: u32 = 8;
/// Godot's Soft Low (the project default): 8 penumbra taps, and for its
/// PCF 4 taps on a disk of 2 texels (`shadows_quality_set`).
pub const GODOT_SOFT_LOW_TAPS: u32 = 8;
pub const GODOT_SOFT_LOW_PCF_TAPS: u32 = 4;
pub const GODOT_SOFT_LOW_RADIUS: f32 = 2.0;
/// Godot's atlas and splits are not emulated: the lesson's 1024² map.
pub const GODOT_MAP_SIZE: u32 = 1024;
/// Godot's `shadow_blur` default: the soft shadow's scale.
pub const GODOT_SHADOW_BLUR: f32 = 1.0;
/// Godot's `shadow_normal_bias` defaults: `Light3D`'s 1.0, and
/// `DirectionalLight3D`'s 2.0.
pub const GODOT_NORMAL_BIAS: f32 = 1.0;
pub const GODOT_DIRECTIONAL_NORMAL_BIAS: f32 = 2.0;
/// Godot's directional atlas (4096², 4 splits): 2048² a split.
pub const GODOT_DIRECTIONAL_MAP_SIZE: u32 = 2048;

/// Godot's `shadow_bias` defaults: `SpotLight3D`'s 0.03, `Light3D`'s 0.1
/// (a sun's), both divided by 100 and scaled by `soft_shadow_scale`.
pub const GODOT_SPOT_SHADOW_BIAS: f32 = 0.03;
pub const GODOT_DIRECTIONAL_SHADOW_BIAS: f32 = 0.1;
/// Godot's spot shadow camera's near plane over its range (0.005).
pub const GODOT_SPOT_NEAR_OVER_RANGE: f32 = 0.005;

/// Godot's receiver offsets for a filter of `soft_shadow_scale` `scale`
/// (its PCF's `shadow_blur × quality radius`, its soft shadow's
/// `shadow_blur`). Along the normal, in texels of the map at the receiver:
/// on a spot `normal * light_length * shadow_normal_bias * (1 − |cos θ|)`
/// with `shadow_normal_bias = normal_bias × 10 / shadow_size`, which is
/// `10 / (2 tan(cone / 2))` of the spot's texels at that distance
/// (`uv_per`, per radian); on a sun `shadow_normal_bias` (2) texels times
/// sin θ ([`Peer::receiver_normal_sin`]). Towards the light: a spot's
/// `shadow_bias / (light_length · inv_radius)` added to its clip depth is,
/// for its near plane of range / 200, a move of `shadow_bias · (1/0.005 −
/// 1)` metres whatever the distance; a sun's `shadow_bias` moves it along
/// the light (its split's `bias_scale` taken as 1).
pub fn godot_receiver(g: &LightGeometry, scale: f32) -> ShadowBias {
    if g.perspective {
        let bias = GODOT_SPOT_SHADOW_BIAS / 100.0 * scale;
        ShadowBias {
            normal: GODOT_NORMAL_BIAS * 10.0 * g.uv_per[0],
            toward_light_world: bias * (1.0 / GODOT_SPOT_NEAR_OVER_RANGE - 1.0),
            ..ShadowBias::NONE
        }
    } else {
        ShadowBias {
            toward_light_world: GODOT_DIRECTIONAL_SHADOW_BIAS / 100.0 * scale,
            ..ShadowBias::NONE
        }
    }
}

/// Godot's map side: a spot's atlas slot (quadrant 0 of the 4096² atlas,
/// subdivided by 2: the lesson's 1024²), a sun's first split (2048²).
pub fn godot_map_size(g: &LightGeometry) -> u32 {
    if g.perspective {
        GODOT_MAP_SIZE
    } else {
        GODOT_DIRECTIONAL_MAP_SIZE
    }
}
/// three.js's `LightShadow` defaults: `mapSize` 512, `radius` 1,
/// `blurSamples` 8.
pub const THREEJS_MAP_SIZE: u32 = 512;
pub const THREEJS_VSM_BLUR: ThreeVsmBlur = ThreeVsmBlur {
    samples: 8,
    radius: 1.0,
};
/// three.js's light-bleeding cut in `VSMShadow`: linstep(0.3, 0.95, p).
pub const THREEJS_VSM_BLEED: (f32, f32) = (0.3, 0.95);

/// Filament's VSM: an EVSM with `vsmExponent` 5.54 (16-bit moments), no
/// blur (`blurWidth` 0), `lightBleedReduction` 0.15, and the least variance
/// `(vsmDepthScale · depth)²` with `vsmDepthScale = minVarianceScale · 0.01
/// · vsmExponent` (`minVarianceScale` 0.5).
pub const FILAMENT_VSM_EXPONENT: f32 = 5.54;
pub const FILAMENT_MIN_VARIANCE_SCALE: f32 = 0.5;
pub const FILAMENT_LIGHT_BLEED_REDUCTION: f32 = 0.15;

pub fn filament_evsm() -> Variance {
    let depth_scale = FILAMENT_MIN_VARIANCE_SCALE * 0.01 * FILAMENT_VSM_EXPONENT;
    Variance {
        blur: 0,
        exponent: Some(FILAMENT_VSM_EXPONENT),
        negative: None,
        min_variance: depth_scale * depth_scale,
        bleed: (FILAMENT_LIGHT_BLEED_REDUCTION, 1.0),
    }
}

/// three.js's VSM: plain moments of the map's depth (as mean and standard
/// deviation), its blur, its cut.
pub fn threejs_vsm() -> (Variance, ThreeVsmBlur) {
    let v = Variance {
        blur: 0,
        exponent: None,
        negative: None,
        min_variance: 0.0,
        bleed: THREEJS_VSM_BLEED,
    };
    (v, THREEJS_VSM_BLUR)
}

/// The port named `variant` for a light of geometry `g`, or `None` if the
/// variant is the lesson's own.
pub fn port(variant: &str, g: &LightGeometry) -> Option<Peer> {
    Some(match variant {
        "filament_pcf" => Peer::FilamentPcf {
            normal_texels: filament_normal_texels(g),
        },
        // The spot's radius as its bulb; on a sun, Filament's default.
        "filament_pcss" => Peer::FilamentPcss {
            bulb_radius: if g.perspective {
                g.size
            } else {
                FILAMENT_BULB_RADIUS
            },
            normal_texels: filament_normal_texels(g),
        },
        "filament_evsm" => Peer::FilamentEvsm(filament_evsm()),
        "bevy_gaussian" => Peer::BevyCastano,
        "bevy_pcss_or_pcf" if g.perspective => Peer::BevyPcss { light_size: g.size },
        "bevy_pcss_or_pcf" => Peer::BevyCastano,
        "godot_pcf" => Peer::GodotPcf {
            taps: GODOT_SOFT_LOW_PCF_TAPS,
            radius: GODOT_SHADOW_BLUR * GODOT_SOFT_LOW_RADIUS,
            receiver: godot_receiver(g, GODOT_SHADOW_BLUR * GODOT_SOFT_LOW_RADIUS),
            map: godot_map_size(g),
        },
        "godot_soft_low" => Peer::GodotSoft {
            taps: GODOT_SOFT_LOW_TAPS,
            size: godot_soft_size(g),
            scale: GODOT_SHADOW_BLUR,
            receiver: godot_receiver(g, GODOT_SHADOW_BLUR),
            map: godot_map_size(g),
        },
        "threejs_pcf" => Peer::ThreePcf,
        "threejs_pcf_soft" => Peer::ThreePcfSoft,
        "threejs_vsm" => {
            let (v, blur) = threejs_vsm();
            Peer::ThreeVsm(v, blur)
        }
        _ => return None,
    })
}

impl Peer {
    /// Whether the renderer runs this filter by default, or a user turns
    /// it on (the card says with which setting).
    pub fn is_default(self) -> bool {
        matches!(
            self,
            Peer::FilamentPcf { .. } | Peer::BevyCastano | Peer::GodotPcf { .. } | Peer::ThreePcf
        )
    }

    /// Depth comparisons per pixel and light (search, filter) and the texels
    /// they read: the counters.
    pub fn taps(self) -> (u64, u64, u64) {
        match self {
            Peer::FilamentPcf { .. } => (0, 4, 16),
            Peer::FilamentPcss { .. } => {
                let n = FILAMENT_PCSS_TAPS as u64;
                (n, n, n + 4 * n)
            }
            // Bilinear depths to search, 2×2 comparisons to filter.
            Peer::BevyPcss { .. } => {
                let n = BEVY_PCSS_TAPS as u64;
                (n, n, 4 * n + 4 * n)
            }
            Peer::BevyCastano => (0, 9, 36),
            Peer::GodotPcf { taps, .. } => (0, taps as u64, 4 * taps as u64),
            Peer::GodotSoft { taps, .. } => (taps as u64, taps as u64, 8 * taps as u64),
            Peer::ThreePcf => {
                let n = THREEJS_PCF_TAPS as u64;
                (0, n, 4 * n)
            }
            Peer::ThreePcfSoft => (0, 16, 16),
            // Four texels of the blurred moments; the blur reads its own.
            Peer::FilamentEvsm(_) | Peer::ThreeVsm(..) => (0, 1, 4),
        }
    }

    /// A variance map's moments and, for three.js, its blur.
    pub fn variance(self) -> Option<(Variance, Option<ThreeVsmBlur>)> {
        match self {
            Peer::FilamentEvsm(v) => Some((v, None)),
            Peer::ThreeVsm(v, b) => Some((v, Some(b))),
            _ => None,
        }
    }

    /// The shader's `mode` (peers.wgsl's constants).
    pub fn mode(self) -> u32 {
        match self {
            Peer::ThreePcfSoft => 5,
            Peer::FilamentPcss { .. } => 7,
            Peer::BevyPcss { .. } => 8,
            Peer::BevyCastano => 9,
            Peer::GodotSoft { .. } => 10,
            Peer::FilamentPcf { .. } => 11,
            Peer::GodotPcf { .. } => 12,
            Peer::ThreePcf => 13,
            Peer::FilamentEvsm(_) => 3,
            // (mean, standard deviation) of the map's own depth: its own.
            Peer::ThreeVsm(..) => 6,
        }
    }

    /// three.js's `PCFSoftShadowMap` compares the nearest texel; the others
    /// blend 2×2.
    pub fn sampler(self) -> wgpu::FilterMode {
        match self {
            Peer::ThreePcfSoft => wgpu::FilterMode::Nearest,
            _ => wgpu::FilterMode::Linear,
        }
    }

    /// The renderer's default shadow map side.
    pub fn map_size(self) -> u32 {
        match self {
            Peer::FilamentPcf { .. } | Peer::FilamentPcss { .. } | Peer::FilamentEvsm(_) => {
                FILAMENT_MAP_SIZE
            }
            // Spot maps are layers of Bevy's directional texture.
            Peer::BevyPcss { .. } | Peer::BevyCastano => BEVY_DIRECTIONAL_MAP_SIZE,
            // Godot's atlas is not emulated: the lesson's map (its card).
            Peer::GodotPcf { map, .. } | Peer::GodotSoft { map, .. } => map,
            Peer::ThreePcf | Peer::ThreePcfSoft | Peer::ThreeVsm(..) => THREEJS_MAP_SIZE,
        }
    }

    /// How the renderer draws its map: which faces, what hardware offset.
    pub fn map_pass(self) -> MapPass {
        match self {
            Peer::FilamentPcf { .. } | Peer::FilamentPcss { .. } => FILAMENT_PASS,
            Peer::FilamentEvsm(_) => FILAMENT_VSM_PASS,
            Peer::BevyPcss { .. } | Peer::BevyCastano => BEVY_PASS,
            Peer::ThreePcf | Peer::ThreePcfSoft => THREEJS_PCF_PASS,
            Peer::ThreeVsm(..) => THREEJS_VSM_PASS,
            // Godot's shadow pass was not read to its lines: the lesson's.
            Peer::GodotPcf { .. } | Peer::GodotSoft { .. } => MapPass::Lesson,
        }
    }

    /// The receiver's offsets before its lookup, as the renderer moves it
    /// (lesson 03's `peer_receiver`): none where its defaults are 0 (three.js)
    /// or its moments take none (the variance maps).
    pub fn receiver_bias(self) -> ShadowBias {
        match self {
            Peer::BevyPcss { .. } | Peer::BevyCastano => BEVY_RECEIVER,
            Peer::FilamentPcf { .. } | Peer::FilamentPcss { .. } => FILAMENT_RECEIVER,
            Peer::GodotPcf { receiver, .. } | Peer::GodotSoft { receiver, .. } => receiver,
            _ => ShadowBias::NONE,
        }
    }

    /// Texels along the normal × sin θ, which `ShadowBias` has no field
    /// for: Filament's normal bias outside VSM, and Godot's on a sun (the
    /// Godot port whose map is a sun's 2048² split).
    pub fn receiver_normal_sin(self) -> f32 {
        match self {
            Peer::GodotPcf { map, .. } | Peer::GodotSoft { map, .. }
                if map == GODOT_DIRECTIONAL_MAP_SIZE =>
            {
                GODOT_DIRECTIONAL_NORMAL_BIAS
            }
            Peer::FilamentPcf { normal_texels } | Peer::FilamentPcss { normal_texels, .. } => {
                normal_texels
            }
            _ => 0.0,
        }
    }

    /// The port's parameters, as the lit pass's uniform takes them.
    pub fn params(self) -> PeerParams {
        let none = PeerParams {
            taps: 0,
            receiver_plane: false,
            size: None,
            scale: 0.0,
            variance: None,
        };
        match self {
            Peer::FilamentPcss { bulb_radius, .. } => PeerParams {
                size: Some(bulb_radius),
                receiver_plane: true,
                ..none
            },
            Peer::BevyPcss { light_size } => PeerParams {
                size: Some(light_size),
                ..none
            },
            Peer::FilamentPcf { .. } | Peer::BevyCastano | Peer::ThreePcf | Peer::ThreePcfSoft => {
                none
            }
            Peer::GodotPcf { taps, radius, .. } => PeerParams {
                taps,
                scale: radius,
                ..none
            },
            Peer::GodotSoft {
                taps, size, scale, ..
            } => PeerParams {
                taps,
                size: Some(size),
                scale,
                ..none
            },
            Peer::FilamentEvsm(v) => PeerParams {
                variance: Some(v),
                ..none
            },
            Peer::ThreeVsm(v, _) => PeerParams {
                variance: Some(v),
                ..none
            },
        }
    }
}

/// What a port sets in the lit pass: its taps and receiver plane as its
/// pipeline's constants (`soft.rs` `SoftConstants`), the rest in its
/// uniform (`SoftUniform`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeerParams {
    /// Search and filter taps (Godot's, which its shader reads).
    pub taps: u32,
    pub receiver_plane: bool,
    /// The renderer's own light size, in its units; `None`: the scene's.
    pub size: Option<f32>,
    /// A second size (Godot's soft_shadow_scale).
    pub scale: f32,
    pub variance: Option<Variance>,
}

/// Godot's soft-shadow size for light geometry `g`: a spot's
/// `(size · 0.5 / range) / (half_np / z_near) · atlas_rect.width` in map
/// units, with `half_np / z_near = tan(spot_angle)`, the whole map as its
/// atlas rect and `size` the light's diameter, twice our radius; a
/// directional light's `softshadow_angle = tan(light_angular_distance)`,
/// the angle Godot's inspector calls the sun's angular diameter: twice our
/// angular radius (light_storage.cpp).
pub fn godot_soft_size(g: &LightGeometry) -> f32 {
    if g.perspective {
        // uv_per = 1 / (2 tan(spot_angle)).
        let tan_half = 0.5 / g.uv_per[0];
        let diameter = 2.0 * g.size;
        (diameter * 0.5 / g.far) / tan_half
    } else {
        (2.0 * g.size.atan()).tan()
    }
}
