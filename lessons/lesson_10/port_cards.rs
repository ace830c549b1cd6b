//! The cards of lesson 10's ports ([`common::ports`]): for each renderer's
//! soft-shadow default the lesson runs, the files and commits it was read
//! at, every constant and formula the port takes from there with its lines,
//! and what the port cannot do here. `tests/port_cards_lesson_10.rs` checks
//! each port ([`super::peers`], `shaders/lesson_10/peers.wgsl`) against its
//! card; the chapter's "where each port departs" table is made from these.
//!
//! Line numbers were read in the files' stored text at the commits named.

use common::ports::{Constant, Departure, PortCard, Source, Value};

const FILAMENT_SHADER: Source = Source {
    file: "shaders/src/surface_shadowing.fs",
    commit: "f366ac3a35118848a4b59182c286a09c3205d004",
};
const FILAMENT_MANAGER: Source = Source {
    file: "filament/src/ShadowMapManager.cpp",
    commit: "cb91a23a03f62cb09f2f77217e9e98ea69f0813d",
};
const FILAMENT_JAVA: Source = Source {
    file: "android/filament-android/src/main/java/com/google/android/filament/LightManager.java",
    commit: "c35a60808c9b24bb2699f72f36dc2aa0e1f5087a",
};
const FILAMENT_VIEW: Source = Source {
    file: "filament/src/PerViewUniforms.cpp",
    commit: "cb91a23a03f62cb09f2f77217e9e98ea69f0813d",
};
const FILAMENT_OPTIONS: Source = Source {
    file: "filament/include/filament/Options.h",
    commit: "2fac13e154fb1a64bbca70e5857838d319957e9c",
};

/// The shared departure of every lesson 10 port: one map, rendered once per
/// light with lesson 02's recommended slope-scaled bias.
const MAP_BIAS: Departure = Departure {
    what: "its own depth and normal bias",
    why: "every variant reads the lesson's map, rendered with lesson 02's slope-scaled hardware bias; a renderer's receiver offsets are not applied",
};

/// Filament's first 16 Poisson points, as lines 93-96 list them (x, y).
pub const FILAMENT_POISSON_16: &[f64] = &[
    0.511749, 0.547686, 0.58929, 0.257224, 0.165018, 0.57663, 0.407692, 0.742285, //
    0.707012, 0.646523, 0.31463, 0.466825, 0.801257, 0.485186, 0.418136, 0.146517, //
    0.579889, 0.0368284, 0.79801, 0.140114, -0.0413185, 0.371455, -0.0529108, 0.627352, //
    0.0821375, 0.882071, 0.17308, 0.301207, -0.120452, 0.867216, 0.371096, 0.916454,
];

pub const FILAMENT_PCSS: PortCard = PortCard {
    variant: "filament_pcss",
    renderer: "Filament",
    repository: "google/filament",
    sources: &[FILAMENT_SHADER, FILAMENT_MANAGER, FILAMENT_JAVA, FILAMENT_OPTIONS],
    constants: &[
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
    ],
    departures: &[
        MAP_BIAS,
        Departure { what: "its shadow camera's near and far planes", why: "the ratio uses the lesson's map planes (its light_view_proj), not Filament's own fit of the camera to the scene" },
        Departure { what: "the bulb radius of a spot", why: "the scene's emitter radius stands in for shadowBulbRadius (a user would set it so); on a sun Filament's default 2 cm is kept, since its directional penumbra does not follow the sun's angle" },
        Departure { what: "its interleaved gradient noise's constants", why: "lesson 03's rotation_angle (Jimenez 2014's 0.06711056, 0.00583715, 52.9829189); Filament's common_math.fs was not read" },
        Departure { what: "TAA (temporalNoise)", why: "the workbook renders single frames; Filament's temporal rotation needs TAA to average it" },
    ],
};

