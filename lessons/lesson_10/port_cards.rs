//! The cards of lesson 10's ports ([`common::ports`]): for each renderer,
//! its default shadow filter and the soft options a user turns on, the
//! files and commits each was read at, every constant and formula the port
//! takes from there with its lines (the map's size, the faces its shadow
//! pass draws, its offsets, its kernel), and what the port cannot do here.
//! `tests/port_cards_lesson_10.rs` checks each port ([`super::peers`],
//! `shaders/lesson_10/peers.wgsl`) against its card; the chapter's "where
//! each port departs" table is made from these.
//!
//! Line numbers were read in the files' stored text at the commits named.

use common::ports::{Constant, Departure, PortCard, Role, Source, Value};

const FILAMENT_SHADER: Source = Source {
    file: "shaders/src/surface_shadowing.fs",
    commit: "f366ac3a35118848a4b59182c286a09c3205d004",
    repository: None,
};
const FILAMENT_MANAGER: Source = Source {
    file: "filament/src/ShadowMapManager.cpp",
    commit: "cb91a23a03f62cb09f2f77217e9e98ea69f0813d",
    repository: None,
};
const FILAMENT_JAVA: Source = Source {
    file: "android/filament-android/src/main/java/com/google/android/filament/LightManager.java",
    commit: "c35a60808c9b24bb2699f72f36dc2aa0e1f5087a",
    repository: None,
};
const FILAMENT_VIEW: Source = Source {
    file: "filament/src/PerViewUniforms.cpp",
    commit: "cb91a23a03f62cb09f2f77217e9e98ea69f0813d",
    repository: None,
};
const FILAMENT_OPTIONS: Source = Source {
    file: "filament/include/filament/Options.h",
    commit: "2fac13e154fb1a64bbca70e5857838d319957e9c",
    repository: None,
};
const FILAMENT_RENDER_PASS: Source = Source {
    file: FILAMENT_RENDER_PASS_FILE,
    commit: FILAMENT_RENDER_PASS_COMMIT,
    repository: None,
};
const FILAMENT_RENDER_PASS_FILE: &str = "filament/src/RenderPass.cpp";
const FILAMENT_RENDER_PASS_COMMIT: &str = "fc9e5e249800cbcd2b438eda1ae0001dcb25de5d";
const FILAMENT_SHADOW_MAP: Source = Source {
    file: "filament/src/ShadowMap.cpp",
    commit: "0362f36ef6e6017426730cbbb68e7af1fda2f38c",
    repository: None,
};
const FILAMENT_COMMON_SHADOWING: Source = Source {
    file: "shaders/src/common_shadowing.glsl",
    commit: "7c0643f122bbb9c7d61f15ba4e1c5f6db2460515",
    repository: None,
};
const FILAMENT_GETTERS: Source = Source {
    file: "shaders/src/surface_getters.fs",
    commit: "24a7bc2799eee5e5694b5df2adea457727ae25d8",
    repository: None,
};
const FILAMENT_MATERIAL_BUILDER: Source = Source {
    file: "libs/filamat/include/filamat/MaterialBuilder.h",
    commit: "cb91a23a03f62cb09f2f77217e9e98ea69f0813d",
    repository: None,
};
/// The sources of the PCF and PCSS cards, in the order their constants
/// index them.
const FILAMENT_PCF_SOURCES: &[Source] = &[
    FILAMENT_SHADER,
    FILAMENT_MANAGER,
    FILAMENT_JAVA,
    FILAMENT_OPTIONS,
    FILAMENT_RENDER_PASS,
    FILAMENT_SHADOW_MAP,
    FILAMENT_COMMON_SHADOWING,
    FILAMENT_GETTERS,
    FILAMENT_MATERIAL_BUILDER,
];

/// Filament's shadow pass and receiver outside VSM (`filament_pcf`,
/// `filament_pcss`, sources [`FILAMENT_PCF_SOURCES`]).
const FILAMENT_PCF_PASS: [Constant; 9] = [
    Constant { name: "polygonOffsetSlope, polygonOffsetConstant", value: Value::List(&[2.0, 0.5]), unit: "", source: 2, lines: "318, 309" },
    Constant { name: "polygonOffset", value: Value::Text("-polygonOffsetSlope, -polygonOffsetConstant, 0 when the view has VSM"), unit: "", source: 1, lines: "362-364, 521-523" },
    Constant { name: "constantBias", value: Value::Num(0.001), unit: "m", source: 2, lines: "249" },
    Constant { name: "constantBias applied", value: Value::Text("the light camera moved by translation(direction * constantBias), 0 under VSM"), unit: "m", source: 5, lines: "246-247, 301-302" },
    Constant { name: "normalBias", value: Value::Num(1.0), unit: "", source: 2, lines: "255" },
    Constant { name: "normalBias scaled", value: Value::Text("a cascade 0.5 * normalBias * wsTexelSize; a spot normalBias * wsTexelSizeAtOneMeter, times zLight (surface_getters.fs 115)"), unit: "m", source: 1, lines: "387-391, 556-563" },
    Constant { name: "computeLightSpacePosition", value: Value::Text("p += n * (sinTheta * b), sinTheta = sqrt(1 - NoL * NoL), not under VSM"), unit: "", source: 6, lines: "14-20" },
    Constant { name: "shadow pass culling", value: Value::Text("cmdDepth.primitive.rasterState.culling = mi->getCullingMode()"), unit: "", source: 4, lines: "551" },
    Constant { name: "mCullingMode", value: Value::Text("CullingMode::BACK by default: front faces drawn"), unit: "", source: 8, lines: "406, 762" },
];

