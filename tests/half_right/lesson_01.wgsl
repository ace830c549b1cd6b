// lesson_01 exercises answered HALF RIGHT (tests/half_right/lesson_01.rs):
// each function has the mistake its comment names, which the grader must
// fail with that likely cause.

// ANCHOR: depth_compare
fn depth_compare(world: vec3<f32>) -> f32 {
    let s = shadow_coords(world);
    if outside_shadow_map(world, s) {
        return 1.0;
    }
    let size = vec2<i32>(textureDimensions(shadow_map));
    // Texel (i, j)'s centre is at ((i, j) + 0.5) / N: t's whole part is the
    // centre up and left of (u, v), its fraction the way to the next ones.
    // THE MISTAKE: texel (i, j)'s centre taken at (i, j) / N, not at
    // ((i, j) + 0.5) / N: every lookup is half a texel off.
    let t = s.xy * vec2<f32>(size);
    let i = vec2<i32>(floor(t));
    let f = t - floor(t);
    let lo = vec2<i32>(0);
    let hi = size - 1;
    let d00 = textureLoad(shadow_depths, clamp(i, lo, hi), 0).x;
    let d10 = textureLoad(shadow_depths, clamp(i + vec2<i32>(1, 0), lo, hi), 0).x;
    let d01 = textureLoad(shadow_depths, clamp(i + vec2<i32>(0, 1), lo, hi), 0).x;
    let d11 = textureLoad(shadow_depths, clamp(i + vec2<i32>(1, 1), lo, hi), 0).x;
    // A flat caster's depth is linear between the centres: exact there.
    let stored = mix(mix(d00, d10, f.x), mix(d01, d11, f.x), f.y);
    // The margin covers rounding, not a slope.
    return select(0.0, 1.0, s.z <= stored + 1e-5);
}
// ANCHOR_END: depth_compare
