// lesson_01/exercise_lit.wgsl: the lit pass of exercise_depth_compare, the
// student's `depth_compare` (exercises.wgsl) as the visibility.

// ANCHOR: shadow_depths
// The shadow map again, as plain floats for `textureLoad` (GL cannot load
// texels through the depth binding at group 2).
@group(3) @binding(0) var shadow_depths: texture_2d<f32>;
// ANCHOR_END: shadow_depths

@fragment
fn fs_exercise_depth_compare(in: VertexOut) -> LitOut {
    return lit_output(in, depth_compare(in.world));
}