pub const FILAMENT_EVSM: PortCard = PortCard {
    variant: "filament_evsm",
    renderer: "Filament",
    repository: "google/filament",
    sources: &[FILAMENT_SHADER, FILAMENT_VIEW, FILAMENT_OPTIONS, FILAMENT_JAVA],
    constants: &[
        Constant { name: "vsmExponent (16-bit moments)", value: Value::Num(5.54), unit: "", source: 1, lines: "329, 345" },
        Constant { name: "vsmDepthScale", value: Value::Text("minVarianceScale * 0.01f * vsmExponent"), unit: "", source: 1, lines: "346" },
        Constant { name: "minVarianceScale", value: Value::Num(0.5), unit: "", source: 2, lines: "591" },
        Constant { name: "lightBleedReduction", value: Value::Num(0.15), unit: "", source: 2, lines: "596" },
        Constant { name: "minVariance", value: Value::Text("(vsmDepthScale * depth)^2 of the warped depth"), unit: "", source: 0, lines: "441-445" },
        Constant { name: "EVSM warp", value: Value::Text("exp(vsmExponent * (2 * depth - 1)), depth linear in [0, 1]"), unit: "", source: 0, lines: "451, 464-468" },
        Constant { name: "reduceLightBleed", value: Value::Text("linstep(amount, 1.0, pMax)"), unit: "", source: 0, lines: "421-424" },
        Constant { name: "chebyshevUpperBound", value: Value::Text("mean <= moments.x ? 1.0 : pMax"), unit: "", source: 0, lines: "426-439" },
        Constant { name: "ELVSM", value: Value::Text("off by default: the positive warp alone"), unit: "", source: 0, lines: "470-472" },
        Constant { name: "filtering", value: Value::Text("LINEAR, no mipmaps, no anisotropy"), unit: "", source: 1, lines: "331-340" },
        Constant { name: "blurWidth", value: Value::Num(0.0), unit: "texels", source: 3, lines: "365" },
        Constant { name: "mapSize", value: Value::Num(1024.0), unit: "texels", source: 3, lines: "194" },
    ],
    departures: &[
        MAP_BIAS,
        Departure { what: "16-bit moments", why: "the moments are 32-bit floats in a storage buffer (GL renders no float targets); the exponent stays the 16-bit one, 5.54" },
        Departure { what: "MSAA of the moments", why: "msaaSamples is 1 by default: nothing to emulate" },
    ],
};

const BEVY_SAMPLING: Source = Source {
    file: "crates/bevy_pbr/src/render/shadow_sampling.wgsl",
    commit: "00ef04ec8ad0f5b8abeea45c6461a003bcb1a0fa",
};
const BEVY_SHADOWS: Source = Source {
    file: "crates/bevy_pbr/src/render/shadows.wgsl",
    commit: "00ef04ec8ad0f5b8abeea45c6461a003bcb1a0fa",
};
const BEVY_UTILS: Source = Source {
    file: "crates/bevy_pbr/src/render/utils.wgsl",
    commit: "e705fe8ea8a7bfbe8b5f343b64910ab07ccd6368",
};
const BEVY_LIGHT: Source = Source {
    file: "crates/bevy_pbr/src/render/light.rs",
    commit: "00ef04ec8ad0f5b8abeea45c6461a003bcb1a0fa",
};
const BEVY_SPOT: Source = Source {
    file: "crates/bevy_light/src/spot_light.rs",
    commit: "00ef04ec8ad0f5b8abeea45c6461a003bcb1a0fa",
};
const BEVY_POINT: Source = Source {
    file: "crates/bevy_light/src/point_light.rs",
    commit: "00ef04ec8ad0f5b8abeea45c6461a003bcb1a0fa",
};
const BEVY_DIRECTIONAL: Source = Source {
    file: "crates/bevy_light/src/directional_light.rs",
    commit: "00ef04ec8ad0f5b8abeea45c6461a003bcb1a0fa",
};

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

