//! Bevy's cards: its default Gaussian filter (`bevy_gaussian`) and its
//! PCSS on a spot (`bevy_pcss_or_pcf`).

use common::ports::{Constant, Departure, PortCard, Role, Source, Value, TAPS_UNIT};

const BEVY_SAMPLING: Source = Source {
    file: "crates/bevy_pbr/src/render/shadow_sampling.wgsl",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_SHADOWS: Source = Source {
    file: "crates/bevy_pbr/src/render/shadows.wgsl",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_UTILS: Source = Source {
    file: "crates/bevy_pbr/src/render/utils.wgsl",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_LIGHT: Source = Source {
    file: "crates/bevy_pbr/src/render/light.rs",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_SPOT: Source = Source {
    file: "crates/bevy_light/src/spot_light.rs",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_DIRECTIONAL: Source = Source {
    file: "crates/bevy_light/src/directional_light.rs",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_MATERIAL: Source = Source {
    file: "crates/bevy_pbr/src/pbr_material.rs",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_PREPASS: Source = Source {
    file: "crates/bevy_pbr/src/prepass/mod.rs",
    commit: BEVY_COMMIT,
    repository: None,
};
const BEVY_LIGHT_LIB: Source = Source {
    file: "crates/bevy_light/src/lib.rs",
    commit: BEVY_COMMIT,
    repository: None,
};
/// A commit on Bevy's main line (#23083, 2026-02-22); every file cited
/// below is byte-identical at 00ef04ec, where it was first read.
const BEVY_COMMIT: &str = "ea0d43eb67ab99d3ce157feffa7d2ea4bebcafd2";

/// Bevy's sources, in the order the two Bevy cards' constants index them.
const BEVY_SOURCES: &[Source] = &[
    BEVY_SAMPLING,
    BEVY_SHADOWS,
    BEVY_UTILS,
    BEVY_LIGHT,
    BEVY_SPOT,
    BEVY_DIRECTIONAL,
    BEVY_MATERIAL,
    BEVY_PREPASS,
    BEVY_LIGHT_LIB,
];

/// What both Bevy ports take: the map, the shadow pass, the receiver's
/// offsets, the default filter.
const BEVY_MAP_AND_PASS: [Constant; 11] = [
    Constant { name: "DirectionalLightShadowMap size (spots too)", value: Value::Num(2048.0), unit: "texels", source: 5, lines: "183, 193-204" },
    Constant { name: "spot maps", value: Value::Text("To control the resolution of the shadow maps, use the DirectionalLightShadowMap resource"), unit: "", source: 4, lines: "21" },
    Constant { name: "directional_light_shadow_map_texture", value: Value::Text("width and height directional_light_shadow_map.size, one layer per cascade and per spot"), unit: "", source: 3, lines: "1204-1216, 1372-1376" },
    Constant { name: "StandardMaterial cull_mode", value: Value::Text("Some(Face::Back), kept by the shadow (depth prepass) pipeline: front faces drawn"), unit: "", source: 6, lines: "922, 1539-1548" },
    Constant { name: "shadow pass DepthBiasState", value: Value::Text("constant material.depth_bias (0), slope_scale 0.0, clamp 0.0"), unit: "", source: 7, lines: "627-631; pbr_material.rs 926, 1553-1556" },
    Constant { name: "shadow_depth_bias (spot and directional)", value: Value::Num(0.02), unit: "m", source: 4, lines: "134" },
    Constant { name: "shadow_normal_bias (spot and directional)", value: Value::Num(1.8), unit: "texels", source: 4, lines: "136" },
    Constant { name: "spot normal bias", value: Value::Text("shadow_normal_bias * texel_size * SQRT_2, texel_size = 2 tan(outer_angle) / map size, times distance_to_light along the normal"), unit: "m", source: 3, lines: "515-516, 537-539" },
    Constant { name: "offset_position", value: Value::Text("shadow_depth_bias * normalize(surface_to_light) + surface_normal * shadow_normal_bias * distance_to_light"), unit: "m", source: 1, lines: "93-96" },
    Constant { name: "ShadowFilteringMethod", value: Value::Text("Gaussian, #[default]: sample_shadow_map_castano_thirteen, 9 bilinear comparisons, weights / 144"), unit: "", source: 8, lines: "288-289" },
    Constant { name: "shadow_maps_enabled", value: Value::Text("false by default on a spot and a sun: the default filter is the one a light gets when its shadows are switched on"), unit: "", source: 4, lines: "152" },
];

pub const BEVY_D3D_SAMPLE_POINT_POSITIONS: &[f64] = &[
    0.125, -0.375, -0.125, 0.375, 0.625, 0.125, -0.375, -0.625, //
    -0.625, 0.625, -0.875, -0.125, 0.375, 0.875, 0.875, -0.875,
];
/// Bevy's spiral, as written there (0.7071 is its rounding of 1/√2).
#[allow(clippy::approx_constant)]
pub const BEVY_SPIRAL_OFFSETS: &[f64] = &[
    -0.7071, 0.7071, -0.0000, -0.8750, 0.5303, 0.5303, -0.6250, -0.0000, //
    0.3536, -0.3536, -0.0000, 0.3750, -0.1768, -0.1768, 0.1250, 0.0000,
];

/// Where both Bevy ports depart from Bevy, bar the PCSS's own.
const BEVY_DEPARTURES: [Departure; 8] = [
    Departure { what: "cascades on a sun", why: "one 2048² map stands for Bevy's first cascade; the lesson fits it to the scene, not to Bevy's cascade splits, and Bevy's sun normal bias (shadow_normal_bias × √2 × the cascade's square texel, ceil(diameter) / 2048: light.rs 659-661, shadows.wgsl 190-193) is taken on the fitted map's texel (its larger side), which can differ from it several-fold" },
    Departure { what: "its spot's near and far planes", why: "Bevy clips casters nearer than 0.1 m and has no far plane; the lesson's spot map runs from range / 1000 to the range (no lesson 10 scene has a caster within 0.1 m of its light)" },
    Departure { what: "a sun's unclipped depth", why: "Bevy draws a sun's casters in front of the map with unclipped depth (light.rs 1852-1856); the lesson's map is fitted around every caster, so none lies in front of it" },
    Departure { what: "the map's rotation about the light's axis", why: "Bevy builds the light's basis with orthonormalize (spot_light.rs 172-193), the lesson with look_at and a stable up: the texel grid and the kernels' patterns turn by another angle, their statistics do not" },
    Departure { what: "the normal it offsets along", why: "Bevy takes the interpolated world_normal as the mesh has it, not normalized, on the side it was drawn; the port normalizes it and turns it to the light's side (lesson 03's peer_receiver)" },
    Departure { what: "the texel its spot normal bias scales", why: "Bevy's spot texel is 2 tan(outer_angle) / 2048 at unit distance; the port takes the map's texel (its larger side) at the receiver, the same where the map's cone is the spot's (as in every lesson 10 scene)" },
    Departure { what: "its infinite reversed depth", why: "the lesson's map is finite and forward (Depth32Float): the comparisons' outcomes agree up to its rounding, about 0.1 mm at 4 m from the default scene's spot" },
    Departure { what: "MSAA (Msaa::Sample4 by default)", why: "the lesson renders one sample per pixel: only geometric edges differ" },
];

pub const BEVY_GAUSSIAN: PortCard = PortCard {
    variant: "bevy_gaussian",
    renderer: "Bevy",
    role: Role::Default,
    repository: "bevyengine/bevy",
    sources: BEVY_SOURCES,
    constants: &[
        BEVY_MAP_AND_PASS[0],
        BEVY_MAP_AND_PASS[1],
        BEVY_MAP_AND_PASS[2],
        BEVY_MAP_AND_PASS[3],
        BEVY_MAP_AND_PASS[4],
        BEVY_MAP_AND_PASS[5],
        BEVY_MAP_AND_PASS[6],
        BEVY_MAP_AND_PASS[7],
        BEVY_MAP_AND_PASS[8],
        BEVY_MAP_AND_PASS[9],
        BEVY_MAP_AND_PASS[10],
        Constant {
            name: "sample_shadow_map_castano_thirteen",
            value: Value::Text("lesson 03's pcf_castano13, Bevy's lines"),
            unit: "",
            source: 0,
            lines: "105-147, 256-264",
        },
        Constant {
            name: "soft_shadows_enabled",
            value: Value::Text("false: no PCSS on a spot"),
            unit: "",
            source: 4,
            lines: "160-161",
        },
    ],
    departures: &BEVY_DEPARTURES,
};

pub const BEVY_PCSS_OR_PCF: PortCard = PortCard {
    variant: "bevy_pcss_or_pcf",
    renderer: "Bevy",
    role: Role::Option("the experimental_pbr_pcss feature, and SpotLight::soft_shadows_enabled with a radius"),
    repository: "bevyengine/bevy",
    sources: BEVY_SOURCES,
    constants: &[
        BEVY_MAP_AND_PASS[0],
        BEVY_MAP_AND_PASS[1],
        BEVY_MAP_AND_PASS[2],
        BEVY_MAP_AND_PASS[3],
        BEVY_MAP_AND_PASS[4],
        BEVY_MAP_AND_PASS[5],
        BEVY_MAP_AND_PASS[6],
        BEVY_MAP_AND_PASS[7],
        BEVY_MAP_AND_PASS[8],
        BEVY_MAP_AND_PASS[9],
        BEVY_MAP_AND_PASS[10],
        Constant { name: "soft_shadows_enabled", value: Value::Text("false by default, behind the experimental_pbr_pcss feature"), unit: "", source: 4, lines: "79-80, 160-161" },
        Constant { name: "depth (spot)", value: Value::Text("near_z / -projected_position.z: reversed and infinite"), unit: "", source: 1, lines: "112" },
        Constant { name: "DEFAULT_SHADOW_MAP_NEAR_Z (spot)", value: Value::Num(0.1), unit: "m", source: 4, lines: "138" },
        Constant { name: "spot PCSS call", value: Value::Text("sample_shadow_map_pcss(shadow_uv, depth, array_index, frag_coord_xy, SPOT_SHADOW_TEXEL_SIZE, soft_shadow_size) when soft_shadow_size > 0"), unit: "", source: 1, lines: "116-125" },
        Constant { name: "soft_shadow_size (spot)", value: Value::Text("light.radius when soft_shadows_enabled, else 0"), unit: "m", source: 3, lines: "1095-1099" },
        Constant { name: "SPOT_SHADOW_TEXEL_SIZE", value: Value::Num(0.0134277345), unit: "texel_size units", source: 0, lines: "71" },
        Constant { name: "shadow_map_size", value: Value::Text("textureDimensions(directional_shadow_textures): the spot's map is a layer of the directional texture"), unit: "texels", source: 0, lines: "170, 228" }, // not a counter: Bevy's shader variable
        Constant { name: "D3D_SAMPLE_POINT_POSITIONS", value: Value::List(BEVY_D3D_SAMPLE_POINT_POSITIONS), unit: "search radii", source: 0, lines: "79-88" },
        Constant { name: "blocker test", value: Value::Text("sampled_depth >= depth, linearly filtered depth"), unit: "", source: 0, lines: "46-61" },
        Constant { name: "search uv_offset_scale", value: Value::Text("search_size / (texel_size * shadow_map_size)"), unit: "uv", source: 0, lines: "229" },
        Constant { name: "no blocker", value: Value::Text("z_blocker 0.0 (the filter still runs)"), unit: "", source: 0, lines: "250-252" },
        Constant { name: "blur_size", value: Value::Text("max((z_blocker - depth) * light_size / depth, 0.5)"), unit: "", source: 0, lines: "303" },
        Constant { name: "Jimenez spacing", value: Value::Text("map(0.00390625, 0.022949219, 0.015, 0.035, texel_size) * blur_size / (texel_size * shadow_map_size)"), unit: "uv", source: 0, lines: "169-175" },
        Constant { name: "SPIRAL_OFFSET_0_..7_", value: Value::List(BEVY_SPIRAL_OFFSETS), unit: "filter radii", source: 2, lines: "88-95" },
        Constant { name: "random_rotation_matrix", value: Value::Text("2 PI * interleaved_gradient_noise(frag_coord, 1) when not temporal; mat2x2(m.y, -m.x, m.x, m.y), m = (sin, cos)"), unit: "", source: 0, lines: "156-164" },
        Constant { name: "interleaved_gradient_noise", value: Value::Text("fract(52.9829189 * fract(0.06711056 * x + 0.00583715 * y)), xy + 5.588238 * (frame % 64)"), unit: "", source: 2, lines: "72-75" },
        Constant { name: "PCSS taps", value: Value::Num(8.0), unit: TAPS_UNIT, source: 0, lines: "177-209, 221-254" },
        Constant { name: "soft_shadow_size (directional)", value: Value::Text("None by default: no PCSS on a sun"), unit: "", source: 5, lines: "116, 158" },
    ],
    departures: &[
        Departure { what: "PCSS on a sun", why: "Bevy's directional PCSS takes soft_shadow_size, a world-space search radius no sun angle gives; the port leaves it None there and runs Bevy's default Gaussian (as bevy_gaussian), and says so in its name" },
        BEVY_DEPARTURES[0],
        BEVY_DEPARTURES[1],
        BEVY_DEPARTURES[2],
        BEVY_DEPARTURES[3],
        BEVY_DEPARTURES[4],
        BEVY_DEPARTURES[5],
        Departure { what: "its infinite reversed depth", why: "the lesson's map is finite and forward; since it is affine in 1/d, each tap's near_z / d follows from it, exactly in algebra and up to Depth32Float's rounding in fact (about 0.1 mm at 4 m here, against Bevy's 2 cm depth bias)" },
        BEVY_DEPARTURES[7],
    ],
};
