// lesson_02/exercises.wgsl: the chapter's exercises, starter code. Compiled
// after common.wgsl, lesson_01/shadow_map.wgsl and lesson_02/bias.wgsl, so
// `to_light`, `shadow_coords`, `shadow_texel_size` and `shadow_texel_extent`
// are there to call. Each stub runs, and is wrong: grade says how.

// ANCHOR: slope_bias
// Exercise 1: slope-scaled bias. How many shadow-map texels to move the
// receiver towards the light, given cos θ = N·L (already clamped to [0, 1];
// θ is the angle between the surface normal and the light). A receiver at θ
// needs tan θ / 2 texels; grazing receivers need many, so scale with tan θ,
// add a small constant, and clamp the result where tan θ runs away.
// The caller moves the receiver `slope_bias(cos_t) × texel` along the light.
fn slope_bias(cos_t: f32) -> f32 {
    // TODO: return a constant plus a multiple of tan θ, clamped.
    return 0.0;
}
// ANCHOR_END: slope_bias

// ANCHOR: grazing_bias
// Exercise 2 (beyond the lesson): a bias for grazing light. Return the
// shadow-map coordinates (u, v, depth) to compare for the receiver at `world`
// (origin-relative) with unit normal `n` on the light's side: the caller
// compares `depth` with the map at (u, v). `shadow_coords(p)` gives them for
// any point p; `shadow_texel_extent(world)` is one texel's two sides in world
// units there, `to_light(world)` the unit vector towards the light.
fn grazing_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    // TODO: move the receiver off its surface (or its depth), so that it
    // stops shadowing itself at grazing angles without letting light under
    // thin casters.
    return shadow_coords(world);
}
// ANCHOR_END: grazing_bias
