// lesson_10 exercises answered with the chapter's own code (grade
// --check-copies must see every one fail). Appended to soft.wgsl in place
// of shaders/lesson_10/exercises.wgsl. The chapter prints the footprint's
// stretch off the axis in words only; its code is the round disk.

// ANCHOR: off_axis_radius
// Copies the radius of the chapter's `pcss` listing, as the chapter derives
// it in "The penumbra's width" (an angle R (d_r − d_b) / (d_r d_b) times
// map units per radian; a sun's (d_r − d_b) tan α times map units per
// world unit): a disk square to the axis, the same off the axis as on it.
fn exercise_off_axis_radius(s: vec3<f32>, d_r: f32, d_b: f32) -> vec2<f32> {
    let h = max(d_r - d_b, 0.0);
    if soft.perspective == 0u {
        return h * soft.size * soft.uv_per;
    }
    return soft.size * h / (d_r * max(d_b, 1e-6)) * soft.uv_per;
}
// ANCHOR_END: off_axis_radius

// ANCHOR: footprint
// Copies the chapter's `disk_pcf` listing's taps, vogel(i, taps, rot) *
// radius, with the radius of its `pcss` listing (as above): a round disk
// as a matrix.
fn exercise_footprint(s: vec3<f32>, d_r: f32, d_b: f32) -> mat2x2<f32> {
    let h = max(d_r - d_b, 0.0);
    var radius = h * soft.size * soft.uv_per;
    if soft.perspective == 1u {
        radius = soft.size * h / (d_r * max(d_b, 1e-6)) * soft.uv_per;
    }
    return mat2x2<f32>(radius.x, 0.0, 0.0, radius.y);
}
// ANCHOR_END: footprint

// ==== calls the lesson's own functions ====
// The second pass of grade --check-copies (WORKBOOK_CHAPTER_COPY=calls):
// each exercise answered with a call of the lesson's own function, as the
// chapter's `pcss` listing calls it. The lesson has no function for the
// stretch: its footprint is filter_radius's round disk.

// Calls soft.wgsl's filter_radius, as the chapter's `pcss` listing does
// for both disks.
fn exercise_off_axis_radius(s: vec3<f32>, d_r: f32, d_b: f32) -> vec2<f32> {
    return filter_radius(d_r, d_b);
}

// Calls soft.wgsl's filter_radius, as the chapter's `pcss` listing does,
// its round disk as a matrix (the `disk_pcf` listing's taps).
fn exercise_footprint(s: vec3<f32>, d_r: f32, d_b: f32) -> mat2x2<f32> {
    let r = filter_radius(d_r, d_b);
    return mat2x2<f32>(r.x, 0.0, 0.0, r.y);
}