/// Where Filament's PCF and PCSS ports depart from Filament.
const FILAMENT_PCF_DEPARTURES: [Departure; 7] = [
    Departure { what: "its 16-bit map", why: "Filament renders these maps as DEPTH16; the lesson's is Depth32Float: with Filament's 1 cm spot near plane one 16-bit step is about 4 cm at 5 m, which its 1 mm constant bias cannot span; the port's depth is finer. Its polygon offset's constant, 0.5 of a 16-bit unit (7.6e-6 of depth), is drawn as 128 units of Depth32Float's 2^-24 (the same for depths in [0.5, 1), twice as much below 0.5); its slope, 2, as it is" },
    Departure { what: "the angle of a spot's normal bias", why: "Filament's spot passes the light's direction to computeLightSpacePosition (surface_getters.fs getSpotLightSpacePosition); its sign was not read to its lines: if it is the axis away from the light, NoL is 0 on every lit face and each moves the full normalBias texels. The port takes sin θ from the point's own ray to the light" },
    Departure { what: "the normal and the faces it shades", why: "Filament takes the geometric normal as it is and skips the lookup where NoL <= 0; the port turns the normal to the light's side and looks up everywhere (the lesson's receivers are lit from their light's side); the directional offset is per vertex in Filament, per pixel here" },
    Departure { what: "its 1-texel border", why: "Filament projects onto 1022² inside the 1024² texture (viewport 1, 1, dim - 2) and clamps taps to it (ShadowMapManager.cpp 304, 360, 518); the port projects onto the whole 1024²" },
    Departure { what: "LiSPSM on a sun", why: "the Java mirror the card cites has lispsm = false (LightManager.java 301); C++'s ShadowOptions::lispsm was not read at a commit the card names. The port's sun map is not warped" },
    Departure { what: "its shadow camera's fit and near and far planes", why: "the lesson's map planes (its light_view_proj); the 1 mm constant bias is a move of the receiver towards the light along its ray (Filament's along the spot's axis: 1 mm × (1 − cos) apart)" },
    Departure { what: "one Filament", why: "the cited files come from several commits (the shader, the manager, ShadowMap.cpp and RenderPass.cpp do not all call each other with the signatures at those commits); each constant is read where cited, and the sampling quality that picks ShadowSample_PCF_Low (Material::Builder::shadowSamplingQuality, LOW by default) was not read to its lines" },
];

/// Filament's sides of a light the ports cannot take.
const FILAMENT_TAA: Departure = Departure {
    what: "TAA (temporalNoise)",
    why: "the workbook renders single frames; Filament's temporal rotation needs TAA to average it",
};

/// Filament's first 16 Poisson points, as lines 93-96 list them (x, y).
pub const FILAMENT_POISSON_16: &[f64] = &[
    0.511749, 0.547686, 0.58929, 0.257224, 0.165018, 0.57663, 0.407692, 0.742285, //
    0.707012, 0.646523, 0.31463, 0.466825, 0.801257, 0.485186, 0.418136, 0.146517, //
    0.579889, 0.0368284, 0.79801, 0.140114, -0.0413185, 0.371455, -0.0529108, 0.627352, //
    0.0821375, 0.882071, 0.17308, 0.301207, -0.120452, 0.867216, 0.371096, 0.916454,
];

pub const FILAMENT_PCF: PortCard = PortCard {
    variant: "filament_pcf",
    renderer: "Filament",
    role: Role::Default,
    repository: "google/filament",
    sources: FILAMENT_PCF_SOURCES,
    constants: &[
        Constant {
            name: "ShadowType",
            value: Value::Text("PCF, the default"),
            unit: "",
            source: 3,
            lines: "545-546",
        },
        Constant {
            name: "ShadowSample_PCF_Low",
            value: Value::Text(
                "4 hardware 2x2 comparisons weighted uw * vw, sum * (1.0 / 16.0): Castaño's 3x3",
            ),
            unit: "",
            source: 0,
            lines: "40-74",
        },
        Constant {
            name: "uw, vw",
            value: Value::Text("vec2(3.0 - 2.0 * st, 1.0 + 2.0 * st)"),
            unit: "",
            source: 0,
            lines: "59-60",
        },
        Constant {
            name: "u, v",
            value: Value::Text("vec2((2.0 - st) / uw.x - 1.0, st / uw.y + 1.0) * texelSize"),
            unit: "texels",
            source: 0,
            lines: "62-66",
        },
        FILAMENT_PCF_PASS[0],
        FILAMENT_PCF_PASS[1],
        FILAMENT_PCF_PASS[2],
        FILAMENT_PCF_PASS[3],
        FILAMENT_PCF_PASS[4],
        FILAMENT_PCF_PASS[5],
        FILAMENT_PCF_PASS[6],
        FILAMENT_PCF_PASS[7],
        FILAMENT_PCF_PASS[8],
        Constant {
            name: "mapSize",
            value: Value::Num(1024.0),
            unit: "texels",
            source: 2,
            lines: "194",
        },
    ],
    departures: &FILAMENT_PCF_DEPARTURES,
};

