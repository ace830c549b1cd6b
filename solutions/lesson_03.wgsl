// lesson_03 exercises, reference solutions (solutions/lesson_03.rs). The
// same functions as shaders/lesson_03/exercises.wgsl.

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
    let n = f32(2 * radius + 1);
    return lit / (n * n);
}
// ANCHOR_END: pcf_kernel

// ANCHOR: rotated_poisson
fn exercise_rotated_poisson(s: vec3<f32>, pixel: vec2<f32>, radius: f32, gradient: vec2<f32>) -> f32 {
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let phi = 6.2831853 * fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715))));
    var lit = 0.0;
    for (var i = 0u; i < 16u; i++) {
        let r = radius * sqrt((f32(i) + 0.5) / 16.0);
        let a = f32(i) * 2.39996323 + phi;
        let o = vec2<f32>(cos(a), sin(a)) * r * texel;
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
    }
    return lit / 16.0;
}
// ANCHOR_END: rotated_poisson
