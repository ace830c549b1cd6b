// lesson_01 exercise 2 answered with the chapter's own code (grade
// --check-copies must see it fail). Compiled in place of
// shaders/lesson_01/exercises.wgsl.

// ANCHOR: depth_compare
// Copies the chapter's `depth_compare` listing (depth_map.wgsl's `visibility`).
fn depth_compare(world: vec3<f32>) -> f32 {
    let s = shadow_coords(world);
    if outside_shadow_map(world, s) {
        return 1.0;
    }
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
}
// ANCHOR_END: depth_compare

// ==== calls the lesson's own functions ====
// The second pass of grade --check-copies (WORKBOOK_CHAPTER_COPY=calls):
// each exercise answered with a call of the lesson's own function.

// Calls the chapter's `depth_compare` listing, depth_map.wgsl's
// `visibility`: the exercise's module leaves depth_map.wgsl out, so this
// does not compile, and the exercise fails with the compiler's line.
fn depth_compare(world: vec3<f32>) -> f32 {
    return visibility(world);
}
