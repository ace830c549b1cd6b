//! The cards of lesson 04's ports ([`super::peers`]): what each takes from
//! its renderer's source, read at a named file, commit and lines, and what
//! it cannot do here. A transcription of the sources, written apart from
//! the port's own constants; `tests/port_cards.rs` checks one against the
//! other, and the book's table of departures is generated from these.

use common::ports::{Constant, Departure, PortCard, Source, Value};

const LEARNOPENGL_AT_279E6BE: &str = "279e6be7fa6d0bcbff11628934dfce29d94ff277";
const LEARNOPENGL_AT_F844F7C: &str = "f844f7c541a2428647683b132170f9e72931e445";
const BEVY_AT_E85A706: &str = "e85a706c30d78f877ea865c1af943f54e94ece33";
const BEVY_AT_3971912: &str = "3971912a7857f8603fc5703f4b6dc514322feff2";

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
    repository: "JoeyDeVries/LearnOpenGL",
    sources: &[
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/point_shadows.cpp",
            commit: LEARNOPENGL_AT_279E6BE,
        },
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/3.2.1.point_shadows_depth.fs",
            commit: LEARNOPENGL_AT_279E6BE,
        },
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/3.2.1.point_shadows.fs",
            commit: LEARNOPENGL_AT_279E6BE,
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
            name: "taps",
            value: Value::Num(1.0),
            unit: "taps",
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
    repository: "JoeyDeVries/LearnOpenGL",
    sources: &[
        Source {
            file: "src/5.advanced_lighting/3.2.2.point_shadows_soft/point_shadows_soft.cpp",
            commit: LEARNOPENGL_AT_F844F7C,
        },
        // point_shadows_soft.cpp line 82 loads the 3.2.1 depth shaders.
        Source {
            file: "src/5.advanced_lighting/3.2.1.point_shadows/3.2.1.point_shadows_depth.fs",
            commit: LEARNOPENGL_AT_F844F7C,
        },
        Source {
            file: "src/5.advanced_lighting/3.2.2.point_shadows_soft/3.2.2.point_shadows.fs",
            commit: LEARNOPENGL_AT_F844F7C,
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
            unit: "taps",
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

/// Bevy's D3D 8×MSAA sample positions, (x, y) pairs.
const D3D_SAMPLE_POINT_POSITIONS: &[f64] = &[
    0.125, -0.375, -0.125, 0.375, 0.625, 0.125, -0.375, -0.625, //
    -0.625, 0.625, -0.875, -0.125, 0.375, 0.875, 0.875, -0.875,
];
/// Their Gaussian weights.
const D3D_SAMPLE_POINT_COEFFS: &[f64] = &[
    0.157112, 0.157112, 0.138651, 0.130251, 0.114946, 0.114946, 0.107982, 0.079001,
];

/// `bevy_point`: Bevy's `PointLight` defaults.
pub const BEVY_POINT: PortCard = PortCard {
    variant: "bevy_point",
    renderer: "Bevy, PointLight",
    repository: "bevyengine/bevy",
    sources: &[
        Source {
            file: "crates/bevy_pbr/src/light/point_light.rs",
            commit: BEVY_AT_E85A706,
        },
        Source {
            file: "crates/bevy_pbr/src/light/mod.rs",
            commit: BEVY_AT_E85A706,
        },
        Source {
            file: "crates/bevy_pbr/src/render/light.rs",
            commit: BEVY_AT_E85A706,
        },
        Source {
            file: "crates/bevy_pbr/src/render/shadows.wgsl",
            commit: BEVY_AT_E85A706,
        },
        Source {
            file: "crates/bevy_pbr/src/render/shadow_sampling.wgsl",
            commit: BEVY_AT_3971912,
        },
        Source {
            file: "crates/bevy_render/src/maths.wgsl",
            commit: BEVY_AT_E85A706,
        },
        Source {
            file: "crates/bevy_core_pipeline/src/core_3d/mod.rs",
            commit: BEVY_AT_E85A706,
        },
        Source {
            file: "crates/bevy_pbr/src/pbr_material.rs",
            commit: BEVY_AT_E85A706,
        },
        Source {
            file: "crates/bevy_pbr/src/render/pbr_functions.wgsl",
            commit: BEVY_AT_E85A706,
        },
    ],
    constants: &[
        Constant {
            name: "PointLight::DEFAULT_SHADOW_DEPTH_BIAS",
            value: Value::Num(0.08),
            unit: "m",
            source: 0,
            lines: "68",
        },
        Constant {
            name: "PointLight::DEFAULT_SHADOW_NORMAL_BIAS",
            value: Value::Num(0.6),
            unit: "texels",
            source: 0,
            lines: "69",
        },
        Constant {
            name: "PointLightShadowMap::default().size",
            value: Value::Num(1024.0),
            unit: "texels",
            source: 1,
            lines: "97",
        },
        Constant {
            name: "ShadowFilteringMethod::default()",
            value: Value::Text("Gaussian"),
            unit: "",
            source: 1,
            lines: "483-484",
        },
        Constant {
            name: "point_light_sampler",
            value: Value::Text("Linear, compare GreaterEqual"),
            unit: "",
            source: 2,
            lines: "147-155",
        },
        Constant {
            name: "point_light_texel_size",
            value: Value::Text("2.0 / point_light_shadow_map.size"),
            unit: "m at 1 m",
            source: 2,
            lines: "230",
        },
        Constant {
            name: "shadow_normal_bias",
            value: Value::Text(
                "point_light.shadow_normal_bias * point_light_texel_size * std::f32::consts::SQRT_2",
            ),
            unit: "m per m",
            source: 2,
            lines: "257-259",
        },
        Constant {
            name: "POINT_LIGHT_NEAR_Z",
            value: Value::Num(0.1),
            unit: "m",
            source: 2,
            lines: "359",
        },
        Constant {
            name: "cube_face_projection",
            value: Value::Text(
                "Mat4::perspective_infinite_reverse_rh(FRAC_PI_2, 1.0, POINT_LIGHT_NEAR_Z): reversed, no far plane, clipped at near",
            ),
            unit: "",
            source: 2,
            lines: "549-550",
        },
        Constant {
            name: "point_light_shadow_map_texture format",
            value: Value::Text("CORE_3D_DEPTH_FORMAT"),
            unit: "",
            source: 2,
            lines: "804",
        },
        Constant {
            name: "CORE_3D_DEPTH_FORMAT",
            value: Value::Text("Depth32Float"),
            unit: "",
            source: 6,
            lines: "44",
        },
        Constant {
            name: "distance_to_light",
            value: Value::Text("max of abs(light position - frag_position)"),
            unit: "m",
            source: 3,
            lines: "21-23",
        },
        Constant {
            name: "normal_offset",
            value: Value::Text("shadow_normal_bias * distance_to_light * surface_normal.xyz"),
            unit: "m",
            source: 3,
            lines: "28",
        },
        Constant {
            name: "depth_offset",
            value: Value::Text("shadow_depth_bias * normalize(surface_to_light.xyz)"),
            unit: "m",
            source: 3,
            lines: "29",
        },
        Constant {
            name: "depth",
            value: Value::Text(
                "zw.x / zw.y of the offset position's major axis (= POINT_LIGHT_NEAR_Z / major axis)",
            ),
            unit: "depth units",
            source: 3,
            lines: "33-42",
        },
        Constant {
            name: "flip_z",
            value: Value::List(&[1.0, 1.0, -1.0]),
            unit: "",
            source: 3,
            lines: "14, 44-46",
        },
        Constant {
            name: "surface_normal",
            value: Value::Text("in.world_normal"),
            unit: "",
            source: 8,
            lines: "416",
        },
        Constant {
            name: "POINT_SHADOW_SCALE",
            value: Value::Num(0.003),
            unit: "m per m of distance_to_light",
            source: 4,
            lines: "32",
        },
        Constant {
            name: "D3D_SAMPLE_POINT_POSITIONS",
            value: Value::List(D3D_SAMPLE_POINT_POSITIONS),
            unit: "(x, y) in units of scale",
            source: 4,
            lines: "39-48",
        },
        Constant {
            name: "D3D_SAMPLE_POINT_COEFFS",
            value: Value::List(D3D_SAMPLE_POINT_COEFFS),
            unit: "weights",
            source: 4,
            lines: "53-62",
        },
        Constant {
            name: "sample_shadow_cubemap_gaussian",
            value: Value::Text(
                "basis = orthonormalize(light_local, up) * scale * distance_to_light, up (0, 1, 0) or (1, 0, 0) where dot > 0.99; sum of coeff × tap at light_local + x * basis[0] + y * basis[1]",
            ),
            unit: "",
            source: 4,
            lines: "206-247",
        },
        Constant {
            name: "taps",
            value: Value::Num(8.0),
            unit: "taps",
            source: 4,
            lines: "222-245",
        },
        Constant {
            name: "orthonormalize",
            value: Value::Text(
                "z = normalize(z_unnormalized); x = normalize(cross(z, up)); y = cross(z, x)",
            ),
            unit: "",
            source: 5,
            lines: "72-77",
        },
        Constant {
            name: "StandardMaterial::default().cull_mode",
            value: Value::Text("Some(Face::Back)"),
            unit: "",
            source: 7,
            lines: "826",
        },
    ],
    departures: &[
        Departure {
            what: "a reversed infinite projection (depth = 0.1 / major axis, compared GreaterEqual); the port stores the lesson's depth from near 0.1 to a far plane at the light's range",
            why: "the lesson's cube has one depth convention; both depths fall with the major axis, so the comparison's outcome is Bevy's up to Depth32Float rounding (60 µm at 10 m here). Casters past the range are clipped here, culled by Bevy (its frusta end at the range): their shadows fall only past the range, where Bevy lights nothing",
        },
        Departure {
            what: "back faces culled in the shadow pass (the default material's `cull_mode`)",
            why: "the lesson draws every caster with both faces: a closed caster's face nearest the light is a front face, so culling stores the same depth; a room around the light (the seams scene), all back faces from inside, would cast nothing in Bevy and here shadows only what lies behind its walls, which no scene shows",
        },
        Departure {
            what: "the normal of the front face Bevy draws (its default material culls back faces); the port turns the interpolated normal to the camera's side",
            why: "the lesson draws both sides of its open meshes; where the camera sees a front face the two agree",
        },
    ],
};

/// Lesson 04's cards, in variant order.
pub const CARDS: &[PortCard] = &[LEARNOPENGL_1TAP, LEARNOPENGL_PCF20, BEVY_POINT];
