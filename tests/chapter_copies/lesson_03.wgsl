// lesson_03 exercises answered with the chapter's own code (grade
// --check-copies must see every one fail). Appended to pcf.wgsl in place of
// shaders/lesson_03/exercises.wgsl.

// ANCHOR: pcf_kernel
// Copies the chapter's `pcf_grid` listing (N = 2 radius + 1).
fn exercise_pcf_kernel(s: vec3<f32>, radius: i32, gradient: vec2<f32>) -> f32 {
    return pcf_grid(s, 2 * radius + 1, gradient);
}
// ANCHOR_END: pcf_kernel

// ANCHOR: world_disk
// Copies the chapter's `poisson` listing (the rotated Poisson disk) with
// poisson_16's radius of 2.5 texels.
fn exercise_world_disk(s: vec3<f32>, world: vec3<f32>, pixel: vec2<f32>, radius_m: f32, gradient: vec2<f32>) -> f32 {
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let a = rotation_angle(pixel);
    let rot = mat2x2<f32>(cos(a), sin(a), -sin(a), cos(a));
    var lit = 0.0;
    for (var i = 0u; i < 16u; i++) {
        let o = rot * POISSON_DISK[i] * 2.5 * texel;
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
    }
    return lit / 16.0;
}
// ANCHOR_END: world_disk

// ==== calls the lesson's own functions ====
// The second pass of grade --check-copies (WORKBOOK_CHAPTER_COPY=calls):
// each exercise answered with a call of the lesson's own function.

// Calls the chapter's `pcf_grid` listing (N = 2 radius + 1), as the
// first pass does.
fn exercise_pcf_kernel(s: vec3<f32>, radius: i32, gradient: vec2<f32>) -> f32 {
    return pcf_grid(s, 2 * radius + 1, gradient);
}

// Calls the chapter's `poisson` listing, `pcf_poisson`: the rotated
// disk of poisson_16's radius, in texels.
fn exercise_world_disk(s: vec3<f32>, world: vec3<f32>, pixel: vec2<f32>, radius_m: f32, gradient: vec2<f32>) -> f32 {
    return pcf_poisson(s, pixel, gradient);
}
