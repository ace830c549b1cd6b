// lesson_07/depth_probe.wgsl: the depth-precision study's probe quads, one
// pixel per (distance, gap), drawn with the real depth test.
struct Probe { rows: vec4<f32>, size: vec4<f32> };
@group(0) @binding(0) var<uniform> probe: Probe;
struct Out { @builtin(position) clip: vec4<f32>, @location(0) value: f32 };

// One pixel-sized quad per instance: (column, row, view distance d, value).
@vertex
fn vs_probe(@builtin(vertex_index) vi: u32, @location(0) inst: vec4<f32>) -> Out {
    let px = inst.xy + vec2<f32>(f32(vi & 1u), f32(vi >> 1u));
    let ndc = vec2<f32>(px.x / probe.size.x * 2.0 - 1.0, 1.0 - px.y / probe.size.y * 2.0);
    // The projection's z and w rows, as a vertex shader applies them.
    let z = probe.rows.x * -inst.z + probe.rows.y;
    let w = probe.rows.z * -inst.z + probe.rows.w;
    var out: Out;
    out.clip = vec4<f32>(ndc * w, z, w);
    out.value = inst.w;
    return out;
}

@fragment
fn fs_probe(in: Out) -> @location(0) vec4<f32> {
    return vec4<f32>(in.value, 0.0, 0.0, 1.0);
}
