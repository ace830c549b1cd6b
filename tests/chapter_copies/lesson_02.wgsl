// lesson_02 exercises answered with the chapter's own code (grade
// --check-copies must see every one fail). Compiled in place of
// shaders/lesson_02/exercises.wgsl.

// ANCHOR: slope_bias
// Copies the chapter's `bias.wgsl:biased_receiver` listing with slope_shader's settings
// (Slope scaling: b0 = 0.1, k = 1, b_max = 4).
fn slope_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let l = to_light(world);
    let cos_t = clamp(dot(n, l), 0.0, 1.0);
    let tan_t = sqrt(1.0 - cos_t * cos_t) / max(cos_t, 1e-4);
    let texel = shadow_texel_size(world, n);
    let along_light = 0.1 + min(1.0 * tan_t, 4.0);
    return shadow_coords(world + texel * along_light * l);
}
// ANCHOR_END: slope_bias

// ANCHOR: grazing_bias
// Copies the chapter's `bias.wgsl:biased_receiver` listing with slope_shader's settings.
fn grazing_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let l = to_light(world);
    let cos_t = clamp(dot(n, l), 0.0, 1.0);
    let tan_t = sqrt(1.0 - cos_t * cos_t) / max(cos_t, 1e-4);
    let texel = shadow_texel_size(world, n);
    let along_light = 0.1 + min(1.0 * tan_t, 4.0);
    return shadow_coords(world + texel * along_light * l);
}
// ANCHOR_END: grazing_bias

// ==== calls the lesson's own functions ====
// The second pass of grade --check-copies (WORKBOOK_CHAPTER_COPY=calls):
// each exercise answered with a call of the lesson's own function.

// Calls the chapter's `bias.wgsl:biased_receiver` listing, its
// `biased_receiver`, with slope_shader's settings (b0 = 0.1, k = 1,
// b_max = 4).
fn slope_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let b = ShadowBias(0.0, 0.1, 1.0, 4.0, 0.0, 0.0, 0.0, 0.0);
    return shadow_coords(biased_receiver(world, n, b));
}

// Calls the chapter's `bias.wgsl:biased_receiver` listing, its
// `biased_receiver` and `depth_bias`, with normal_offset's settings.
fn grazing_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let b = ShadowBias(0.0, 0.3, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0);
    let s = shadow_coords(biased_receiver(world, n, b));
    return vec3<f32>(s.xy, s.z - depth_bias(world, n, b));
}