pub const FILAMENT_PCSS: PortCard = PortCard {
    variant: "filament_pcss",
    renderer: "Filament",
    role: Role::Option("View::setShadowType(ShadowType::PCSS)"),
    repository: "google/filament",
    sources: FILAMENT_PCF_SOURCES,
    constants: &[
        Constant { name: "ShadowType", value: Value::Text("PCSS, an option (PCF is the default)"), unit: "", source: 3, lines: "545-549" },
        Constant { name: "poissonDisk[0..16]", value: Value::List(FILAMENT_POISSON_16), unit: "disk radii", source: 0, lines: "92-96" },
        Constant { name: "PCSS_SHADOW_BLOCKER_SEARCH_TAP_COUNT", value: Value::Num(16.0), unit: "taps", source: 0, lines: "114" },
        Constant { name: "PCSS_SHADOW_FILTER_TAP_COUNT", value: Value::Num(16.0), unit: "taps", source: 0, lines: "116" },
        Constant { name: "getRandomRotationMatrix", value: Value::Text("interleavedGradientNoise(fragCoord) * (2.0 * PI), temporalNoise 0 without TAA"), unit: "radians", source: 0, lines: "139-146" },
        Constant { name: "getPenumbraLs", value: Value::Text("bulbRadiusLs, / zLight for a spot"), unit: "texels", source: 0, lines: "148-158" },
        Constant { name: "penumbraRatio (directional)", value: Value::Text("(z_blocker - z_receiver) / (1.0 - z_blocker)"), unit: "reversed depth", source: 0, lines: "171" },
        Constant { name: "penumbraRatio (spot)", value: Value::Text("(nearOverFarMinusNear + z_blocker) / (nearOverFarMinusNear + z_receiver) - 1.0"), unit: "reversed depth", source: 0, lines: "177" },
        Constant { name: "z_occSum", value: Value::Text("z_occSum += z_occ * occluded (the blockers' depths, not distances)"), unit: "reversed depth", source: 0, lines: "207" },
        Constant { name: "occluded", value: Value::Text("step(z_bias, dz), z_bias = dot(dz_duv, duv): receiver-plane bias per tap"), unit: "", source: 0, lines: "203-205" },
        Constant { name: "filterPCSS", value: Value::Text("the same points, radius texelSize * (penumbra * penumbraRatio), each a 2x2 bilinear comparison"), unit: "", source: 0, lines: "211-245, 330-333" },
        Constant { name: "early exit", value: Value::Text("z_occSum == 0.0 returns 1.0"), unit: "", source: 0, lines: "324-326" },
        Constant { name: "nearOverFarMinusNear", value: Value::Text("n / (f - n), n the shadow camera's near, f its culling far"), unit: "", source: 1, lines: "559-566" },
        Constant { name: "bulbRadiusLs", value: Value::Text("penumbraScale * shadowBulbRadius / wsTexelSize (texel size at 1 m)"), unit: "texels", source: 1, lines: "392-393, 568-569" },
        Constant { name: "shadowBulbRadius", value: Value::Num(0.02), unit: "m", source: 2, lines: "367-371" },
        Constant { name: "mapSize", value: Value::Num(1024.0), unit: "texels", source: 2, lines: "194" },
        Constant { name: "penumbraScale", value: Value::Num(1.0), unit: "", source: 3, lines: "609" },
        Constant { name: "penumbraRatioScale", value: Value::Num(1.0), unit: "", source: 3, lines: "617" },
        FILAMENT_PCF_PASS[0],
        FILAMENT_PCF_PASS[1],
        FILAMENT_PCF_PASS[2],
        FILAMENT_PCF_PASS[3],
        FILAMENT_PCF_PASS[4],
        FILAMENT_PCF_PASS[5],
        FILAMENT_PCF_PASS[6],
        FILAMENT_PCF_PASS[7],
        FILAMENT_PCF_PASS[8],
    ],
    departures: &[
        FILAMENT_PCF_DEPARTURES[0],
        FILAMENT_PCF_DEPARTURES[1],
        FILAMENT_PCF_DEPARTURES[2],
        FILAMENT_PCF_DEPARTURES[3],
        FILAMENT_PCF_DEPARTURES[4],
        FILAMENT_PCF_DEPARTURES[6],
        Departure { what: "its shadow camera's near and far planes", why: "the ratio uses the lesson's map planes (its light_view_proj), not Filament's own fit of the camera to the scene (its spot near plane is 1 cm)" },
        Departure { what: "the bulb radius of a spot", why: "the scene's emitter radius stands in for shadowBulbRadius (a user would set it so); on a sun Filament's default 2 cm is kept, since its directional penumbra does not follow the sun's angle" },
        Departure { what: "its interleaved gradient noise's constants", why: "lesson 03's rotation_angle (Jimenez 2014's 0.06711056, 0.00583715, 52.9829189); Filament's common_math.fs was not read" },
        Departure { what: "its disk's shape on a sun", why: "Filament's disk is round in texels (one wsTexelSize), the port's round in world units (the map's two uv_per); they differ where the fitted map's texels are not square" },
        FILAMENT_TAA,
    ],
};

