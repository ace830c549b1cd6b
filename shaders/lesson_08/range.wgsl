// lesson_08.wgsl: the lit pass of a light with a limited range.
// Appended to common.wgsl and shadow_volume.wgsl.

// ANCHOR: fs_lit_range
// The stencil test has already kept only pixels with a count of 0.
// Beyond the light's range the light adds nothing, and with depth bounds
// its volumes were never counted there: draw nothing, in every variant
// alike, so that the variants' pixels can be compared one for one.
@fragment
fn fs_lit_range(in: VertexOut) -> LitOut {
    let local = light.position_or_dir.w > 0.5;
    if local && distance(in.world, light.position_or_dir.xyz) > light.color_range.w {
        discard;
    }
    return lit_output(in, 1.0);
}
// ANCHOR_END: fs_lit_range
