// lesson_10 exercises answered HALF RIGHT (tests/half_right/lesson_10.rs):
// each function has the mistake its comment names, which the grader must
// fail with that likely cause.

// tan β at the receiver, as a vector away from the axis: its offset from
// the map's centre over map units per unit of tan.
fn half_right_tan_beta(s: vec3<f32>) -> vec2<f32> {
    return (s.xy - 0.5) / soft.uv_per;
}

// ANCHOR: off_axis_radius
// THE MISTAKE: the off-axis disk foreshortened, cos β, as a disk square to
// the axis looks from the receiver: the lesson's own emitter, not the
// reference's, which faces the receiver; carried onto the light's plane it
// is 1/cos β longer, not cos β shorter.
fn exercise_off_axis_radius(s: vec3<f32>, d_r: f32, d_b: f32) -> vec2<f32> {
    let r = filter_radius(d_r, d_b);
    if soft.perspective == 0u {
        return r;
    }
    let t = length(half_right_tan_beta(s));
    let cos_beta = 1.0 / sqrt(1.0 + t * t);
    return r * cos_beta;
}
// ANCHOR_END: off_axis_radius

// ANCHOR: footprint
// THE MISTAKE: exercise 1's disk as the matrix, 1/cos β longer in every
// direction: right across an edge that faces the axis, but across an edge
// that runs away from it the footprint is no wider than on the axis.
fn exercise_footprint(s: vec3<f32>, d_r: f32, d_b: f32) -> mat2x2<f32> {
    let r = filter_radius(d_r, d_b);
    var k = 1.0;
    if soft.perspective == 1u {
        let t = length(half_right_tan_beta(s));
        k = sqrt(1.0 + t * t);
    }
    return mat2x2<f32>(k * r.x, 0.0, 0.0, k * r.y);
}
// ANCHOR_END: footprint
