// lesson_02/exercise_lit.wgsl: the lit passes of the chapter's exercises.
// Compiled after bias.wgsl and the exercises' WGSL (the student's
// `slope_bias` and `grazing_bias`), which it plugs into the lesson's lookup.

// Exercise 1: the receiver moves slope_bias(cos θ) texels towards the light.
@fragment
fn fs_exercise_slope_bias(in: VertexOut) -> LitOut {
    let n = light_side_normal(in);
    let l = to_light(in.world);
    let cos_t = clamp(dot(n, l), 0.0, 1.0);
    let p = in.world + shadow_texel_size(in.world, n) * slope_bias(cos_t) * l;
    let s = shadow_coords(p);
    var lit = 1.0;
    if !outside_shadow_map(p, s) {
        lit = textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
    }
    return lit_output(in, lit);
}

// Exercise 2: compare what grazing_bias returns.
@fragment
fn fs_exercise_grazing_bias(in: VertexOut) -> LitOut {
    let s = grazing_bias(in.world, light_side_normal(in));
    var lit = 1.0;
    if !outside_shadow_map(in.world, s) {
        lit = textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z);
    }
    return lit_output(in, lit);
}
