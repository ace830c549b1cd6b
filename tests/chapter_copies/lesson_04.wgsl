// lesson_04/exercises.wgsl: the chapter's shader exercise, starter code.
// Appended to cube_map.wgsl; the lit pass calls it for the variant
// `exercise_cube_depth` only. Grade with
// `cargo run --release --bin grade -- lesson_04`.

// ANCHOR: cube_depth
// Exercise 2: the depth the hardware-depth cube stores for a point at
// distance `d` from the light along the direction `v` (v: from the light to
// the point, any length). The face that holds v looks along v's major axis,
// so its depth is the perspective depth of the distance along that axis,
// m = max(|v.x|, |v.y|, |v.z|) · d / |v|:
// depth = far · (m − near) / ((far − near) · m), in [0, 1] from near to far.
fn exercise_cube_depth(v: vec3<f32>, d: f32, near: f32, far: f32) -> f32 {
    // Starter: the linear distance, what the other storage keeps. Against
    // hardware depth it is far too small: nothing reads as shadowed.
    return d / far;
}
// ANCHOR_END: cube_depth
