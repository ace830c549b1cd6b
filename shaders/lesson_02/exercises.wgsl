// lesson_02/exercises.wgsl: the chapter's exercises, starter code. Compiled
// after common.wgsl, lesson_01/shadow_map.wgsl and lesson_02/bias.wgsl, so
// `to_light`, `shadow_coords`, `shadow_texel_size` and `shadow_texel_extent`
// are there to call. Each stub runs, and is wrong: grade says how.

// ANCHOR: slope_bias
// Exercise 1 (beyond the lesson): a slope-scaled bias from the map's own
// slope. Return the shadow-map coordinates (u, v, depth) to compare for the
// receiver at `world`; `n` is its interpolated normal on the light's side.
// `slope_shader` reads the slope off n (tan θ), but where a mesh's normals
// are smoothed across its edges, n is not the plane of the triangle that
// the map stored. Take the receiver's
// depth gradient across the map, g = (dz/du, dz/dv), from one pixel's
// steps across the screen, `dpdxFine(world)` and `dpdyFine(world)` (call
// them before any branch), mapped with `shadow_coords`; then subtract from
// the depth what the plane's depth can differ by at the texel's centre,
// with a margin.
fn slope_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    // TODO: map the two steps, solve them for g, and lower s.z by enough.
    return shadow_coords(world);
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
