// lesson_02.wgsl: the lit pass with a bias. Compiled after common.wgsl and
// shadow_map.wgsl, which hold the lookup and the bias (lesson 03 reuses them).

// This variant's receiver-side bias (all zeros for the shadow-pass fixes).
@group(3) @binding(0) var<uniform> bias: ShadowBias;

// ANCHOR: fs_lit
@fragment
fn fs_lit(in: VertexOut) -> LitOut {
    return lit_output(in, biased_visibility(in.world, light_side_normal(in), bias));
}
// ANCHOR_END: fs_lit
