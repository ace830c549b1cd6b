//! The cards of lesson 02's ports (`learnopengl`, `wgpu_example`,
//! `bevy_bias`): what each takes from its renderer's source, read at a
//! named file, commit and lines, and what it cannot do here. A
//! transcription of the sources, written apart from the ports' constants
//! ([`super::bias`]); `tests/port_cards.rs` checks one against the other,
//! and the book's table of departures is generated from these. Lesson 03's
//! cards reuse these rows (its ports add their filters).

use common::measure::counters::TAPS;
use common::ports::{Constant, Departure, PortCard, Role, Source, Value, TAPS_UNIT};

const LEARNOPENGL_AT_85530AB: &str = "85530ab9976154133a21cfd228f642c47b0c88da";
/// The snapshot of gfx-rs/wgpu that was read (its trunk, 2024-10-23).
const WGPU_AT_64A61EE: &str = "64a61ee5c69569bbb3db03563997e88a229eba17";
pub const BEVY_AT_E85A706: &str = "e85a706c30d78f877ea865c1af943f54e94ece33";

// LearnOpenGL "Shadow Mapping": sources 0 and 1 of its cards.

pub const LEARNOPENGL_SOURCES: &[Source] = &[
    Source {
        file: "src/5.advanced_lighting/3.1.3.shadow_mapping/3.1.3.shadow_mapping.fs",
        commit: LEARNOPENGL_AT_85530AB,
        repository: None,
    },
    Source {
        file: "src/5.advanced_lighting/3.1.3.shadow_mapping/shadow_mapping.cpp",
        commit: LEARNOPENGL_AT_85530AB,
        repository: None,
    },
];

pub const LEARNOPENGL_SHADOW_WIDTH: Constant = Constant {
    name: "SHADOW_WIDTH",
    value: Value::Num(1024.0),
    unit: "texels",
    source: 1,
    lines: "119",
};
pub const LEARNOPENGL_NEAREST: Constant = Constant {
    name: "GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER",
    value: Value::Text("GL_NEAREST"),
    unit: "",
    source: 1,
    lines: "127-128",
};
pub const LEARNOPENGL_BORDER: Constant = Constant {
    name: "GL_CLAMP_TO_BORDER, borderColor",
    value: Value::Text("1.0: outside the map is lit"),
    unit: "",
    source: 1,
    lines: "129-132",
};
pub const LEARNOPENGL_NEAR: Constant = Constant {
    name: "near_plane",
    value: Value::Num(1.0),
    unit: "m",
    source: 1,
    lines: "181",
};
pub const LEARNOPENGL_FAR: Constant = Constant {
    name: "far_plane",
    value: Value::Num(7.5),
    unit: "m",
    source: 1,
    lines: "181",
};
pub const LEARNOPENGL_PROJECTION: Constant = Constant {
    name: "lightProjection",
    value: Value::Text("glm::ortho(-10.0f, 10.0f, -10.0f, 10.0f, near_plane, far_plane)"),
    unit: "",
    source: 1,
    lines: "183",
};
pub const LEARNOPENGL_BIAS: Constant = Constant {
    name: "bias",
    value: Value::Text("max(0.05 * (1.0 - dot(normal, lightDir)), 0.005)"),
    unit: "depth units",
    source: 0,
    lines: "28-30",
};
pub const LEARNOPENGL_BIAS_SLOPE: Constant = Constant {
    name: "bias: the 0.05 of 0.05 * (1.0 - dot(normal, lightDir))",
    value: Value::Num(0.05),
    unit: "depth units",
    source: 0,
    lines: "30",
};
pub const LEARNOPENGL_BIAS_MIN: Constant = Constant {
    name: "bias: the 0.005 of max(..., 0.005)",
    value: Value::Num(0.005),
    unit: "depth units",
    source: 0,
    lines: "30",
};
pub const LEARNOPENGL_PAST_FAR: Constant = Constant {
    name: "projCoords.z > 1.0",
    value: Value::Text("shadow = 0.0: past the far plane is lit"),
    unit: "",
    source: 0,
    lines: "47-48",
};

/// The source's depth units are its own light's; ours are the lesson's fit.
pub const LEARNOPENGL_DEPTH_UNITS: Departure = Departure {
    what: "its depth spans an orthographic near 1 to far 7.5 (6.5 m) over 20 m × 20 m; the port subtracts the bias's numbers from the depth of the lesson's light, fitted to the scene",
    why: "the lesson fits every light to its scene (lesson 01); the bias is in depth units as the source writes it, so here it is (the fit's depth range / 6.5 m) times as long",
};
/// `GL_DEPTH_COMPONENT` is the driver's choice.
pub const GL_DEPTH_FORMAT: Departure = Departure {
    what: "`GL_DEPTH_COMPONENT` with `GL_FLOAT` leaves the depth format to the driver (commonly 24-bit); the port's map is Depth32Float",
    why: "the lesson's map is Depth32Float on every backend; 24 bits of 6.5 m are 0.4 µm steps, far under the bias",
};

