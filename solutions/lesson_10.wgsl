// lesson_10 exercises, solved (shaders/lesson_10/exercises.wgsl is the
// starter). Appended to soft.wgsl.

// Exercise 1: the blocker search.
fn exercise_blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    let size = vec2<f32>(textureDimensions(shadow_depths));
    var sum = 0.0;
    var count = 0u;
    for (var i = 0u; i < soft.search_taps; i++) {
        let o = vogel(i, soft.search_taps, angle) * radius;
        let t = clamp(vec2<i32>(floor((s.xy + o) * size)), vec2<i32>(0), vec2<i32>(size) - 1);
        let z = textureLoad(shadow_depths, t, 0).r;
        // In front of the receiver's plane at the tap: a blocker.
        if z < s.z + dot(gradient, o) {
            sum += light_distance(z);
            count += 1u;
        }
    }
    return Blockers(sum / max(f32(count), 1.0), count);
}

// Exercise 2: the penumbra estimate, by similar triangles.
fn exercise_filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    let h = max(d_r - d_b, 0.0);
    if soft.perspective == 0u {
        // A cone of half-angle α: the blockers' footprint is h tan α wide.
        return h * soft.size * soft.uv_per;
    }
    // A disk of radius R: R h / d_r at distance d_b, an angle of R h / (d_r d_b).
    return soft.size * h / (d_r * max(d_b, 1e-6)) * soft.uv_per;
}
