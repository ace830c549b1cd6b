//! The cards of lesson 03's ports (`learnopengl_pcf`, `wgpu_example_hw2x2`,
//! `bevy`): lesson 02's cards of the same renderers (their biases, maps and
//! shadow passes), with the filters they add, read at a named file, commit
//! and lines. `tests/port_cards.rs` checks them against the ports
//! ([`super::pcf`], `shaders/lesson_03/pcf.wgsl`); the book's table of
//! departures is generated from these.

use common::measure::counters::TAPS;
use common::ports::{Constant, PortCard, Role, Source, Value, TAPS_UNIT};

use crate::lesson_02::port_cards as l02;

const BEVY_AT_3971912: &str = "3971912a7857f8603fc5703f4b6dc514322feff2";

/// LearnOpenGL's 3×3 offsets, (x, y) in texels, in its loop's order.
const LEARNOPENGL_PCF_OFFSETS: &[f64] = &[
    -1., -1., -1., 0., -1., 1., //
    0., -1., 0., 0., 0., 1., //
    1., -1., 1., 0., 1., 1.,
];

/// `learnopengl_pcf`: LearnOpenGL's bias and 3×3 PCF.
pub const LEARNOPENGL_PCF: PortCard = PortCard {
    variant: "learnopengl_pcf",
    renderer: "LearnOpenGL, Shadow Mapping",
    role: Role::Default,
    repository: "JoeyDeVries/LearnOpenGL",
    sources: l02::LEARNOPENGL_SOURCES,
    constants: &[
        l02::LEARNOPENGL_SHADOW_WIDTH,
        l02::LEARNOPENGL_NEAREST,
        l02::LEARNOPENGL_BORDER,
        l02::LEARNOPENGL_NEAR,
        l02::LEARNOPENGL_FAR,
        l02::LEARNOPENGL_PROJECTION,
        l02::LEARNOPENGL_BIAS,
        l02::LEARNOPENGL_BIAS_SLOPE,
        l02::LEARNOPENGL_BIAS_MIN,
        Constant {
            name: "texelSize",
            value: Value::Text("1.0 / textureSize(shadowMap, 0)"),
            unit: "uv",
            source: 0,
            lines: "35",
        },
        Constant {
            name: "PCF offsets (x, y)",
            value: Value::List(LEARNOPENGL_PCF_OFFSETS),
            unit: "texels",
            source: 0,
            lines: "36-43",
        },
        Constant {
            name: "shadow",
            value: Value::Text(
                "shadow += currentDepth - bias > pcfDepth ? 1.0 : 0.0: every tap against the centre's depth",
            ),
            unit: "",
            source: 0,
            lines: "40-41",
        },
        Constant {
            name: TAPS.name,
            value: Value::Num(9.0),
            unit: TAPS_UNIT,
            source: 0,
            lines: "44",
        },
        l02::LEARNOPENGL_PAST_FAR,
    ],
    departures: &[l02::LEARNOPENGL_DEPTH_UNITS, l02::GL_DEPTH_FORMAT],
};

/// `wgpu_example_hw2x2`: the wgpu example's shadow pass and its linear
/// comparison sampler.
pub const WGPU_EXAMPLE_HW2X2: PortCard = PortCard {
    variant: "wgpu_example_hw2x2",
    renderer: "wgpu, shadow example",
    role: Role::Default,
    repository: "gfx-rs/wgpu",
    sources: l02::WGPU_SOURCES,
    constants: &[
        l02::WGPU_SHADOW_SIZE,
        l02::WGPU_SHADOW_FORMAT,
        l02::WGPU_CULL,
        l02::WGPU_UNCLIPPED,
        l02::WGPU_DEPTH_COMPARE,
        l02::WGPU_BIAS_CONSTANT,
        l02::WGPU_BIAS_SLOPE,
        l02::WGPU_BIAS_CLAMP,
        l02::WGPU_SAMPLER,
        l02::WGPU_LIGHTS,
        l02::WGPU_FETCH_SHADOW,
        Constant {
            name: TAPS.name,
            value: Value::Num(1.0),
            unit: "taps (of 2×2 texels)",
            source: 1,
            lines: "75",
        },
    ],
    departures: &l02::WGPU_DEPARTURES,
};

