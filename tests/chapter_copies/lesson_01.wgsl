// lesson_01/exercises.wgsl: the chapter's shader exercise, starter code.
// Compiled after common.wgsl (the `light` binding: `light.view_proj`) and
// lesson_01/shadow_map.wgsl (`shadow_map`, `shadow_compare`).

// ANCHOR: depth_compare
// Exercise 2: the shadow test. Return 1 if the point `world` (origin-relative
// world space) is lit by the light, 0 if something nearer to the light hides
// it. Project it with `light.view_proj` into the light's clip space, divide by
// w, turn NDC x, y into texture coordinates u, v (v points down), and compare
// its depth with the stored one: `textureSampleCompareLevel(shadow_map,
// shadow_compare, uv, depth)` returns 1 where depth <= stored. A point outside
// the map (u or v outside [0, 1), depth > 1, or w <= 0) is lit.
fn depth_compare(world: vec3<f32>) -> f32 {
    // TODO: the shadow test. This stub calls everything lit.
    return 1.0;
}
// ANCHOR_END: depth_compare
