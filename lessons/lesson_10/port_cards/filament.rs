//! Filament's cards: its default, `ShadowType::PCF` (`filament_pcf`), and
//! its options PCSS (`filament_pcss`) and VSM (`filament_evsm`).

use common::ports::{Constant, Departure, PortCard, Role, Source, Value, TAPS_UNIT};

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
        Constant { name: "PCSS_SHADOW_BLOCKER_SEARCH_TAP_COUNT", value: Value::Num(16.0), unit: TAPS_UNIT, source: 0, lines: "114" },
        Constant { name: "PCSS_SHADOW_FILTER_TAP_COUNT", value: Value::Num(16.0), unit: TAPS_UNIT, source: 0, lines: "116" },
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
