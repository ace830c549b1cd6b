//! The card of lesson 04's Bevy port ([`super::peers`]): what `bevy_point`
//! takes from Bevy's point-light source, read at a named file, commit and
//! lines, and what it cannot do here (LearnOpenGL's cards sit beside it,
//! in `port_cards.rs`, which lists all three).

use common::measure::counters::TAPS;
use common::ports::{Constant, Departure, PortCard, Role, Source, Value, TAPS_UNIT};

use crate::lesson_02::port_cards::{self as l02, BEVY_AT_E85A706};
use crate::lesson_03::port_cards as l03;

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
    role: Role::Default,
    repository: "bevyengine/bevy",
    sources: &[
        Source {
            file: "crates/bevy_pbr/src/light/point_light.rs",
            commit: BEVY_AT_E85A706,
            repository: None,
        },
        // The files lesson 02's Bevy card (and lesson 03's) cites too.
        l02::BEVY_SOURCES[1],
        l02::BEVY_SOURCES[2],
        l02::BEVY_SOURCES[3],
        l03::BEVY_SHADOW_SAMPLING,
        Source {
            file: "crates/bevy_render/src/maths.wgsl",
            commit: BEVY_AT_E85A706,
            repository: None,
        },
        l02::BEVY_SOURCES[4],
        l02::BEVY_SOURCES[5],
        Source {
            file: "crates/bevy_pbr/src/render/pbr_functions.wgsl",
            commit: BEVY_AT_E85A706,
            repository: None,
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
        l03::BEVY_FILTER_DEFAULT,
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
            name: TAPS.name,
            value: Value::Num(8.0),
            unit: TAPS_UNIT,
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
