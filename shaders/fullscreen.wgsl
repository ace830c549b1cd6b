// fullscreen.wgsl: one triangle that covers the whole target, for passes that
// process an image or mark every pixel (common::fullscreen). Prepended to the
// pass's own WGSL.

struct FullscreenOut {
    @builtin(position) pos: vec4<f32>,
    // (0, 0) at the top-left corner of the target, (1, 1) at the bottom-right.
    @location(0) uv: vec2<f32>,
};

// Vertex i (0, 1, 2) at window depth z: the corners (-1, 1), (3, 1), (-1, -3)
// in NDC, so the triangle's inside covers the [-1, 1]² square.
fn fullscreen_position(i: u32, z: f32) -> FullscreenOut {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var o: FullscreenOut;
    // NDC y points up, uv.y down.
    o.pos = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z, 1.0);
    o.uv = uv;
    return o;
}

@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> FullscreenOut {
    return fullscreen_position(i, 0.0);
}
