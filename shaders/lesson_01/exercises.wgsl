// lesson_01/exercises.wgsl: the chapter's shader exercise, starter code.
// Compiled after common.wgsl (the `light` binding: `light.view_proj`) and
// lesson_01/shadow_map.wgsl (`shadow_map`, `shadow_compare`, `shadow_coords`,
// `outside_shadow_map`); `shadow_depths` (the map as floats) is declared by
// lesson_01/exercise_lit.wgsl.

// ANCHOR: depth_compare
// Exercise 2: a depth comparison without acne, and without a bias. Return 1
// if the point `world` (origin-relative world space) is lit by the light, 0
// if something nearer to the light hides it. The map holds each texel's depth
// at the texel's centre, ((i, j) + 0.5) / N, and the lesson compares the
// receiver with the nearest centre's depth: on a sloped receiver, half of
// each texel lies behind it (acne). Compare with the stored surface at the
// receiver's own (u, v) instead: between four texel centres a flat caster's
// depth is linear in u and v, so interpolate the four stored depths
// bilinearly (`textureLoad(shadow_depths, texel, 0).x` reads one, the same
// map as floats; stay inside it) and return 1 where depth <= that (plus a margin of about 1e-5 for
// rounding). A point outside the map (u or v outside [0, 1), depth > 1, or
// w <= 0) is lit. `light.view_proj` projects into the light's clip space;
// NDC y points up, texture v down.
fn depth_compare(world: vec3<f32>) -> f32 {
    // TODO: the interpolated comparison. This stub calls everything lit.
    return 1.0;
}
// ANCHOR_END: depth_compare
