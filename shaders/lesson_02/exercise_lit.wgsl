// lesson_02/exercise_lit.wgsl: the lit passes of the chapter's exercises.
// Compiled after bias.wgsl and the exercises' WGSL (the student's
// `slope_bias` and `grazing_bias`), which it plugs into the lesson's lookup.

// Exercise 1: compare what slope_bias returns (called first: it takes
// screen-space derivatives, which need uniform control flow).
@fragment
fn fs_exercise_slope_bias(in: VertexOut) -> LitOut {
    let s = slope_bias(in.world, light_side_normal(in));
    var lit = 1.0;
    if !outside_shadow_map(in.world, s) {
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
