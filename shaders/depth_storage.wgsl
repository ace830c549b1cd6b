// depth_storage.wgsl: the depth-storage probe (common/src/depth_probe.rs).
// One pixel-wide quad per instance, covering column `inst.x` of a W×1
// target, writing window depth `inst.y` exactly and the value `inst.z`.
struct Out {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) depth: f32,
    @location(1) @interpolate(flat) value: f32,
};

@vertex
fn vs_probe(@builtin(vertex_index) vi: u32, @location(0) inst: vec4<f32>) -> Out {
    let x = (inst.x + f32(vi & 1u)) / inst.w * 2.0 - 1.0;
    let y = f32(vi >> 1u) * 2.0 - 1.0;
    var out: Out;
    out.clip = vec4<f32>(x, y, 0.5, 1.0);
    out.depth = inst.y;
    out.value = inst.z;
    return out;
}

struct Frag {
    // Written, not interpolated: no plane equation, and no GL 2z − w
    // rewrite (that applies to clip z only), so the format sees this f32.
    @builtin(frag_depth) depth: f32,
    @location(0) color: vec4<f32>,
};

@fragment
fn fs_probe(in: Out) -> Frag {
    var f: Frag;
    f.depth = in.depth;
    f.color = vec4<f32>(in.value, 0.0, 0.0, 1.0);
    return f;
}
