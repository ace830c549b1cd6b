// lesson_04 exercise answered with the nearest code chapter 04 prints
// (tests/chapter_copies/lesson_04.rs, for grade --check-copies).

fn exercise_cube_depth(v: vec3<f32>, d: f32, near: f32, far: f32) -> f32 {
    // Chapter 04's listing `cube_map.wgsl:receiver_depth`, pasted.
    let a = abs(v);
    let m = max(a.x, max(a.y, a.z)) * d / length(v);
    return far * (m - near) / ((far - near) * m);
}
