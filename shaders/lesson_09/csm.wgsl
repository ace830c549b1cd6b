// csm.wgsl: the lit pass of cascaded shadow maps. Appended to common.wgsl
// (bindings, vs_scene, lit_output). The shadow pass is lesson 01's
// (vs_light_depth), drawn once per layer with that cascade's matrix.

@group(2) @binding(0) var cascade_maps: texture_depth_2d_array;
// Linear filtering: the hardware compares the 4 nearest texels and blends
// the answers (lesson 03's hw_2x2), one tap per lookup.
@group(2) @binding(1) var cascade_compare: sampler_comparison;

// Rust: lesson_09::csm::CsmParams.
struct Cascades {
    view_proj: array<mat4x4<f32>, 4>,
    // The view depth where cascade i ends.
    split_far: vec4<f32>,
    // Cascade i's texel, in metres.
    texel: vec4<f32>,
    // xyz: the camera's view axis, w: unused (the count is CASCADES).
    forward: vec4<f32>,
    // x: blend band (fraction of a cascade), y: normal offset in texels,
    // z: the first cascade's near depth.
    options: vec4<f32>,
};
@group(2) @binding(2) var<storage, read> cascades: Cascades;

// The variant's choices, fixed when its pipeline is compiled (Rust:
// lesson_09 `CsmPipelines`): a loop or a branch on a buffer value stays in
// the shader, and a software rasteriser runs every iteration and the
// second lookup, masked, in every pixel of every variant.
// The cascade count, 1 to 4 (no default: every pipeline sets it).
override CASCADES: u32;
// Blend across the splits; the band's width is options.x.
override BLEND: bool = false;

// ANCHOR: select_cascade
// The first cascade whose far split lies beyond the pixel's view depth
// (the distance along the view axis, not to the eye: the splits are
// planes). Past the last split: the last cascade. CASCADES, the count,
// is a constant of the variant's pipeline.
fn select_cascade(view_depth: f32) -> u32 {
    let count = CASCADES;
    var i = 0u;
    while i + 1u < count && view_depth >= cascades.split_far[i] {
        i += 1u;
    }
    return i;
}
// ANCHOR_END: select_cascade

// ANCHOR: cascade_lookup
// 1 = lit. The receiver first moves along its normal by a fraction of
// THIS cascade's texel (a far cascade's texels are metres wide; one bias
// in metres would be too much near and too little far), times sin θ:
// nothing head-on, most at grazing light. The shadow pass adds lesson 02's
// slope-scaled bias, which the rasteriser scales per cascade by itself.
fn cascade_lookup(i: u32, world: vec3<f32>, n: vec3<f32>) -> f32 {
    let cos_t = clamp(dot(n, to_light(world)), 0.0, 1.0);
    let sin_t = sqrt(1.0 - cos_t * cos_t);
    let p = world + n * (cascades.options.y * cascades.texel[i] * sin_t);
    let clip = cascades.view_proj[i] * vec4<f32>(p, 1.0);
    // Orthographic: w = 1. NDC y up, texture v down: flip y.
    let s = vec3<f32>(clip.x * 0.5 + 0.5, -clip.y * 0.5 + 0.5, clip.z);
    if any(s.xy < vec2<f32>(0.0)) || any(s.xy >= vec2<f32>(1.0)) || s.z > 1.0 {
        return 1.0; // outside the cascade's box: nothing was rendered there
    }
    return textureSampleCompareLevel(cascade_maps, cascade_compare, s.xy, i32(i), s.z);
}
// ANCHOR_END: cascade_lookup

fn csm_visibility(world: vec3<f32>, n: vec3<f32>) -> f32 {
    let depth = dot(world - camera.eye.xyz, cascades.forward.xyz);
    let i = select_cascade(depth);
    var v = cascade_lookup(i, world, n);
    // ANCHOR: blend
    // In the last `band` of cascade i, fade into cascade i + 1: the step in
    // texel size at the split becomes a ramp instead of a visible seam.
    if BLEND && i + 1u < CASCADES {
        let band = cascades.options.x;
        var start = cascades.options.z;
        if i > 0u {
            start = cascades.split_far[i - 1u];
        }
        let end = cascades.split_far[i];
        let width = band * (end - start);
        let t = (depth - (end - width)) / width;
        if t > 0.0 {
            v = mix(v, cascade_lookup(i + 1u, world, n), clamp(t, 0.0, 1.0));
        }
    }
    // ANCHOR_END: blend
    return v;
}

@fragment
fn fs_lit(in: VertexOut) -> LitOut {
    return lit_output(in, csm_visibility(in.world, facing_normal(in)));
}

// The cascade picture (`<variant>_cascades.png`): each pixel tinted by the
// cascade it samples, shaded by the light and its shadow.
const CASCADE_TINTS = array<vec3<f32>, 4>(
    vec3<f32>(1.0, 0.35, 0.3), vec3<f32>(0.35, 0.9, 0.35),
    vec3<f32>(0.35, 0.5, 1.0), vec3<f32>(1.0, 0.85, 0.3),
);

@fragment
fn fs_cascade_tint(in: VertexOut) -> @location(0) vec4<f32> {
    let n = facing_normal(in);
    let depth = dot(in.world - camera.eye.xyz, cascades.forward.xyz);
    let i = select_cascade(depth);
    let lambert = max(dot(n, to_light(in.world)), 0.0);
    let shade = 0.3 + 0.7 * lambert * csm_visibility(in.world, n);
    return vec4<f32>(CASCADE_TINTS[i] * shade, 1.0);
}
