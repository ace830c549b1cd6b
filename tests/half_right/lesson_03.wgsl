// lesson_03 exercises answered HALF RIGHT (tests/half_right/lesson_03.rs):
// each function has the mistake its comment names, which the grader must
// fail with that likely cause.

// ANCHOR: pcf_kernel
fn exercise_pcf_kernel(s: vec3<f32>, radius: i32, gradient: vec2<f32>) -> f32 {
    let size = f32(textureDimensions(shadow_map).x);
    let texel = 1.0 / size;
    // The texel centre up and left of s, and the fraction from it to s.
    let t = s.xy * size - 0.5;
    let base = (floor(t) + 0.5) * texel;
    let f = t - floor(t);
    var lit = 0.0;
    for (var y = -radius; y <= radius + 1; y++) {
        // The first row weighs 1 - f.y, the last f.y, the others 1.
        var wy = 1.0;
        if y == -radius { wy = 1.0 - f.y; }
        if y == radius + 1 { wy = f.y; }
        for (var x = -radius; x <= radius + 1; x++) {
            var wx = 1.0;
            if x == -radius { wx = 1.0 - f.x; }
            if x == radius + 1 { wx = f.x; }
            let c = base + vec2<f32>(f32(x), f32(y)) * texel;
            let o = c - s.xy;
            let v = textureSampleCompareLevel(shadow_map, shadow_compare, c, s.z + dot(gradient, o));
            lit += wx * wy * v;
        }
    }
    // THE MISTAKE: the sum divided by the (N + 1)² taps it has, not by
    // the N² their weights add up to.
    let n = f32(2 * radius + 2);
    return lit / (n * n);
}
// ANCHOR_END: pcf_kernel

// ANCHOR: world_disk
fn exercise_world_disk(s: vec3<f32>, world: vec3<f32>, pixel: vec2<f32>, radius_m: f32, gradient: vec2<f32>) -> f32 {
    // The radius in map units along u and along v: metres / (metres per
    // texel × texels across). Texels are not square, so neither is the disk
    // on the map; on the light's plane it is round.
    let size = f32(textureDimensions(shadow_map).x);
    let r = radius_m / (shadow_texel_extent(world) * size);
    let a = rotation_angle(pixel);
    let rot = mat2x2<f32>(cos(a), sin(a), -sin(a), cos(a));
    var lit = 0.0;
    for (var i = 0u; i < 16u; i++) {
        let o = (rot * POISSON_DISK[i]) * r;
        // THE MISTAKE: every tap compared with the receiver's own depth s.z,
        // not with its plane at the tap: the taps uphill see acne.
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z);
    }
    return lit / 16.0;
}
// ANCHOR_END: world_disk
