//! The cards of lesson 04's ports ([`super::peers`]): what each takes from
//! its renderer's source, read at a named file, commit and lines, and what
//! it cannot do here. A transcription of the sources, written apart from
//! the port's own constants; `tests/port_cards.rs` checks one against the
//! other, and the book's table of departures is generated from these.

use common::measure::counters::TAPS;
use common::ports::{Constant, Departure, PortCard, Role, Source, Value, TAPS_UNIT};

pub use super::bevy_card::BEVY_POINT;

const LEARNOPENGL_AT_279E6BE: &str = "279e6be7fa6d0bcbff11628934dfce29d94ff277";
const LEARNOPENGL_AT_F844F7C: &str = "f844f7c541a2428647683b132170f9e72931e445";

/// LearnOpenGL's depth cube is whatever `GL_DEPTH_COMPONENT` the driver
/// picks; ours is Depth32Float.
const GL_DEPTH_FORMAT: Departure = Departure {
    what: "`GL_DEPTH_COMPONENT` with `GL_FLOAT` leaves the depth format to the driver (commonly 24-bit); the port stores Depth32Float",
    why: "the lesson's cube is Depth32Float on every backend; 24 bits of distance / 25 m are 1.5 µm steps, far under the bias",
};

/// LearnOpenGL renders the six faces in one pass.
const GL_GEOMETRY_SHADER: Departure = Departure {
    what: "one pass for the six faces, a geometry shader emitting each triangle to every face (`3.2.1.point_shadows_depth.gs`)",
    why: "wgpu has no geometry shaders: six passes write the same texels, at another cost",
};

/// LearnOpenGL culls the cubes' back faces in its depth pass.
const GL_CULL_BACK: Departure = Departure {
    what: "back faces culled in the depth pass (`GL_CULL_FACE` on, off only for its room)",
    why: "the lesson draws every caster with both faces: a closed caster's face nearest the light is a front face, so culling stores the same depth; a room around the light (the seams scene) LearnOpenGL draws unculled too",
};

/// The lesson leaves out what its light's range cannot reach.
const RANGE_CULLING: Departure = Departure {
    what: "every object drawn into every face; the port leaves out casters past the light's range and faces they miss (the lesson's culling)",
    why: "what it leaves out shadows only receivers past the range, which the lesson's light does not reach and its metric does not count",
};

const LEARNOPENGL_DIFFUSE: &str = "max(dot(lightDir, normal), 0.0)";

/// `learnopengl_1tap`: LearnOpenGL "Point Shadows".
pub const LEARNOPENGL_1TAP: PortCard = PortCard {
    variant: "learnopengl_1tap",
    renderer: "LearnOpenGL, Point Shadows",
    role: Role::Default,
    repository: "JoeyDeVries/LearnOpenGL",
    sources: &[
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/point_shadows.cpp",
            commit: LEARNOPENGL_AT_279E6BE,
            repository: None,
        },
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/3.2.1.point_shadows_depth.fs",
            commit: LEARNOPENGL_AT_279E6BE,
            repository: None,
        },
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/3.2.1.point_shadows.fs",
            commit: LEARNOPENGL_AT_279E6BE,
            repository: None,
        },
    ],
    constants: &[
        Constant {
            name: "SHADOW_WIDTH",
            value: Value::Num(1024.0),
            unit: "texels",
            source: 0,
            lines: "94",
        },
        Constant {
            name: "GL_TEXTURE_MAG_FILTER, GL_TEXTURE_MIN_FILTER",
            value: Value::Text("GL_NEAREST"),
            unit: "",
            source: 0,
            lines: "103-104",
        },
        Constant {
            name: "near_plane",
            value: Value::Num(1.0),
            unit: "m",
            source: 0,
            lines: "150",
        },
        Constant {
            name: "far_plane",
            value: Value::Num(25.0),
            unit: "m",
            source: 0,
            lines: "151",
        },
        Constant {
            name: "shadowProj",
            value: Value::Text(
                "glm::perspective(glm::radians(90.0f), 1, near_plane, far_plane): clipped at both planes (no GL_DEPTH_CLAMP)",
            ),
            unit: "",
            source: 0,
            lines: "152",
        },
        Constant {
            name: "gl_FragDepth",
            value: Value::Text("length(FragPos.xyz - lightPos) / far_plane"),
            unit: "depth units",
            source: 1,
            lines: "9-15",
        },
        Constant {
            name: "bias",
            value: Value::Num(0.05),
            unit: "m",
            source: 2,
            lines: "30",
        },
        Constant {
            name: "shadow",
            value: Value::Text(
                "currentDepth - bias > closestDepth ? 1.0 : 0.0, closestDepth = texture(depthMap, fragToLight).r * far_plane",
            ),
            unit: "",
            source: 2,
            lines: "22-31",
        },
        Constant {
            name: TAPS.name,
            value: Value::Num(1.0),
            unit: TAPS_UNIT,
            source: 2,
            lines: "24",
        },
        Constant {
            name: "diff",
            value: Value::Text(LEARNOPENGL_DIFFUSE),
            unit: "",
            source: 2,
            lines: "47",
        },
    ],
    departures: &[GL_DEPTH_FORMAT, GL_GEOMETRY_SHADER, GL_CULL_BACK, RANGE_CULLING],
};