pub const BEVY_PCSS_OR_PCF: PortCard = PortCard {
    variant: "bevy_pcss_or_pcf",
    renderer: "Bevy",
    repository: "bevyengine/bevy",
    sources: &[BEVY_SAMPLING, BEVY_SHADOWS, BEVY_UTILS, BEVY_LIGHT, BEVY_SPOT, BEVY_POINT, BEVY_DIRECTIONAL],
    constants: &[
        Constant { name: "depth (spot)", value: Value::Text("near_z / -projected_position.z: reversed and infinite"), unit: "", source: 1, lines: "112" },
        Constant { name: "DEFAULT_SHADOW_MAP_NEAR_Z (spot)", value: Value::Num(0.1), unit: "m", source: 4, lines: "138" },
        Constant { name: "spot PCSS call", value: Value::Text("sample_shadow_map_pcss(shadow_uv, depth, array_index, frag_coord_xy, SPOT_SHADOW_TEXEL_SIZE, soft_shadow_size) when soft_shadow_size > 0"), unit: "", source: 1, lines: "116-125" },
        Constant { name: "soft_shadow_size (spot)", value: Value::Text("light.radius when soft_shadows_enabled, else 0"), unit: "m", source: 3, lines: "1095-1099" },
        Constant { name: "SPOT_SHADOW_TEXEL_SIZE", value: Value::Num(0.0134277345), unit: "texel_size units", source: 0, lines: "71" },
        Constant { name: "D3D_SAMPLE_POINT_POSITIONS", value: Value::List(BEVY_D3D_SAMPLE_POINT_POSITIONS), unit: "search radii", source: 0, lines: "79-88" },
        Constant { name: "blocker test", value: Value::Text("sampled_depth >= depth, linearly filtered depth"), unit: "", source: 0, lines: "46-61" },
        Constant { name: "search uv_offset_scale", value: Value::Text("search_size / (texel_size * shadow_map_size)"), unit: "uv", source: 0, lines: "229" },
        Constant { name: "no blocker", value: Value::Text("z_blocker 0.0 (the filter still runs)"), unit: "", source: 0, lines: "250-252" },
        Constant { name: "blur_size", value: Value::Text("max((z_blocker - depth) * light_size / depth, 0.5)"), unit: "", source: 0, lines: "303" },
        Constant { name: "Jimenez spacing", value: Value::Text("map(0.00390625, 0.022949219, 0.015, 0.035, texel_size) * blur_size / (texel_size * shadow_map_size)"), unit: "uv", source: 0, lines: "169-175" },
        Constant { name: "SPIRAL_OFFSET_0_..7_", value: Value::List(BEVY_SPIRAL_OFFSETS), unit: "filter radii", source: 2, lines: "75-82" },
        Constant { name: "random_rotation_matrix", value: Value::Text("2 PI * interleaved_gradient_noise(frag_coord, 1) when not temporal; mat2x2(m.y, -m.x, m.x, m.y), m = (sin, cos)"), unit: "", source: 0, lines: "156-164" },
        Constant { name: "interleaved_gradient_noise", value: Value::Text("fract(52.9829189 * fract(0.06711056 * x + 0.00583715 * y)), xy + 5.588238 * (frame % 64)"), unit: "", source: 2, lines: "66-69" },
        Constant { name: "PCSS taps", value: Value::Num(8.0), unit: "taps", source: 0, lines: "177-209, 221-254" },
        Constant { name: "PointLightShadowMap size (spots too)", value: Value::Num(1024.0), unit: "texels", source: 5, lines: "188" },
        Constant { name: "soft_shadow_size (directional)", value: Value::Text("None by default: no PCSS on a sun"), unit: "", source: 6, lines: "116, 158" },
        Constant { name: "DirectionalLightShadowMap size", value: Value::Num(2048.0), unit: "texels", source: 6, lines: "204" },
        Constant { name: "sample_shadow_map_castano_thirteen (default Gaussian filter)", value: Value::Text("9 bilinear comparisons, weights / 144"), unit: "", source: 0, lines: "105-147" },
    ],
    departures: &[
        MAP_BIAS,
        Departure { what: "PCSS on a sun", why: "off in Bevy by default (soft_shadow_size None): on a sun the variant runs Bevy's default Gaussian PCF instead, and says so in its name" },
        Departure { what: "cascades on a sun", why: "one 2048² map stands for Bevy's first cascade; the lesson fits it to the scene, not to Bevy's cascade splits" },
        Departure { what: "its infinite reversed depth", why: "the lesson's map is finite and forward; since it is affine in 1/d, each tap's near_z / d is recovered exactly from it (bilinear blends too)" },
        Departure { what: "the experimental_pbr_pcss feature", why: "Bevy builds PCSS only with that feature and soft_shadows_enabled on the light; the port assumes both" },
    ],
};