/// `learnopengl`: LearnOpenGL's bias, one tap.
pub const LEARNOPENGL: PortCard = PortCard {
    variant: "learnopengl",
    renderer: "LearnOpenGL, Shadow Mapping",
    role: Role::Default,
    repository: "JoeyDeVries/LearnOpenGL",
    sources: LEARNOPENGL_SOURCES,
    constants: &[
        LEARNOPENGL_SHADOW_WIDTH,
        LEARNOPENGL_NEAREST,
        LEARNOPENGL_BORDER,
        LEARNOPENGL_NEAR,
        LEARNOPENGL_FAR,
        LEARNOPENGL_PROJECTION,
        LEARNOPENGL_BIAS,
        LEARNOPENGL_BIAS_SLOPE,
        LEARNOPENGL_BIAS_MIN,
        Constant {
            name: "shadow (one tap)",
            value: Value::Text("currentDepth - bias > closestDepth ? 1.0 : 0.0"),
            unit: "",
            source: 0,
            lines: "24-26, 32",
        },
        Constant {
            name: TAPS.name,
            value: Value::Num(1.0),
            unit: TAPS_UNIT,
            source: 0,
            lines: "32",
        },
        LEARNOPENGL_PAST_FAR,
    ],
    departures: &[
        LEARNOPENGL_DEPTH_UNITS,
        Departure {
            what: "its active code filters 3×3 (lines 34-44); its one-tap test is line 32, commented out",
            why: "lesson 02 compares biases at one tap; the 3×3 is lesson 03's `learnopengl_pcf`",
        },
        GL_DEPTH_FORMAT,
    ],
};

// The wgpu shadow example: sources 0 and 1 of its cards.

pub const WGPU_SOURCES: &[Source] = &[
    Source {
        file: "examples/src/shadow/mod.rs",
        commit: WGPU_AT_64A61EE,
        repository: None,
    },
    Source {
        file: "examples/src/shadow/shader.wgsl",
        commit: WGPU_AT_64A61EE,
        repository: None,
    },
];

pub const WGPU_SHADOW_SIZE: Constant = Constant {
    name: "SHADOW_SIZE",
    value: Value::Num(512.0),
    unit: "texels",
    source: 0,
    lines: "164-166",
};
pub const WGPU_SHADOW_FORMAT: Constant = Constant {
    name: "SHADOW_FORMAT",
    value: Value::Text("Depth32Float"),
    unit: "",
    source: 0,
    lines: "163",
};
pub const WGPU_CULL: Constant = Constant {
    name: "shadow pass cull_mode",
    value: Value::Text("Some(wgpu::Face::Back)"),
    unit: "",
    source: 0,
    lines: "506",
};
pub const WGPU_UNCLIPPED: Constant = Constant {
    name: "shadow pass unclipped_depth",
    value: Value::Text("device.features().contains(wgpu::Features::DEPTH_CLIP_CONTROL)"),
    unit: "",
    source: 0,
    lines: "507-509",
};
pub const WGPU_DEPTH_COMPARE: Constant = Constant {
    name: "shadow pass depth_compare",
    value: Value::Text("LessEqual"),
    unit: "",
    source: 0,
    lines: "515",
};
pub const WGPU_BIAS_CONSTANT: Constant = Constant {
    name: "DepthBiasState::constant",
    value: Value::Num(2.0),
    unit: "units of the depth format",
    source: 0,
    lines: "518",
};
pub const WGPU_BIAS_SLOPE: Constant = Constant {
    name: "DepthBiasState::slope_scale",
    value: Value::Num(2.0),
    unit: "× the depth slope",
    source: 0,
    lines: "519",
};
pub const WGPU_BIAS_CLAMP: Constant = Constant {
    name: "DepthBiasState::clamp",
    value: Value::Num(0.0),
    unit: "depth units (0: none)",
    source: 0,
    lines: "520",
};
pub const WGPU_SAMPLER: Constant = Constant {
    name: "shadow_sampler",
    value: Value::Text("ClampToEdge, mag_filter and min_filter Linear, compare LessEqual"),
    unit: "",
    source: 0,
    lines: "366-376",
};
pub const WGPU_LIGHTS: Constant = Constant {
    name: "Light::to_raw projection",
    value: Value::Text(
        "perspective_rh(fov, 1.0, depth.start, depth.end): fov 60° and 45°, depth 1.0..20.0",
    ),
    unit: "",
    source: 0,
    lines: "109-114, 413-414, 425-426",
};
pub const WGPU_FETCH_SHADOW: Constant = Constant {
    name: "fetch_shadow",
    value: Value::Text(
        "w <= 0.0: lit; else one textureSampleCompareLevel at xy * (0.5, -0.5) / w + 0.5, depth z / w",
    ),
    unit: "",
    source: 1,
    lines: "65-76",
};

