// lesson_01.wgsl: the lit pass of a shadow map with a hard depth comparison.
// Appended to common.wgsl (bindings, vs_scene, lit_output) and
// shadow_map.wgsl (the shadow map, its comparison sampler, shadow_coords).

// ANCHOR: depth_compare
// 1 = lit, 0 = in shadow.
fn visibility(world: vec3<f32>) -> f32 {
    let s = shadow_coords(world);
    if outside_shadow_map(world, s) {
        return 1.0;
    }
    // lit = (s.z <= stored depth of the texel holding s.xy): the comparison
    // sampler, with nearest filtering, answers 0 or 1. No bias: on a sloped
    // receiver, the half of each texel beyond the texel's centre lies behind
    // the depth stored for it and reads "in shadow". That is shadow acne:
    // about half of every lit surface at any map size (measured here); the
    // bias that removes it grows with the texel and tan θ (lesson 02).
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
}
// ANCHOR_END: depth_compare

// ANCHOR: fs_lit
// The lit pass's fragment shader: the light, times its visibility.
@fragment
fn fs_lit(in: VertexOut) -> LitOut {
    return lit_output(in, visibility(in.world));
}
// ANCHOR_END: fs_lit