pub const FILAMENT_EVSM: PortCard = PortCard {
    variant: "filament_evsm",
    renderer: "Filament",
    role: Role::Option("View::setShadowType(ShadowType::VSM)"),
    repository: "google/filament",
    sources: &[FILAMENT_SHADER, FILAMENT_VIEW, FILAMENT_OPTIONS, FILAMENT_JAVA, FILAMENT_MANAGER, FILAMENT_RENDER_PASS, FILAMENT_MATERIAL_BUILDER, FILAMENT_COMMON_SHADOWING],
    constants: &[
        Constant { name: "vsmExponent (16-bit moments)", value: Value::Num(5.54), unit: "", source: 1, lines: "329, 345" },
        Constant { name: "vsmDepthScale", value: Value::Text("minVarianceScale * 0.01f * vsmExponent"), unit: "", source: 1, lines: "346" },
        Constant { name: "minVarianceScale", value: Value::Num(0.5), unit: "", source: 2, lines: "591" },
        Constant { name: "lightBleedReduction", value: Value::Num(0.15), unit: "", source: 2, lines: "596" },
        Constant { name: "minVariance", value: Value::Text("(vsmDepthScale * depth)^2 of the warped depth"), unit: "", source: 0, lines: "441-445" },
        Constant { name: "EVSM warp", value: Value::Text("exp(vsmExponent * (2 * depth - 1)), depth linear in [0, 1]"), unit: "", source: 0, lines: "451, 464-468" },
        Constant { name: "reduceLightBleed", value: Value::Text("linstep(amount, 1.0, pMax)"), unit: "", source: 0, lines: "421-424" },
        Constant { name: "chebyshevUpperBound", value: Value::Text("mean <= moments.x ? 1.0 : pMax"), unit: "", source: 0, lines: "426-439" },
        Constant { name: "ELVSM", value: Value::Text("off by default (LightManager.java 359): the positive warp alone"), unit: "", source: 0, lines: "470-472" },
        Constant { name: "filtering", value: Value::Text("LINEAR, no mipmaps, no anisotropy"), unit: "", source: 1, lines: "331-340" },
        Constant { name: "blurWidth", value: Value::Num(0.0), unit: "texels", source: 3, lines: "365" },
        Constant { name: "mapSize", value: Value::Num(1024.0), unit: "texels", source: 3, lines: "194" },
        Constant { name: "offsets under VSM", value: Value::Text("constantBias, normalBias and the polygon offset are ignored when the View's ShadowType is VSM"), unit: "", source: 3, lines: "247, 253, 307, 316" },
        Constant { name: "polygonOffset", value: Value::Text("0 when the view has VSM"), unit: "", source: 4, lines: "362-364, 521-523" },
        Constant { name: "normalBias under VSM", value: Value::Text("0: shadowMapInfo.vsm ? 0.0f : ..., and computeLightSpacePosition moves nothing under VARIANT_HAS_VSM"), unit: "", source: 4, lines: "387, 556" },
        Constant { name: "shadow pass culling", value: Value::Text("cmdDepth.primitive.rasterState.culling = mi->getCullingMode()"), unit: "", source: 5, lines: "551" },
        Constant { name: "mCullingMode", value: Value::Text("CullingMode::BACK by default: front faces drawn"), unit: "", source: 6, lines: "406, 762" },
    ],
    departures: &[
        Departure { what: "16-bit moments", why: "the moments are 32-bit floats in a storage buffer (GL renders no float targets); the exponent stays the 16-bit one, 5.54" },
        Departure { what: "MSAA of the moments", why: "msaaSamples is 1 by default: nothing to emulate" },
        Departure { what: "its shadow camera's near and far planes", why: "the moments warp the lesson's linear depth between its map planes, not Filament's own fit of the camera" },
    ],
};

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
        Constant { name: "shadow_map_size", value: Value::Text("textureDimensions(directional_shadow_textures): the spot's map is a layer of the directional texture"), unit: "texels", source: 0, lines: "170, 228" },
        Constant { name: "D3D_SAMPLE_POINT_POSITIONS", value: Value::List(BEVY_D3D_SAMPLE_POINT_POSITIONS), unit: "search radii", source: 0, lines: "79-88" },
        Constant { name: "blocker test", value: Value::Text("sampled_depth >= depth, linearly filtered depth"), unit: "", source: 0, lines: "46-61" },
        Constant { name: "search uv_offset_scale", value: Value::Text("search_size / (texel_size * shadow_map_size)"), unit: "uv", source: 0, lines: "229" },
        Constant { name: "no blocker", value: Value::Text("z_blocker 0.0 (the filter still runs)"), unit: "", source: 0, lines: "250-252" },
        Constant { name: "blur_size", value: Value::Text("max((z_blocker - depth) * light_size / depth, 0.5)"), unit: "", source: 0, lines: "303" },
        Constant { name: "Jimenez spacing", value: Value::Text("map(0.00390625, 0.022949219, 0.015, 0.035, texel_size) * blur_size / (texel_size * shadow_map_size)"), unit: "uv", source: 0, lines: "169-175" },
        Constant { name: "SPIRAL_OFFSET_0_..7_", value: Value::List(BEVY_SPIRAL_OFFSETS), unit: "filter radii", source: 2, lines: "88-95" },
        Constant { name: "random_rotation_matrix", value: Value::Text("2 PI * interleaved_gradient_noise(frag_coord, 1) when not temporal; mat2x2(m.y, -m.x, m.x, m.y), m = (sin, cos)"), unit: "", source: 0, lines: "156-164" },
        Constant { name: "interleaved_gradient_noise", value: Value::Text("fract(52.9829189 * fract(0.06711056 * x + 0.00583715 * y)), xy + 5.588238 * (frame % 64)"), unit: "", source: 2, lines: "72-75" },
        Constant { name: "PCSS taps", value: Value::Num(8.0), unit: "taps", source: 0, lines: "177-209, 221-254" },
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

