//! three.js's cards: its default `PCFShadowMap` (`threejs_pcf`), and its
//! options `PCFSoftShadowMap` (`threejs_pcf_soft`) and `VSMShadowMap`
//! (`threejs_vsm`).

use common::ports::{Constant, Departure, PortCard, Role, Source, Value, TAPS_UNIT};

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
        Constant { name: "PCF taps", value: Value::Num(5.0), unit: TAPS_UNIT, source: 0, lines: "137-143" },
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
        Constant { name: "PCF_SOFT taps", value: Value::Num(16.0), unit: TAPS_UNIT, source: 5, lines: "172-206" },
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
