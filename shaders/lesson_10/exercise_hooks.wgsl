// lesson_10/exercise_hooks.wgsl: how the chapter's exercises meet PCSS.
// An exercise's module leaves soft.wgsl's pcss out and takes the part of
// this file named `shaped_pcss`, whose pcss is the lesson's three steps
// with each disk's taps placed by footprint_shape, and the exercise's own
// part, whose footprint_shape is the student's function
// (lessons/lesson_10/exercise_shaders.rs). The lesson's module takes none.

// ANCHOR: shaped_pcss
// The lesson's pcss, its two disks given as a matrix from the unit disk
// to map units (the lesson's round disk of radius r is diag(r.x, r.y)):
// tap i of a disk `shape` lies at s.xy + shape * vogel(i, n, rot), rot the
// disk's rotation at this pixel.
fn pcss(s: vec3<f32>, angle: f32, gradient: vec2<f32>) -> f32 {
    let d_r = light_distance(s.z);
    let search = footprint_shape(s, d_r, min(soft.nearest_caster, d_r));
    let blockers = shaped_blocker_search(s, search, disk_rotation(angle), gradient);
    if blockers.count == 0u {
        return 1.0;
    }
    let shape = footprint_shape(s, d_r, blockers.distance);
    return shaped_disk_pcf(s, shape, FILTER_TAPS, disk_rotation(angle + 1.0), gradient);
}

// soft.wgsl's blocker_search, its taps placed by `shape`.
fn shaped_blocker_search(s: vec3<f32>, shape: mat2x2<f32>, rot: mat2x2<f32>, gradient: vec2<f32>) -> Blockers {
    let size = vec2<f32>(textureDimensions(shadow_depths));
    var sum = 0.0;
    var count = 0u;
    for (var i = 0u; i < SEARCH_TAPS; i++) {
        let o = shape * vogel(i, SEARCH_TAPS, rot);
        let texel = clamp(vec2<i32>(floor((s.xy + o) * size)), vec2<i32>(0), vec2<i32>(size) - 1);
        let depth = textureLoad(shadow_depths, texel, 0).r;
        if depth < s.z + dot(gradient, o) {
            sum += light_distance(depth);
            count += 1u;
        }
    }
    return Blockers(sum / max(f32(count), 1.0), count);
}

// soft.wgsl's disk_pcf, its taps placed by `shape`.
fn shaped_disk_pcf(s: vec3<f32>, shape: mat2x2<f32>, taps: u32, rot: mat2x2<f32>, gradient: vec2<f32>) -> f32 {
    var lit = 0.0;
    for (var i = 0u; i < taps; i++) {
        let o = shape * vogel(i, taps, rot);
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
    }
    return lit / f32(taps);
}
// ANCHOR_END: shaped_pcss

// ANCHOR: off_axis_radius
// exercise_off_axis_radius's module: a round disk of the student's radius.
fn footprint_shape(s: vec3<f32>, d_r: f32, d_b: f32) -> mat2x2<f32> {
    let r = exercise_off_axis_radius(s, d_r, d_b);
    return mat2x2<f32>(r.x, 0.0, 0.0, r.y);
}
// ANCHOR_END: off_axis_radius

// ANCHOR: footprint
// exercise_elliptic_footprint's module: the student's matrix.
fn footprint_shape(s: vec3<f32>, d_r: f32, d_b: f32) -> mat2x2<f32> {
    return exercise_footprint(s, d_r, d_b);
}
// ANCHOR_END: footprint
