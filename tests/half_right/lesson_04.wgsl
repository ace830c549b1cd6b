// lesson_04 exercises answered HALF RIGHT (tests/half_right/lesson_04.rs):
// each function has the mistake its comment names, which the grader must
// fail with that likely cause.

// ANCHOR: cube_texel
// The major axis picks the face (ties go to z, then y, like the sampler's
// usual order); each face's (sc, tc) are the two other components, signed
// so that s runs along its column axis and t down its rows (CUBE_FACES:
// the side faces have up −Y, +Y has +Z, −Y has −Z).
fn exercise_cube_texel(v: vec3<f32>) -> vec3<f32> {
    let a = abs(v);
    var sc: f32;
    var tc: f32;
    var m: f32;
    var layer: f32;
    if a.z >= a.x && a.z >= a.y {
        m = a.z;
        if v.z >= 0.0 {
            sc = v.x;
            layer = 4.0;
        } else {
            sc = -v.x;
            layer = 5.0;
        }
        tc = -v.y;
    } else if a.y >= a.x {
        m = a.y;
        sc = v.x;
        if v.y >= 0.0 {
            tc = v.z;
            layer = 2.0;
        } else {
            // THE MISTAKE: -Y's rows taken along +Z like +Y's.
            tc = v.z;
            layer = 3.0;
        }
    } else {
        m = a.x;
        if v.x >= 0.0 {
            sc = -v.z;
            layer = 0.0;
        } else {
            sc = v.z;
            layer = 1.0;
        }
        tc = -v.y;
    }
    return vec3<f32>(0.5 * (sc / m + 1.0), 0.5 * (tc / m + 1.0), layer);
}
// ANCHOR_END: cube_texel
