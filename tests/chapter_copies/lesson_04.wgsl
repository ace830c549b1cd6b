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

// ==== calls the lesson's own functions ====
// The second pass of grade --check-copies (WORKBOOK_CHAPTER_COPY=calls).
// Chapter 04's lookup is the sampler's (its `visibility` listing hands v
// to textureSampleCompare on the cube view): no function of the lesson
// returns a face and a texel, so there is none to call. The answer a call
// of the lesson's code comes nearest to: the face of v's major axis, as
// `cube_map.wgsl:receiver_depth` finds it, read at its centre.
fn exercise_cube_texel(v: vec3<f32>) -> vec3<f32> {
    let a = abs(v);
    let m = max(a.x, max(a.y, a.z));
    var layer = select(5.0, 4.0, v.z >= 0.0);
    if a.x == m {
        layer = select(1.0, 0.0, v.x >= 0.0);
    } else if a.y == m {
        layer = select(3.0, 2.0, v.y >= 0.0);
    }
    return vec3<f32>(0.5, 0.5, layer);
}
