// lesson_10 exercises answered with the chapter's own code (grade
// --check-copies must see every one fail). Appended to soft.wgsl in place
// of shaders/lesson_10/exercises.wgsl.

// ANCHOR: blocker_search
// Copies the chapter's `disk_pcf` listing: the share of taps that see no
// blocker, not where the blockers are; called a distance.
fn exercise_blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    let lit = disk_pcf(s, radius, soft.search_taps, angle, gradient);
    let d_r = light_distance(s.z);
    if lit >= 1.0 {
        return Blockers(0.0, 0u);
    }
    return Blockers(d_r * lit, 1u);
}
// ANCHOR_END: blocker_search

// ANCHOR: filter_radius
// Copies the ratio of the chapter's `pcss` listing (Fernando's
// (d_r − d_b) / d_b, the renderers' branch) times the light's size, as the
// map's radius: the floor's penumbra, not the blockers' footprint.
fn exercise_filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    return (d_r - d_b) / max(d_b, 1e-6) * soft.size * soft.uv_per;
}
// ANCHOR_END: filter_radius

// ==== calls the lesson's own functions ====
// The second pass of grade --check-copies (WORKBOOK_CHAPTER_COPY=calls):
// each exercise answered with one call of the lesson's own function, as
// the chapter's `pcss` listing calls it. Each exercise's module leaves
// that function out and gives its name to the exercise
// (lessons/lesson_10/exercise_shaders.rs): the call is a call of itself,
// which WGSL refuses, and the exercise fails with the compiler's line.

// Calls soft.wgsl's blocker_search, as the chapter's `pcss` listing does.
fn exercise_blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    return blocker_search(s, radius, angle, gradient);
}

// Calls soft.wgsl's filter_radius, as the chapter's `pcss` listing does.
fn exercise_filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    return filter_radius(d_r, d_b);
}
