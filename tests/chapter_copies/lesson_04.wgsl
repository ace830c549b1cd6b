// lesson_04 exercise answered with the nearest code chapter 04 prints
// (tests/chapter_copies/lesson_04.rs, for grade --check-copies).

fn exercise_cube_texel(v: vec3<f32>) -> vec3<f32> {
    // Chapter 04's "Six faces that match the sampler": the major axis and its
    // sign pick the face (as in `cube_map.wgsl:receiver_depth`), and the
    // texel is the one formula it prints, +X's s = (1 - v_z/m)/2, t = (1 - v_y/m)/2.
    let a = abs(v);
    let m = max(a.x, max(a.y, a.z));
    var layer = 0.0;
    if a.x == m {
        layer = select(1.0, 0.0, v.x >= 0.0);
    } else if a.y == m {
        layer = select(3.0, 2.0, v.y >= 0.0);
    } else {
        layer = select(5.0, 4.0, v.z >= 0.0);
    }
    return vec3<f32>(0.5 * (1.0 - v.z / m), 0.5 * (1.0 - v.y / m), layer);
}
