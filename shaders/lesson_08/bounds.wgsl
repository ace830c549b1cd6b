// lesson_08/bounds.wgsl: the depth-bounds markers. Two full-screen triangles
// (fullscreen.wgsl), one at zmax and one at zmin of the light's range sphere;
// the depth test against the stored depth sets or clears stencil bit 7.

// (zmin, zmax, -, -) of the light being drawn: a dynamic offset per light.
@group(0) @binding(0) var<uniform> bounds: vec4<f32>;

@vertex
fn vs_bound_max(@builtin(vertex_index) i: u32) -> FullscreenOut {
    return fullscreen_position(i, bounds.y);
}

@vertex
fn vs_bound_min(@builtin(vertex_index) i: u32) -> FullscreenOut {
    return fullscreen_position(i, bounds.x);
}
