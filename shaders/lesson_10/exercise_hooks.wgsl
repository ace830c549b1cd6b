// lesson_10/exercise_hooks.wgsl: how pcss (soft.wgsl) meets the chapter's
// exercises. pcss calls blocker_search and filter_radius; an exercise's
// module leaves the lesson's one out of soft.wgsl and takes its part of
// this file, which gives that name to the student's function
// (lessons/lesson_10/exercise_shaders.rs). The lesson's module takes none.

// ANCHOR: blocker_search
// exercise_blocker_search's module: soft.wgsl without the lesson's
// blocker_search, whose name is the student's function here. An exercise
// that calls blocker_search calls itself, which WGSL refuses.
fn blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    return exercise_blocker_search(s, radius, angle, gradient);
}
// ANCHOR_END: blocker_search

// ANCHOR: penumbra
// exercise_penumbra's module: soft.wgsl without the lesson's filter_radius,
// whose name is the student's function here (pcss's search radius uses it
// too). An exercise that calls filter_radius calls itself, which WGSL
// refuses.
fn filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    return exercise_filter_radius(d_r, d_b);
}
// ANCHOR_END: penumbra