const fn bevy_sources() -> [Source; 7] {
    let b = l02::BEVY_SOURCES;
    [b[0], b[1], b[2], b[3], b[4], b[5], BEVY_SHADOW_SAMPLING]
}
const BEVY_SOURCES: [Source; 7] = bevy_sources();

/// Bevy's shadow sampling (its Castaño 13 and the point light's filters).
pub const BEVY_SHADOW_SAMPLING: Source = Source {
    file: "crates/bevy_pbr/src/render/shadow_sampling.wgsl",
    commit: BEVY_AT_3971912,
    repository: None,
};

/// Bevy's default filter; `source: 1` is `crates/bevy_pbr/src/light/mod.rs`
/// in this card and in lesson 04's `bevy_point`.
pub const BEVY_FILTER_DEFAULT: Constant = Constant {
    name: "ShadowFilteringMethod::default()",
    value: Value::Text("Gaussian"),
    unit: "",
    source: 1,
    lines: "483-484",
};

/// Bevy's Castaño 13, as its source writes it (source 6).
const fn castano(name: &'static str, text: &'static str, lines: &'static str) -> Constant {
    Constant {
        name,
        value: Value::Text(text),
        unit: "",
        source: 6,
        lines,
    }
}

/// `bevy`: Bevy's directional biases and its default filter.
pub const BEVY: PortCard = PortCard {
    variant: "bevy",
    renderer: "Bevy, DirectionalLight",
    role: Role::Default,
    repository: "bevyengine/bevy",
    sources: &BEVY_SOURCES,
    constants: &[
        l02::BEVY_DEPTH_BIAS,
        l02::BEVY_NORMAL_BIAS,
        l02::BEVY_SQRT_2,
        l02::BEVY_NORMAL_OFFSET,
        l02::BEVY_DEPTH_OFFSET,
        l02::BEVY_OUTSIDE,
        l02::BEVY_MAP_SIZE,
        l02::BEVY_CASCADES,
        l02::BEVY_TEXEL_SIZE,
        l02::BEVY_SAMPLER,
        l02::BEVY_FORMAT,
        l02::BEVY_CULL,
        BEVY_FILTER_DEFAULT,
        castano(
            "sample_shadow_map (SHADOW_FILTER_METHOD_GAUSSIAN)",
            "sample_shadow_map_castano_thirteen(light_local, depth, array_index)",
            "156-158",
        ),
        castano(
            "base_uv",
            "var base_uv = floor(uv + 0.5); base_uv -= 0.5; base_uv *= inv_shadow_map_size;",
            "70, 73-74",
        ),
        castano(
            "s, t",
            "let s = (uv.x + 0.5 - base_uv.x); let t = (uv.y + 0.5 - base_uv.y);",
            "71-72",
        ),
        castano(
            "uw0, uw1, uw2",
            "let uw0 = (4.0 - 3.0 * s); let uw1 = 7.0; let uw2 = (1.0 + 3.0 * s);",
            "76-78",
        ),
        castano(
            "u0, u1, u2",
            "let u0 = (3.0 - 2.0 * s) / uw0 - 2.0; let u1 = (3.0 + s) / uw1; let u2 = s / uw2 + 2.0;",
            "80-82",
        ),
        castano(
            "vw0, vw1, vw2",
            "let vw0 = (4.0 - 3.0 * t); let vw1 = 7.0; let vw2 = (1.0 + 3.0 * t);",
            "84-86",
        ),
        castano(
            "v0, v1, v2",
            "let v0 = (3.0 - 2.0 * t) / vw0 - 2.0; let v1 = (3.0 + t) / vw1; let v2 = t / vw2 + 2.0;",
            "88-90",
        ),
        castano(
            "sum",
            "sum += uwi * vwj * sample_shadow_map_hardware(base_uv + (vec2(ui, vj) * inv_shadow_map_size), depth, array_index), i and j in 0..3",
            "94-104",
        ),
        castano("return", "return sum * (1.0 / 144.0);", "106"),
        Constant {
            name: TAPS.name,
            value: Value::Num(9.0),
            unit: "taps (of 2×2 texels)",
            source: 6,
            lines: "94-104",
        },
    ],
    departures: &l02::BEVY_DEPARTURES,
};

/// Lesson 03's cards, in variant order.
pub const CARDS: &[PortCard] = &[LEARNOPENGL_PCF, WGPU_EXAMPLE_HW2X2, BEVY];
