// lesson_01.wgsl: the lit pass of a shadow map with a hard depth comparison.
// Appended to common.wgsl (bindings, vs_scene, lit_output).

@group(2) @binding(0) var shadow_map: texture_depth_2d;
// A comparison sampler with nearest filtering: the hardware does the
// `receiver <= stored` test for one texel and returns 0 or 1.
@group(2) @binding(1) var shadow_compare: sampler_comparison;

// ANCHOR: shadow_coords
// World position -> (u, v, depth) in the shadow map.
fn shadow_coords(world: vec3<f32>) -> vec3<f32> {
    let clip = light.view_proj * vec4<f32>(world, 1.0);
    let ndc = clip.xyz / clip.w;
    // NDC y points up, texture v points down: flip y. WebGPU depth is already in [0, 1].
    return vec3<f32>(ndc.x * 0.5 + 0.5, -ndc.y * 0.5 + 0.5, ndc.z);
}
// ANCHOR_END: shadow_coords

// ANCHOR: depth_compare
// 1 = lit, 0 = in shadow.
fn visibility(world: vec3<f32>) -> f32 {
    let s = shadow_coords(world);
    // Outside the light's frustum nothing was rendered: call it lit.
    if any(s.xy < vec2<f32>(0.0)) || any(s.xy >= vec2<f32>(1.0)) || s.z > 1.0 {
        return 1.0;
    }
    // lit = (s.z <= stored depth of the texel holding s.xy). No bias: a
    // receiver a rounding error behind its own stored depth is "in shadow".
    // That is shadow acne, measured here and fixed in lesson 02.
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
}
// ANCHOR_END: depth_compare

@fragment
fn fs_lit(in: VertexOut) -> LitOut {
    return lit_output(in, visibility(in.world));
}
