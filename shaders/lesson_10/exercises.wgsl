// lesson_10/exercises.wgsl: the chapter's exercises, the starter code.
// Appended to soft.wgsl: light_distance, filter_radius and the `soft`
// parameters are there. The variants exercise_off_axis_radius and
// exercise_elliptic_footprint run the lesson's PCSS with its search and
// filter disks from one of these functions in place of filter_radius's
// round disk (lessons/lesson_10/exercise_shaders.rs). `s` is the
// receiver's place in the map (s.xy, 0 to 1; the spot's axis is at
// (0.5, 0.5)) and its depth there (s.z); d_r and d_b are the receiver's
// and the blockers' distances from the light, along its axis.

// ANCHOR: off_axis_radius
// Exercise 1: the footprint off the axis. Return the radius, in map units
// (u, v), of the round disk that holds the whole footprint of the emitter
// on the blockers' plane at d_b, as the receiver at s sees it, for the
// reference's emitter: a disk that faces the receiver. The variant's PCSS
// searches and filters on that disk. soft.perspective is 1 for a spot
// (soft.uv_per: map units per radian at the axis), 0 for a sun.
fn exercise_off_axis_radius(s: vec3<f32>, d_r: f32, d_b: f32) -> vec2<f32> {
    // Starter: the lesson's round disk, a disk square to the axis.
    return filter_radius(d_r, d_b);
}
// ANCHOR_END: off_axis_radius

// ANCHOR: footprint
// Exercise 2: the footprint's shape. Return the matrix that takes the unit
// disk onto that footprint in map units: the variant's PCSS puts tap i of
// each disk at s.xy + m * vogel(i, n, rot). The lesson's round disk of
// radius r is mat2x2<f32>(r.x, 0.0, 0.0, r.y).
fn exercise_footprint(s: vec3<f32>, d_r: f32, d_b: f32) -> mat2x2<f32> {
    // Starter: the lesson's round disk.
    let r = filter_radius(d_r, d_b);
    return mat2x2<f32>(r.x, 0.0, 0.0, r.y);
}
// ANCHOR_END: footprint