const GODOT_SHADER: Source = Source {
    file: "servers/rendering/renderer_rd/shaders/scene_forward_lights_inc.glsl",
    commit: "8bae2a49c6fb4ac65abbe9d0b5265fcb06e8b1d7",
};
const GODOT_STORAGE: Source = Source {
    file: "servers/rendering/renderer_rd/storage_rd/light_storage.cpp",
    commit: "8403baa5a1e36485516c769a6393e056ed55192a",
};
const GODOT_RENDER: Source = Source {
    file: "servers/rendering/renderer_rd/renderer_scene_render_rd.cpp",
    commit: "238862bddb647a832b4be38791b86f882b20af6a",
};

pub const GODOT_SOFT_LOW: PortCard = PortCard {
    variant: "godot_soft_low",
    renderer: "Godot 4",
    repository: "godotengine/godot",
    sources: &[GODOT_SHADER, GODOT_STORAGE, GODOT_RENDER],
    constants: &[
        Constant { name: "SOFT_LOW penumbra samples", value: Value::Num(8.0), unit: "taps", source: 2, lines: "3061-3065, 3108-3112" },
        Constant { name: "get_vogel_disk golden_angle", value: Value::Num(2.4), unit: "radians", source: 2, lines: "38-48" },
        Constant { name: "quick_hash", value: Value::Text("fract(52.9829189 * fract(dot(pos, (0.06711056, 0.00583715))))"), unit: "", source: 0, lines: "236-239" },
        Constant { name: "disk_rotation", value: Value::Text("mat2(vec2(cr, -sr), vec2(sr, cr)), r = quick_hash(gl_FragCoord.xy) * 2 PI"), unit: "", source: 0, lines: "341-347, 750-756" },
        Constant { name: "blocker test", value: Value::Text("d > z, d linearly filtered reversed depth"), unit: "", source: 0, lines: "351-352, 763-764" },
        Constant { name: "penumbra (directional)", value: Value::Text("(-pssm_coord.z + blocker_average) / (1.0 - blocker_average)"), unit: "", source: 0, lines: "361" },
        Constant { name: "uv_size (spot)", value: Value::Text("soft_shadow_size * z_norm * soft_shadow_scale"), unit: "uv", source: 0, lines: "758" },
        Constant { name: "z_norm (spot)", value: Value::Text("dot(spot_dir, -light_rel_vec) * inv_radius"), unit: "", source: 0, lines: "743" },
        Constant { name: "penumbra (spot)", value: Value::Text("(-z_norm + blocker_average) / (1.0 - blocker_average)"), unit: "", source: 0, lines: "773" },
        Constant { name: "no blocker", value: Value::Text("shadow = 1.0"), unit: "", source: 0, lines: "372-375, 786-789" },
        Constant { name: "soft_shadow_size (spot)", value: Value::Text("(size * 0.5 / radius) / (half_np / z_near) * rect.size.width"), unit: "uv", source: 1, lines: "1005-1006" },
        Constant { name: "softshadow_angle (directional)", value: Value::Text("tan(deg_to_rad(LIGHT_PARAM_SIZE)), the angular diameter"), unit: "", source: 1, lines: "664-685" },
        Constant { name: "soft_shadow_scale", value: Value::Text("LIGHT_PARAM_SHADOW_BLUR (default 1.0)"), unit: "", source: 1, lines: "684, 973" },
    ],
    departures: &[
        MAP_BIAS,
        Departure { what: "the directional call's tex_scale", why: "uv_scale1 * (range_pos - range_begin) * softshadow_angle * soft_shadow_scale comes from Godot's forward shader, found by text search in the store but not resolved to a file and commit" },
        Departure { what: "its shadow atlas and 4-split PSSM", why: "one map of the lesson's size stands for the atlas quadrant or the first split" },
        Departure { what: "its spot near plane", why: "the spot's reversed depth is taken with the lesson's near and far planes; Godot's own near was not read" },
        Departure { what: "shadow_opacity and TAA (taa_frame_count)", why: "opacity 1 and one frame: nothing to emulate" },
    ],
};

