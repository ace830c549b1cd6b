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

// ANCHOR: rotated_poisson
// Exercise 2 (beyond the lesson): 16 taps on a disk of `radius` texels that
// you generate (no table), rotated per pixel. Tap i sits at distance
// radius · sqrt((i + 0.5) / 16) from the centre, at angle i · 2.39996 (the
// golden angle) plus a per-pixel angle from `pixel` (the fragment's
// position in pixels): interleaved gradient noise,
// 2π · fract(52.9829189 · fract(dot(pixel, vec2(0.06711056, 0.00583715)))).
// Compare each tap at s.z + dot(gradient, o) as in exercise 1 (the sampler
// is bilinear here: each tap blends 2×2 comparisons) and return the average.
fn exercise_rotated_poisson(s: vec3<f32>, pixel: vec2<f32>, radius: f32, gradient: vec2<f32>) -> f32 {
    // Starter: one bilinear comparison at the centre (a 2-texel penumbra).
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
}
// ANCHOR_END: rotated_poisson