/// The wgpu example's departures, the filter aside.
pub const WGPU_DEPARTURES: [Departure; 4] = [
    Departure {
        what: "its two lights are perspective (60° and 45°, depth 1 to 20) over its own scene; the port runs on the scene's light, fitted to the scene",
        why: "the port takes the example's shadow pass, not its scene; its bias is in units of the map's depth and slope, so it follows the lesson's fit",
    },
    Departure {
        what: "unclipped depth where the device has DEPTH_CLIP_CONTROL; the lesson's shadow pass clips",
        why: "the lesson fits the light's frustum around every caster: nothing reaches its near or far plane",
    },
    Departure {
        what: "the shadow pass tests LessEqual; the lesson's tests Less",
        why: "they differ only where a caster's own faces meet at equal depths, which store the same depth either way",
    },
    Departure {
        what: "outside the map, ClampToEdge reads its edge texel; the lesson reads lit",
        why: "the lesson's light frustum covers every receiver",
    },
];

/// `wgpu_example`: the wgpu example's shadow pass, one nearest tap.
pub const WGPU_EXAMPLE: PortCard = PortCard {
    variant: "wgpu_example",
    renderer: "wgpu, shadow example",
    role: Role::Default,
    repository: "gfx-rs/wgpu",
    sources: WGPU_SOURCES,
    constants: &[
        WGPU_SHADOW_SIZE,
        WGPU_SHADOW_FORMAT,
        WGPU_CULL,
        WGPU_UNCLIPPED,
        WGPU_DEPTH_COMPARE,
        WGPU_BIAS_CONSTANT,
        WGPU_BIAS_SLOPE,
        WGPU_BIAS_CLAMP,
        WGPU_SAMPLER,
        WGPU_LIGHTS,
        WGPU_FETCH_SHADOW,
    ],
    departures: &[
        Departure {
            what: "its sampler filters Linear (a 2×2 comparison); one nearest tap here",
            why:
                "lesson 02 compares biases at one tap; the 2×2 is lesson 03's `wgpu_example_hw2x2`",
        },
        WGPU_DEPARTURES[0],
        WGPU_DEPARTURES[1],
        WGPU_DEPARTURES[2],
        WGPU_DEPARTURES[3],
    ],
};

// Bevy's DirectionalLight: sources 0 to 5 of its cards.

pub const BEVY_SOURCES: [Source; 6] = [
    Source {
        file: "crates/bevy_pbr/src/light/directional_light.rs",
        commit: BEVY_AT_E85A706,
        repository: None,
    },
    Source {
        file: "crates/bevy_pbr/src/light/mod.rs",
        commit: BEVY_AT_E85A706,
        repository: None,
    },
    Source {
        file: "crates/bevy_pbr/src/render/light.rs",
        commit: BEVY_AT_E85A706,
        repository: None,
    },
    Source {
        file: "crates/bevy_pbr/src/render/shadows.wgsl",
        commit: BEVY_AT_E85A706,
        repository: None,
    },
    Source {
        file: "crates/bevy_core_pipeline/src/core_3d/mod.rs",
        commit: BEVY_AT_E85A706,
        repository: None,
    },
    Source {
        file: "crates/bevy_pbr/src/pbr_material.rs",
        commit: BEVY_AT_E85A706,
        repository: None,
    },
];

