// lesson_04 exercise, reference solution (solutions/lesson_04.rs). The same
// function as shaders/lesson_04/exercises.wgsl.

// ANCHOR: cube_depth
fn exercise_cube_depth(v: vec3<f32>, d: f32, near: f32, far: f32) -> f32 {
    let a = abs(v);
    let m = max(a.x, max(a.y, a.z)) * d / length(v);
    return far * (m - near) / ((far - near) * m);
}
// ANCHOR_END: cube_depth
