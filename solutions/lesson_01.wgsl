// lesson_01 exercises: the reference solution (the starter is
// shaders/lesson_01/exercises.wgsl, with the same function).

// ANCHOR: depth_compare
fn depth_compare(world: vec3<f32>) -> f32 {
    let clip = light.view_proj * vec4<f32>(world, 1.0);
    if clip.w <= 0.0 {
        return 1.0; // behind the light
    }
    let ndc = clip.xyz / clip.w;
    // NDC y points up, texture v down; depth is already in [0, 1].
    let uv = vec2<f32>(ndc.x * 0.5 + 0.5, -ndc.y * 0.5 + 0.5);
    if any(uv < vec2<f32>(0.0)) || any(uv >= vec2<f32>(1.0)) || ndc.z > 1.0 {
        return 1.0; // outside the map: nothing was rendered there
    }
    // 1 where ndc.z <= the stored depth: lit.
    return textureSampleCompareLevel(shadow_map, shadow_compare, uv, ndc.z);
}
// ANCHOR_END: depth_compare