const GODOT_SHADER: Source = Source {
    file: "servers/rendering/renderer_rd/shaders/scene_forward_lights_inc.glsl",
    commit: "8bae2a49c6fb4ac65abbe9d0b5265fcb06e8b1d7",
    repository: None,
};
const GODOT_STORAGE: Source = Source {
    file: "servers/rendering/renderer_rd/storage_rd/light_storage.cpp",
    commit: "8403baa5a1e36485516c769a6393e056ed55192a",
    repository: None,
};
const GODOT_RENDER: Source = Source {
    file: "servers/rendering/renderer_rd/renderer_scene_render_rd.cpp",
    commit: "238862bddb647a832b4be38791b86f882b20af6a",
    repository: None,
};
const GODOT_LIGHT: Source = Source {
    file: "scene/3d/light_3d.cpp",
    commit: "8ea4ec9531e385802c08b97cb214e2de03056ddc",
    repository: None,
};
const GODOT_HEADER: Source = Source {
    file: "servers/rendering/renderer_rd/storage_rd/light_storage.h",
    commit: "05c838b763fd7907910773cd73e4d10c97f289dd",
    repository: None,
};
const GODOT_CULL: Source = Source {
    file: "servers/rendering/renderer_scene_cull.cpp",
    commit: "e2deec67b9b3258f1c4fc7ee8c9a375676a0571a",
    repository: None,
};
const GODOT_SOURCES: &[Source] = &[
    GODOT_SHADER,
    GODOT_STORAGE,
    GODOT_RENDER,
    GODOT_LIGHT,
    GODOT_HEADER,
    GODOT_CULL,
];

/// What both Godot ports take: the receiver's normal offset, the Vogel
/// disk, the rotation.
const GODOT_COMMON: [Constant; 10] = [
    Constant { name: "shadow_bias (spot)", value: Value::Text("splane.z += shadow_bias / (light_length * inv_radius), shadow_bias = SHADOW_BIAS / 100.0 * soft_shadow_scale"), unit: "clip depth", source: 0, lines: "736; light_storage.cpp 958, 1011" },
    Constant { name: "SpotLight3D shadow_bias", value: Value::Num(0.03), unit: "", source: 3, lines: "673" },
    Constant { name: "spot near / range", value: Value::Num(0.005), unit: "", source: 5, lines: "2322" },
    Constant { name: "get_vogel_disk golden_angle", value: Value::Num(2.4), unit: "radians", source: 2, lines: "38-48" },
    Constant { name: "quick_hash", value: Value::Text("fract(52.9829189 * fract(dot(pos, (0.06711056, 0.00583715))))"), unit: "", source: 0, lines: "236-239" },
    Constant { name: "disk_rotation", value: Value::Text("mat2(vec2(cr, -sr), vec2(sr, cr)), r = quick_hash(gl_FragCoord.xy) * 2 PI"), unit: "", source: 0, lines: "276-282, 341-347, 750-756" },
    Constant { name: "normal_bias (spot)", value: Value::Text("normal * light_length * shadow_normal_bias * (1.0 - abs(dot(normal, light_rel_vec_norm)))"), unit: "", source: 0, lines: "730, 733" },
    Constant { name: "shadow_normal_bias", value: Value::Text("SHADOW_NORMAL_BIAS (1.0) * shadow_texel_size * 10.0"), unit: "", source: 1, lines: "954-955" },
    Constant { name: "shadow_normal_bias (directional)", value: Value::Text("SHADOW_NORMAL_BIAS (2.0 for DirectionalLight3D) * the split's world texel, times sin θ across the light"), unit: "texels", source: 1, lines: "711; light_3d.cpp 596" },
    Constant { name: "shadow_texel_size", value: Value::Text("light_instance_get_shadow_texel_size: 1.0 / shadow_size, the atlas slot's side in texels"), unit: "uv", source: 4, lines: "702-721" },
];

/// Godot's sides the ports cannot take.
const GODOT_DEPARTURES: [Departure; 7] = [
    Departure { what: "its shadow pass", why: "not read to its lines: the port reads the lesson's map (both faces, lesson 02's slope-scaled bias). Its shadow_bias is applied as the move it amounts to: a spot's, added to the clip depth over distance / range, is for its near plane of range / 200 (renderer_scene_cull.cpp, read at an older commit) a move of 199 × shadow_bias metres towards the light; a sun's moves the receiver along the light by 0.1 / 100 × the filter's scale, its split's bias_scale (light_storage.cpp 709-710) taken as 1" },
    Departure { what: "its 16-bit depth", why: "Godot's shadow atlases default to 16-bit depth, the lesson's map is Depth32Float: acne Godot's biases are tuned against is finer here" },
    Departure { what: "its shadow atlas and 4-split PSSM", why: "a spot's map is the 1024² slot of the 4096² atlas's first quadrant, a sun's the first of 4 splits of its 4096² directional atlas, 2048² (both the project settings' defaults, read in stored versions not pinned to a commit): the port runs those sizes; the normal bias's 10 / shadow_size per metre of light_length is taken as 10 / (2 tan(cone / 2)) of the map's texels at the receiver (the texel's larger side, at its distance along the axis, not its distance from the light)" },
    Departure { what: "the direction of its sun's normal bias", why: "Godot moves the receiver by n's part across the light, n − L (L·n), sin θ long; the port moves it the same length along n itself (lesson 03's peer_receiver), which also brings it sin θ cos θ nearer the light" },
    Departure { what: "its spot near plane", why: "the spot's reversed depth is taken with the lesson's near and far planes; Godot's own near was not read" },
    Departure { what: "shadow_opacity and TAA (taa_frame_count)", why: "opacity 1 and one frame: nothing to emulate; Soft Low is the project's default quality on desktop (a mobile project's directional default is Hard, one tap), read in stored versions not pinned to a commit" },
    Departure { what: "the directional call's tex_scale", why: "uv_scale1 * (range_pos - range_begin) * softshadow_angle * soft_shadow_scale comes from Godot's forward shader, found by text search in the store but not resolved to a file and commit" },
];

