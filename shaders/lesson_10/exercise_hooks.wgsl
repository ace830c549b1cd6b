// lesson_10/exercise_hooks.wgsl: how pcss (soft.wgsl) meets the chapter's
// exercises. Each module takes one part of this file
// (lessons/lesson_10/exercise_shaders.rs).

// ANCHOR: lesson
// The lesson's own module: no student code; the exercises' names are the
// lesson's functions (pcss runs them only for the exercise variants, which
// have modules of their own).
fn exercise_blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    return blocker_search(s, radius, angle, gradient);
}

fn exercise_filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    return filter_radius(d_r, d_b);
}
// ANCHOR_END: lesson

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
