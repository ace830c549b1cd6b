//! Godot 4's cards: its PCF while a light's size is 0 (`godot_pcf`) and
//! its soft shadow at Soft Low (`godot_soft_low`).

use common::ports::{Constant, Departure, PortCard, Role, Source, Value, TAPS_UNIT};

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
        Constant { name: "SOFT_LOW soft_shadow_samples", value: Value::Num(4.0), unit: TAPS_UNIT, source: 2, lines: "3061-3065, 3108-3112" },
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
            unit: TAPS_UNIT,
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