pub const BEVY_DEPTH_BIAS: Constant = Constant {
    name: "DirectionalLight::DEFAULT_SHADOW_DEPTH_BIAS",
    value: Value::Num(0.02),
    unit: "m",
    source: 0,
    lines: "81",
};
pub const BEVY_NORMAL_BIAS: Constant = Constant {
    name: "DirectionalLight::DEFAULT_SHADOW_NORMAL_BIAS",
    value: Value::Num(1.8),
    unit: "texels",
    source: 0,
    lines: "82",
};
pub const BEVY_SQRT_2: Constant = Constant {
    name: "shadow_normal_bias",
    value: Value::Text("directional_light.shadow_normal_bias * std::f32::consts::SQRT_2"),
    unit: "texels",
    source: 2,
    lines: "347-348",
};
pub const BEVY_NORMAL_OFFSET: Constant = Constant {
    name: "normal_offset",
    value: Value::Text("shadow_normal_bias * texel_size * surface_normal.xyz"),
    unit: "m",
    source: 3,
    lines: "153-154",
};
pub const BEVY_DEPTH_OFFSET: Constant = Constant {
    name: "depth_offset",
    value: Value::Text("shadow_depth_bias * direction_to_light.xyz"),
    unit: "m",
    source: 3,
    lines: "155-156",
};
pub const BEVY_OUTSIDE: Constant = Constant {
    name: "world_to_directional_light_local outside the cascade",
    value: Value::Text("w == 0.0: return 1.0 (lit)"),
    unit: "",
    source: 3,
    lines: "133-137, 158-161",
};
pub const BEVY_MAP_SIZE: Constant = Constant {
    name: "DirectionalLightShadowMap::default().size",
    value: Value::Num(2048.0),
    unit: "texels",
    source: 1,
    lines: "114",
};
pub const BEVY_CASCADES: Constant = Constant {
    name: "CascadeShadowConfigBuilder::default()",
    value: Value::Text(
        "num_cascades: 4, minimum_distance: 0.1, maximum_distance: 1000.0, first_cascade_far_bound: 5.0, overlap_proportion: 0.2",
    ),
    unit: "",
    source: 1,
    lines: "255-261",
};
pub const BEVY_TEXEL_SIZE: Constant = Constant {
    name: "cascade_texel_size",
    value: Value::Text("cascade_diameter / cascade_texture_size"),
    unit: "m",
    source: 1,
    lines: "400",
};
pub const BEVY_SAMPLER: Constant = Constant {
    name: "directional_light_sampler",
    value: Value::Text("ClampToEdge, Linear, compare GreaterEqual"),
    unit: "",
    source: 2,
    lines: "157-165",
};
pub const BEVY_FORMAT: Constant = Constant {
    name: "CORE_3D_DEPTH_FORMAT",
    value: Value::Text("Depth32Float"),
    unit: "",
    source: 4,
    lines: "44",
};
pub const BEVY_CULL: Constant = Constant {
    name: "StandardMaterial::default().cull_mode",
    value: Value::Text("Some(Face::Back), in the shadow pass too"),
    unit: "",
    source: 5,
    lines: "826, 1405-1414",
};

/// Bevy's departures, the filter aside.
pub const BEVY_DEPARTURES: [Departure; 4] = [
    Departure {
        what: "4 cascades (the first to 5 m), each a 2048² map fitted to a slice of the camera's frustum, blended over 20 % overlaps",
        why: "the lesson renders one map per light, fitted to the scene (lesson 01): it stands for one cascade at Bevy's size, so a texel, and the normal bias in texels, is the scene's extent / 2048, not a slice's",
    },
    Departure {
        what: "reversed depth, compared GreaterEqual",
        why: "an orthographic light's depth is linear either way: the comparison's outcome is the same up to rounding",
    },
    Departure {
        what: "casters before the light's near plane clamped onto it (`DEPTH_CLAMP_ORTHO`, render/light.rs line 1216)",
        why: "the lesson fits the light's frustum around every caster: none lies before it",
    },
    Departure {
        what: "back faces culled in the shadow pass (the default material's `cull_mode`); the lesson draws both",
        why: "the scenes' casters are closed meshes and a floor facing the light: the face nearest the light is a front face either way",
    },
];

/// `bevy_bias`: Bevy's directional biases, one tap.
pub const BEVY_BIAS: PortCard = PortCard {
    variant: "bevy_bias",
    renderer: "Bevy, DirectionalLight",
    role: Role::Default,
    repository: "bevyengine/bevy",
    sources: &BEVY_SOURCES,
    constants: &[
        BEVY_DEPTH_BIAS,
        BEVY_NORMAL_BIAS,
        BEVY_SQRT_2,
        BEVY_NORMAL_OFFSET,
        BEVY_DEPTH_OFFSET,
        BEVY_OUTSIDE,
        BEVY_MAP_SIZE,
        BEVY_CASCADES,
        BEVY_TEXEL_SIZE,
        BEVY_SAMPLER,
        BEVY_FORMAT,
        BEVY_CULL,
    ],
    departures: &[
        Departure {
            what:
                "its default filter, the Gaussian (Castaño's 9 bilinear taps); one nearest tap here",
            why: "lesson 02 compares biases at one tap; the filter is lesson 03's `bevy`",
        },
        BEVY_DEPARTURES[0],
        BEVY_DEPARTURES[1],
        BEVY_DEPARTURES[2],
        BEVY_DEPARTURES[3],
    ],
};

/// Lesson 02's cards, in variant order.
pub const CARDS: &[PortCard] = &[LEARNOPENGL, WGPU_EXAMPLE, BEVY_BIAS];
