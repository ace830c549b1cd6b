// lesson_10 exercises, solved (shaders/lesson_10/exercises.wgsl is the
// starter). Each exercise's module leaves soft.wgsl's own function out
// (lessons/lesson_10/exercise_shaders.rs): these implement it.

// Exercise 1: the blocker search. The taps on the Vogel disk, a blocker
// where the stored depth is in front of the receiver's plane at the tap
// (z < s.z + dot(gradient, o)), the mean of light_distance(z) over the
// blockers only.
fn exercise_blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    let size = vec2<f32>(textureDimensions(shadow_depths));
    var sum = 0.0;
    var count = 0u;
    for (var i = 0u; i < soft.search_taps; i++) {
        let o = vogel(i, soft.search_taps, angle) * radius;
        let t = clamp(vec2<i32>(floor((s.xy + o) * size)), vec2<i32>(0), vec2<i32>(size) - 1);
        let z = textureLoad(shadow_depths, t, 0).r;
        if z < s.z + dot(gradient, o) {
            sum += light_distance(z);
            count += 1u;
        }
    }
    return Blockers(sum / max(f32(count), 1.0), count);
}

// Exercise 2: the penumbra estimate. The blockers' footprint h tan α (a
// cone, in world units times map units per world unit), or R h / (d_r d_b)
// (a spot's disk, an angle times map units per radian), h = d_r − d_b.
fn exercise_filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    let h = max(d_r - d_b, 0.0);
    if soft.perspective == 0u {
        return h * soft.size * soft.uv_per;
    }
    return soft.size * h / (d_r * max(d_b, 1e-6)) * soft.uv_per;
}