pub const GODOT_PCF: PortCard = PortCard {
    variant: "godot_pcf",
    renderer: "Godot 4",
    role: Role::Default,
    repository: "godotengine/godot",
    sources: GODOT_SOURCES,
    constants: &[
        Constant { name: "PARAM_SIZE (light_size)", value: Value::Num(0.0), unit: "m", source: 3, lines: "472" },
        Constant { name: "hard shadow (size 0)", value: Value::Text("sample_pcf_shadow(shadow_atlas, soft_shadow_scale * shadow_atlas_pixel_size, shadow_uv, taa_frame_count)"), unit: "", source: 0, lines: "791-793" },
        Constant { name: "sample_pcf_shadow", value: Value::Text("sc_soft_shadow_samples() bilinear comparisons at pos + shadow_pixel_size * (disk_rotation * soft_shadow_kernel[i].xy), averaged"), unit: "", source: 0, lines: "267-291" },
        Constant { name: "SOFT_LOW soft_shadow_samples", value: Value::Num(4.0), unit: "taps", source: 2, lines: "3061-3065, 3108-3112" },
        Constant { name: "SOFT_LOW shadows_quality_radius", value: Value::Num(2.0), unit: "texels", source: 2, lines: "3061-3065, 3108-3112" },
        Constant { name: "soft_shadow_scale (size 0)", value: Value::Text("shadow_blur (1.0) * shadows_quality_radius"), unit: "", source: 1, lines: "973, 1007-1010" },
        GODOT_COMMON[0],
        GODOT_COMMON[1],
        GODOT_COMMON[2],
        GODOT_COMMON[3],
        GODOT_COMMON[4],
        GODOT_COMMON[5],
        GODOT_COMMON[6],
        GODOT_COMMON[7],
        GODOT_COMMON[8],
        GODOT_COMMON[9],
    ],
    departures: &[GODOT_DEPARTURES[0], GODOT_DEPARTURES[1], GODOT_DEPARTURES[2], GODOT_DEPARTURES[3], GODOT_DEPARTURES[5]],
};

pub const GODOT_SOFT_LOW: PortCard = PortCard {
    variant: "godot_soft_low",
    renderer: "Godot 4",
    role: Role::Option("Light3D light_size (a spot) or light_angular_distance (a sun) above 0"),
    repository: "godotengine/godot",
    sources: GODOT_SOURCES,
    constants: &[
        Constant {
            name: "soft shadow branch",
            value: Value::Text("sc_use_light_soft_shadows() && soft_shadow_size > 0.0"),
            unit: "",
            source: 0,
            lines: "739",
        },
        Constant {
            name: "SOFT_LOW penumbra samples",
            value: Value::Num(8.0),
            unit: "taps",
            source: 2,
            lines: "3061-3065, 3108-3112",
        },
        Constant {
            name: "blocker test",
            value: Value::Text("d > z, d linearly filtered reversed depth"),
            unit: "",
            source: 0,
            lines: "351-352, 763-764",
        },
        Constant {
            name: "penumbra (directional)",
            value: Value::Text("(-pssm_coord.z + blocker_average) / (1.0 - blocker_average)"),
            unit: "",
            source: 0,
            lines: "361",
        },
        Constant {
            name: "uv_size (spot)",
            value: Value::Text("soft_shadow_size * z_norm * soft_shadow_scale"),
            unit: "uv",
            source: 0,
            lines: "758",
        },
        Constant {
            name: "z_norm (spot)",
            value: Value::Text("dot(spot_dir, -light_rel_vec) * inv_radius"),
            unit: "",
            source: 0,
            lines: "743",
        },
        Constant {
            name: "penumbra (spot)",
            value: Value::Text("(-z_norm + blocker_average) / (1.0 - blocker_average)"),
            unit: "",
            source: 0,
            lines: "773",
        },
        Constant {
            name: "no blocker",
            value: Value::Text("shadow = 1.0"),
            unit: "",
            source: 0,
            lines: "372-375, 786-789",
        },
        Constant {
            name: "soft_shadow_size (spot)",
            value: Value::Text("(size * 0.5 / radius) / (half_np / z_near) * rect.size.width"),
            unit: "uv",
            source: 1,
            lines: "1005-1006",
        },
        Constant {
            name: "softshadow_angle (directional)",
            value: Value::Text("tan(deg_to_rad(LIGHT_PARAM_SIZE)), the angular diameter"),
            unit: "",
            source: 1,
            lines: "664-685",
        },
        Constant {
            name: "soft_shadow_scale",
            value: Value::Text("LIGHT_PARAM_SHADOW_BLUR, 1.0 by default (light_3d.cpp 483)"),
            unit: "",
            source: 1,
            lines: "684, 973",
        },
        GODOT_COMMON[0],
        GODOT_COMMON[1],
        GODOT_COMMON[2],
        GODOT_COMMON[3],
        GODOT_COMMON[4],
        GODOT_COMMON[5],
        GODOT_COMMON[6],
        GODOT_COMMON[7],
        GODOT_COMMON[8],
        GODOT_COMMON[9],
    ],
    departures: &GODOT_DEPARTURES,
};