/// LearnOpenGL's 20 `gridSamplingDisk` directions, in its order.
const GRID_SAMPLING_DISK: &[f64] = &[
    1., 1., 1., 1., -1., 1., -1., -1., 1., -1., 1., 1., //
    1., 1., -1., 1., -1., -1., -1., -1., -1., -1., 1., -1., //
    1., 1., 0., 1., -1., 0., -1., -1., 0., -1., 1., 0., //
    1., 0., 1., -1., 0., 1., 1., 0., -1., -1., 0., -1., //
    0., 1., 1., 0., -1., 1., 0., -1., -1., 0., 1., -1.,
];

/// `learnopengl_pcf20`: LearnOpenGL "Point Shadows", soft.
pub const LEARNOPENGL_PCF20: PortCard = PortCard {
    variant: "learnopengl_pcf20",
    renderer: "LearnOpenGL, Point Shadows (soft)",
    role: Role::Default,
    repository: "JoeyDeVries/LearnOpenGL",
    sources: &[
        Source {
            file: "src/5.advanced_lighting/3.2.2.point_shadows_soft/point_shadows_soft.cpp",
            commit: LEARNOPENGL_AT_F844F7C,
            repository: None,
        },
        // point_shadows_soft.cpp line 82 loads the 3.2.1 depth shaders.
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/3.2.1.point_shadows_depth.fs",
            commit: LEARNOPENGL_AT_F844F7C,
            repository: None,
        },
        Source {
            file: "src/5.advanced_lighting/3.2.2.point_shadows_soft/3.2.2.point_shadows.fs",
            commit: LEARNOPENGL_AT_F844F7C,
            repository: None,
        },
    ],
    constants: &[
        Constant {
            name: "SHADOW_WIDTH",
            value: Value::Num(1024.0),
            unit: "texels",
            source: 0,
            lines: "90",
        },
        Constant {
            name: "GL_TEXTURE_MAG_FILTER, GL_TEXTURE_MIN_FILTER",
            value: Value::Text("GL_NEAREST"),
            unit: "",
            source: 0,
            lines: "99-100",
        },
        Constant {
            name: "near_plane",
            value: Value::Num(1.0),
            unit: "m",
            source: 0,
            lines: "146",
        },
        Constant {
            name: "far_plane",
            value: Value::Num(25.0),
            unit: "m",
            source: 0,
            lines: "147",
        },
        Constant {
            name: "shadowProj",
            value: Value::Text(
                "glm::perspective(glm::radians(90.0f), 1, near_plane, far_plane): clipped at both planes (no GL_DEPTH_CLAMP)",
            ),
            unit: "",
            source: 0,
            lines: "148",
        },
        Constant {
            name: "gl_FragDepth",
            value: Value::Text("length(FragPos.xyz - lightPos) / far_plane"),
            unit: "depth units",
            source: 1,
            lines: "9-15",
        },
        Constant {
            name: "gridSamplingDisk",
            value: Value::List(GRID_SAMPLING_DISK),
            unit: "directions (x, y, z)",
            source: 2,
            lines: "21-28",
        },
        Constant {
            name: "bias",
            value: Value::Num(0.15),
            unit: "m",
            source: 2,
            lines: "63",
        },
        Constant {
            name: "samples",
            value: Value::Num(20.0),
            unit: TAPS_UNIT,
            source: 2,
            lines: "64",
        },
        Constant {
            name: "diskRadius",
            value: Value::Text("(1.0 + (viewDistance / far_plane)) / 25.0"),
            unit: "m",
            source: 2,
            lines: "65-66",
        },
        Constant {
            name: "diskRadius divisor",
            value: Value::Num(25.0),
            unit: "",
            source: 2,
            lines: "66",
        },
        Constant {
            name: "shadow",
            value: Value::Text(
                "sum over i of currentDepth - bias > texture(depthMap, fragToLight + gridSamplingDisk[i] * diskRadius).r * far_plane, / samples",
            ),
            unit: "",
            source: 2,
            lines: "67-74",
        },
        Constant {
            name: "diff",
            value: Value::Text(LEARNOPENGL_DIFFUSE),
            unit: "",
            source: 2,
            lines: "91",
        },
    ],
    departures: &[GL_DEPTH_FORMAT, GL_GEOMETRY_SHADER, GL_CULL_BACK, RANGE_CULLING],
};

/// Lesson 04's cards, in variant order.
pub const CARDS: &[PortCard] = &[LEARNOPENGL_1TAP, LEARNOPENGL_PCF20, BEVY_POINT];
