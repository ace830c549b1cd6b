// lesson_04/exercises.wgsl: the chapter's shader exercise, starter code.
// Appended to cube_map.wgsl; the lit pass of the variant
// `exercise_cube_faces` (fs_lit_faces) calls it, and only that variant.
// Grade with `cargo run --release --bin grade -- lesson_04`.

// ANCHOR: cube_texel
// Exercise 2: the cube lookup by hand. For the direction `v` from the light
// to the receiver (any length, not zero), return (s, t, layer): the face
// the cube sampler would read, as its layer in wgpu's order +X, −X, +Y, −Y,
// +Z, −Z (0 to 5, as a float), and the texel coordinates on that face,
// s to the right and t down the rows, each in [0, 1]. The variant binds
// the six faces as a `texture_depth_2d_array` (no cube view: a storage or
// an adapter without cube sampling reads them this way) and compares at
// (s, t) in that layer.
fn exercise_cube_texel(v: vec3<f32>) -> vec3<f32> {
    // Starter: the centre of the +X face for every direction, so every
    // receiver reads one texel.
    return vec3<f32>(0.5, 0.5, 0.0);
}
// ANCHOR_END: cube_texel