const THREE_R182: &str = "ec1bc8aed59bd41f636ef19e420451a3f7975812";
/// The mirror of three.js's releases whose commit `THREE_R182` is r182.0.
const THREE_R182_MIRROR: &str = "pschroen/three-src";
/// r182's files, from the `pschroen/three-src` mirror of release r182.0
/// (`mrdoob/three.js` is stored only at other commits).
const THREE_R182_SHADOW: Source = Source {
    file: "src/renderers/shaders/ShaderChunk/shadowmap_pars_fragment.glsl.js",
    commit: THREE_R182,
    repository: Some(THREE_R182_MIRROR),
};
const THREE_R182_MAP: Source = Source {
    file: "src/renderers/webgl/WebGLShadowMap.js",
    commit: THREE_R182,
    repository: Some(THREE_R182_MIRROR),
};
const THREE_R182_MATERIAL: Source = Source {
    file: "src/materials/Material.js",
    commit: THREE_R182,
    repository: Some(THREE_R182_MIRROR),
};
const THREE_R182_LIGHT_SHADOW: Source = Source {
    file: "src/lights/LightShadow.js",
    commit: THREE_R182,
    repository: Some(THREE_R182_MIRROR),
};
const THREE_R182_VSM: Source = Source {
    file: "src/renderers/shaders/ShaderLib/vsm.glsl.js",
    commit: THREE_R182,
    repository: Some(THREE_R182_MIRROR),
};
const THREE_R182_PROGRAM: Source = Source {
    file: "src/renderers/webgl/WebGLProgram.js",
    commit: THREE_R182,
    repository: Some(THREE_R182_MIRROR),
};
const THREE_SHADOW_R179: Source = Source {
    file: "src/renderers/shaders/ShaderChunk/shadowmap_pars_fragment.glsl.js",
    commit: "99e4d38509e60dccd471011b64d03975102dd25f",
    repository: None,
};
/// three.js's sources, in the order the three cards' constants index them.
const THREE_SOURCES: &[Source] = &[
    THREE_R182_SHADOW,
    THREE_R182_MAP,
    THREE_R182_MATERIAL,
    THREE_R182_LIGHT_SHADOW,
    THREE_R182_VSM,
    THREE_SHADOW_R179,
    THREE_R182_PROGRAM,
];

/// three.js's shadow camera, which no three.js port follows.
const THREE_CAMERA: Departure = Departure { what: "its shadow camera", why: "a spot's PerspectiveCamera(fov 2 × angle, near 0.5, far light.distance or 500) and a sun's OrthographicCamera(±5, near 0.5, far 500), placed from the light to its target (SpotLightShadow.js 17, 51-53; DirectionalLightShadow.js 16); the ports use the lesson's map planes, fitted to the scene (a spot from range / 1000 to the range, a sun's box around the casters), with a stable up instead of (0, 1, 0)" };
/// three.js's noise runs on gl_FragCoord, origin bottom-left.
const THREE_NOISE: Departure = Departure { what: "the noise's pixel origin", why: "three.js's interleaved gradient noise reads gl_FragCoord (origin bottom-left), the port the framebuffer position (top-left): each pixel's turn differs, their statistics do not" };

/// What every three.js port takes: the map, its offsets (none).
const THREE_COMMON: [Constant; 4] = [
    Constant {
        name: "mapSize",
        value: Value::Num(512.0),
        unit: "texels",
        source: 3,
        lines: "94",
    },
    Constant {
        name: "bias, normalBias",
        value: Value::List(&[0.0, 0.0]),
        unit: "",
        source: 3,
        lines: "53, 64",
    },
    Constant {
        name: "Material.side, shadowSide",
        value: Value::Text("FrontSide, null"),
        unit: "",
        source: 2,
        lines: "86, 340",
    },
    Constant {
        name: "depth material offset",
        value: Value::Text(
            "none: getDepthMaterial copies no polygon offset; Material.polygonOffset false",
        ),
        unit: "",
        source: 2,
        lines: "373, 381, 389",
    },
];

pub const THREEJS_PCF: PortCard = PortCard {
    variant: "threejs_pcf",
    renderer: "three.js",
    role: Role::Default,
    repository: "mrdoob/three.js",
    sources: THREE_SOURCES,
    constants: &[
        Constant { name: "shadowMap.type", value: Value::Text("PCFShadowMap, the default"), unit: "", source: 1, lines: "89" },
        Constant { name: "shadowSide", value: Value::Text("{ FrontSide: BackSide, BackSide: FrontSide, DoubleSide: DoubleSide }: a front-sided material's back faces"), unit: "", source: 1, lines: "51, 476" },
        Constant { name: "PCF depth texture", value: Value::Text("compareFunction LessEqualCompare, LinearFilter: bilinear comparisons"), unit: "", source: 1, lines: "260-264" },
        Constant { name: "PCF taps", value: Value::Num(5.0), unit: "taps", source: 0, lines: "137-143" },
        Constant { name: "vogelDiskSample", value: Value::Text("r = sqrt((i + 0.5) / n), theta = i * 2.399963229728653 + phi"), unit: "", source: 0, lines: "104-111" },
        Constant { name: "phi", value: Value::Text("interleavedGradientNoise(gl_FragCoord.xy) * 6.28318530718"), unit: "radians", source: 0, lines: "97-101, 135" },
        Constant { name: "radius", value: Value::Text("shadowRadius * texelSize.x, shadowRadius 1 (LightShadow.radius)"), unit: "texels", source: 0, lines: "132; LightShadow.js 77" },
        THREE_COMMON[0],
        THREE_COMMON[1],
        THREE_COMMON[2],
        THREE_COMMON[3],
    ],
    departures: &[
        Departure { what: "its 24-bit depth", why: "three.js's PCF map is UnsignedIntType depth; the lesson's is Depth32Float: the comparisons agree up to that rounding" },
        THREE_CAMERA,
        THREE_NOISE,
    ],
};