const THREE_SHADOW: Source = Source {
    file: "src/renderers/shaders/ShaderChunk/shadowmap_pars_fragment.glsl.js",
    commit: "99e4d38509e60dccd471011b64d03975102dd25f",
};
const THREE_VSM: Source = Source {
    file: "src/renderers/shaders/ShaderLib/vsm.glsl.js",
    commit: "1b7857ec6020acc9cdf7128729058ab6ae8e6cc3",
};
const THREE_LIGHT_SHADOW: Source = Source {
    file: "src/lights/LightShadow.js",
    commit: "d5761f37f9b90d82a9796cc8d6dd3b58297e5b7f",
};

pub const THREEJS_PCF_SOFT: PortCard = PortCard {
    variant: "threejs_pcf_soft",
    renderer: "three.js",
    repository: "mrdoob/three.js",
    sources: &[THREE_SHADOW, THREE_LIGHT_SHADOW],
    constants: &[
        Constant { name: "PCF_SOFT taps", value: Value::Num(16.0), unit: "taps", source: 0, lines: "172-206" },
        Constant { name: "PCF_SOFT weights", value: Value::Text("the outer row and column mixed by f = fract(uv * size + 0.5), sum / 9"), unit: "", source: 0, lines: "179-206" },
        Constant { name: "texture2DCompare", value: Value::Text("step(compare, depth): one nearest texel"), unit: "", source: 0, lines: "76-90" },
        Constant { name: "mapSize", value: Value::Num(512.0), unit: "texels", source: 1, lines: "104" },
    ],
    departures: &[
        MAP_BIAS,
        Departure { what: "RGBA-packed depth", why: "the lesson's 32-bit float depth map; the comparison is the same" },
        Departure { what: "receiver-plane comparison", why: "each tap compares with the receiver's plane (three.js's bias is 0 by default and its outer taps acne without it)" },
    ],
};

pub const THREEJS_VSM: PortCard = PortCard {
    variant: "threejs_vsm",
    renderer: "three.js",
    repository: "mrdoob/three.js",
    sources: &[THREE_SHADOW, THREE_VSM, THREE_LIGHT_SHADOW],
    constants: &[
        Constant { name: "VSMShadow", value: Value::Text("hard_shadow = step(compare, mean); else max(hard, linstep(0.3, 0.95, var / (var + d^2)))"), unit: "", source: 0, lines: "98-125" },
        Constant { name: "bleed cut", value: Value::List(&[0.3, 0.95]), unit: "", source: 0, lines: "119" },
        Constant { name: "moments", value: Value::Text("(mean, std_dev) of the map's own depth; variance = std_dev^2"), unit: "", source: 1, lines: "43-48" },
        Constant { name: "blur samples", value: Value::Text("uvStart + i * uvStride over [-1, 1] * radius, first along y from the depth, then along x"), unit: "texels", source: 1, lines: "16-41" },
        Constant { name: "blurSamples", value: Value::Num(8.0), unit: "samples", source: 2, lines: "95" },
        Constant { name: "radius", value: Value::Num(1.0), unit: "texels", source: 2, lines: "87" },
        Constant { name: "mapSize", value: Value::Num(512.0), unit: "texels", source: 2, lines: "104" },
    ],
    departures: &[
        MAP_BIAS,
        Departure { what: "16-bit moments", why: "three.js keeps (mean, std_dev) in half floats (r182: RGFormat HalfFloatType, in the pschroen/three-src mirror of release r182.0, WebGLShadowMap.js 224-239); the port keeps 32-bit floats" },
        Departure { what: "the blur's filtering", why: "its first pass reads the depth texture nearest (NearestFilter) and its second the half-float target linearly, as r182's WebGLShadowMap.js (mirror, lines 233-239, 388-413) sets them; mrdoob/three.js's own copy of that file is stored only at an older commit" },
    ],
};

/// Every card of lesson 10, in the variants' order.
pub const CARDS: &[PortCard] = &[
    FILAMENT_PCSS,
    FILAMENT_EVSM,
    BEVY_PCSS_OR_PCF,
    GODOT_SOFT_LOW,
    THREEJS_PCF_SOFT,
    THREEJS_VSM,
];
