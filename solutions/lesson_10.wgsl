// lesson_10 exercises, solved (shaders/lesson_10/exercises.wgsl is the
// starter). Appended to soft.wgsl, whose own functions are the answers:
// the chapter describes them and does not print them.

// Exercise 1: the blocker search. soft.wgsl's `blocker_search`: the taps
// on the Vogel disk, a blocker where the stored depth is in front of the
// receiver's plane at the tap (z < s.z + dot(gradient, o)), the mean of
// light_distance(z) over the blockers only.
fn exercise_blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    return blocker_search(s, radius, angle, gradient);
}

// Exercise 2: the penumbra estimate. soft.wgsl's `filter_radius`: the
// blockers' footprint h tan α (a cone, in world units times map units per
// world unit), or R h / (d_r d_b) (a spot's disk, an angle times map units
// per radian), h = d_r − d_b.
fn exercise_filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    return filter_radius(d_r, d_b);
}