pub const THREEJS_PCF_SOFT: PortCard = PortCard {
    variant: "threejs_pcf_soft",
    renderer: "three.js",
    role: Role::Option("WebGLRenderer.shadowMap.type = PCFSoftShadowMap, through r181; r182 deprecates it"),
    repository: "mrdoob/three.js",
    sources: THREE_SOURCES,
    constants: &[
        Constant { name: "PCFSoftShadowMap deprecated", value: Value::Text("'PCFSoftShadowMap has been deprecated. Using PCFShadowMap instead.', tested on lights.type, the array of lights"), unit: "", source: 1, lines: "99-104" },
        Constant { name: "shadowMapTypeDefines", value: Value::Text("PCF and VSM only; any other type compiles SHADOWMAP_TYPE_BASIC"), unit: "", source: 6, lines: "345-352" },
        Constant { name: "PCF_SOFT taps", value: Value::Num(16.0), unit: "taps", source: 5, lines: "172-206" },
        Constant { name: "PCF_SOFT weights", value: Value::Text("the outer row and column mixed by f = fract(uv * size + 0.5), sum / 9"), unit: "", source: 5, lines: "179-206" },
        Constant { name: "texture2DCompare", value: Value::Text("step(compare, depth): one nearest texel"), unit: "", source: 5, lines: "76-90" },
        Constant { name: "shadowSide", value: Value::Text("{ FrontSide: BackSide, BackSide: FrontSide, DoubleSide: DoubleSide }: a front-sided material's back faces"), unit: "", source: 1, lines: "51, 476" },
        THREE_COMMON[0],
        THREE_COMMON[1],
        THREE_COMMON[2],
        THREE_COMMON[3],
    ],
    departures: &[
        Departure { what: "RGBA-packed depth", why: "r179 writes its map into an RGBA8 colour target (MeshDepthMaterial, RGBADepthPacking, nearest); the lesson's is a 32-bit float depth map: the comparisons agree up to the packing's rounding" },
        Departure { what: "its release", why: "the kernel is r179's (commit 99e4d38), unchanged through r181; the shadow pass's sides and the defaults are r182's, the same there. In r182 as written the deprecation's test reads lights.type (the array of lights), not the renderer's type, so a user who sets PCFSoftShadowMap gets SHADOWMAP_TYPE_BASIC, one comparison, not PCFShadowMap: not ported" },
        THREE_CAMERA,
    ],
};

pub const THREEJS_VSM: PortCard = PortCard {
    variant: "threejs_vsm",
    renderer: "three.js",
    role: Role::Option("WebGLRenderer.shadowMap.type = VSMShadowMap"),
    repository: "mrdoob/three.js",
    sources: THREE_SOURCES,
    constants: &[
        Constant { name: "VSM getShadow", value: Value::Text("hard_shadow = step(shadowCoord.z, mean); else max(hard_shadow, clamp((p_max - 0.3) / 0.65, 0, 1)), variance at least 0.0000001"), unit: "", source: 0, lines: "151-207" },
        Constant { name: "bleed cut", value: Value::List(&[0.3, 0.95]), unit: "", source: 0, lines: "197" },
        Constant { name: "moments", value: Value::Text("(mean, std_dev) of the map's own depth; variance = std_dev^2"), unit: "", source: 4, lines: "43-48" },
        Constant { name: "blur samples", value: Value::Text("uvStart + i * uvStride over [-1, 1] * radius, first along y from the depth, then along x"), unit: "texels", source: 4, lines: "14-41" },
        Constant { name: "blurSamples", value: Value::Num(8.0), unit: "samples", source: 3, lines: "85" },
        Constant { name: "radius", value: Value::Num(1.0), unit: "texels", source: 3, lines: "77" },
        Constant { name: "VSM side", value: Value::Text("material.shadowSide ?? material.side: the front faces of a front-sided material"), unit: "", source: 1, lines: "470-472" },
        Constant { name: "VSM receivers", value: Value::Text("object.castShadow || (object.receiveShadow && type === VSMShadowMap)"), unit: "", source: 1, lines: "514" },
        Constant { name: "VSM targets", value: Value::Text("RGFormat HalfFloatType moments, linear; FloatType depth read nearest"), unit: "", source: 1, lines: "224-239" },
        THREE_COMMON[0],
        THREE_COMMON[1],
        THREE_COMMON[2],
        THREE_COMMON[3],
    ],
    departures: &[
        Departure { what: "16-bit moments", why: "three.js keeps (mean, std_dev) in half floats; the port keeps 32-bit floats" },
        Departure { what: "receivers that cast nothing", why: "three.js draws them into a VSM map too; the port draws the scene's casters, and no lesson 10 scene has an object with casts_shadow = false" },
        THREE_CAMERA,
        Departure { what: "the depth units of its variance", why: "its least variance, 1e-7, and Chebyshev's distance are in the map's depth, which its camera's near plane sets: with three.js's 0.5 m a receiver 8 cm behind the default scene's slab is 2.9e-3 deep behind it and in shadow; with the lesson's 0.012 m it is 6.7e-5 deep and lit. The port's figures are of the lesson's planes" },
    ],
};

/// Every card of lesson 10, in the variants' order.
pub const CARDS: &[PortCard] = &[
    FILAMENT_PCF,
    FILAMENT_PCSS,
    FILAMENT_EVSM,
    BEVY_GAUSSIAN,
    BEVY_PCSS_OR_PCF,
    GODOT_PCF,
    GODOT_SOFT_LOW,
    THREEJS_PCF,
    THREEJS_PCF_SOFT,
    THREEJS_VSM,
];
