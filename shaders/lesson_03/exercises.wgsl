// lesson_03/exercises.wgsl: the chapter's exercises, starter code. Appended
// to pcf.wgsl, so `shadow_map`, `shadow_compare` (a comparison sampler: 1.0
// where the stored depth is not in front of the compared depth) and
// `textureDimensions(shadow_map)` are in scope. Each stub runs and gives a
// wrong answer until you fill it in; grade with
// `cargo run --release --bin grade -- lesson_03`.

// ANCHOR: pcf_kernel
// Exercise 1: smooth PCF, the N×N grid (N = 2·radius + 1) slid to the
// receiver's exact (u, v) instead of snapped to texels. The lesson's grid
// taps the texels whose centres lie nearest s.xy + o, so its penumbra moves
// in whole-texel steps. Take the comparisons at texel centres instead: the
// (N + 1)×(N + 1) centres around s.xy (from the centre up and left of it,
// floor(s.xy · size − 0.5) + 0.5, over size), each compared at
// s.z + dot(gradient, c − s.xy) (the receiver's plane at the centre c), and
// weigh them with the bilinear fractions f of s.xy between those centres:
// the first column 1 − f.x, the last f.x, the others 1 (rows likewise).
// Return the weighted sum over N²: the N×N box filter, interpolated.
// `s`: the receiver's (u, v, depth) in the shadow map. The sampler is nearest.
fn exercise_pcf_kernel(s: vec3<f32>, radius: i32, gradient: vec2<f32>) -> f32 {
    // Starter: one comparison at the nearest texel, a hard edge.
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
}
// ANCHOR_END: pcf_kernel

// ANCHOR: world_disk
// Exercise 2 (beyond the lesson): a penumbra whose size is given in world
// units. `pcf_poisson` spreads its 16 taps over `radius` texels, so its
// penumbra grows with the texels: a bigger light frustum or a smaller map
// widens it. Spread them over a disk of `radius_m` metres on the plane the
// light looks through instead, centred on the receiver at `world`:
// `shadow_texel_extent(world)` is one texel's two sides there (along u and
// along v; they differ), and the map is `textureDimensions(shadow_map).x`
// texels across. Rotate the disk per pixel as `pcf_poisson` does
// (`rotation_angle(pixel)`, `POISSON_DISK`), compare each tap at
// s.z + dot(gradient, o) (the sampler is bilinear: each tap blends 2×2
// comparisons) and return the average.
fn exercise_world_disk(s: vec3<f32>, world: vec3<f32>, pixel: vec2<f32>, radius_m: f32, gradient: vec2<f32>) -> f32 {
    // Starter: one bilinear comparison at the centre (a 2-texel penumbra).
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
}
// ANCHOR_END: world_disk
