// lesson_03 exercises, reference solutions (solutions/lesson_03.rs). The
// same functions as shaders/lesson_03/exercises.wgsl.

// ANCHOR: pcf_kernel
fn exercise_pcf_kernel(s: vec3<f32>, radius: i32, gradient: vec2<f32>) -> f32 {
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    var lit = 0.0;
    for (var y = -radius; y <= radius; y++) {
        for (var x = -radius; x <= radius; x++) {
            let o = vec2<f32>(f32(x), f32(y)) * texel;
            lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
        }
    }
    let n = 2 * radius + 1;
    return lit / f32(n * n);
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
