// lesson_01/exercise_lit.wgsl: the lit pass of exercise_depth_compare, the
// student's `depth_compare` (exercises.wgsl) as the visibility.

@fragment
fn fs_exercise_depth_compare(in: VertexOut) -> LitOut {
    return lit_output(in, depth_compare(in.world));
}
