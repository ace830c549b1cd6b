// lesson_10 exercises, solved (shaders/lesson_10/exercises.wgsl is the
// starter). The emitter faces the receiver; carried onto the light's
// plane along the rays to the receiver, it is an ellipse 1/cos β longer
// away from the axis, β the receiver's angle off the axis, and so is its
// footprint on the blockers' plane. A perspective map is linear on that
// plane: its offset from the map's centre is tan β times soft.uv_per.

// 1/cos β = sqrt(1 + tan² β) at the receiver (1 for a sun, whose cone of
// directions is the same everywhere), and the direction away from the axis
// in map units (0 on the axis).
fn off_axis(s: vec3<f32>) -> vec3<f32> {
    if soft.perspective == 0u {
        return vec3<f32>(1.0, 0.0, 0.0);
    }
    let tan_beta = (s.xy - 0.5) / soft.uv_per;
    let t = length(tan_beta);
    let away = select(vec2<f32>(0.0), tan_beta / t, t > 1e-6);
    return vec3<f32>(sqrt(1.0 + t * t), away);
}

// Exercise 1: the round disk that holds the ellipse: the lesson's radius,
// 1/cos β longer.
fn exercise_off_axis_radius(s: vec3<f32>, d_r: f32, d_b: f32) -> vec2<f32> {
    return filter_radius(d_r, d_b) * off_axis(s).x;
}

// Exercise 2: the ellipse: the lesson's round disk, then stretched by
// 1/cos β along the direction away from the axis only,
// I + (1/cos β − 1) a aᵀ.
fn exercise_footprint(s: vec3<f32>, d_r: f32, d_b: f32) -> mat2x2<f32> {
    let r = filter_radius(d_r, d_b);
    let o = off_axis(s);
    let a = o.yz;
    let stretch = mat2x2<f32>(1.0, 0.0, 0.0, 1.0) + (o.x - 1.0) * mat2x2<f32>(a * a.x, a * a.y);
    return stretch * mat2x2<f32>(r.x, 0.0, 0.0, r.y);
}
