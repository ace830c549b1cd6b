// common.wgsl: what every lesson's shaders share. A lesson's WGSL file is
// appended to this one (WGSL has no #include), so it can use these bindings,
// `vs_scene` and `direct_light`.

struct Camera {
    view_proj: mat4x4<f32>,
    eye: vec4<f32>,
    ambient: vec4<f32>,
};

struct Light {
    view_proj: mat4x4<f32>,
    // xyz: position (point, spot) or the direction light travels (directional)
    // w: 0 directional, 1 point, 2 spot
    position_or_dir: vec4<f32>,
    // xyz: spot direction, w: cos(half cone angle)
    spot: vec4<f32>,
    // rgb: colour, w: range (0 for directional)
    color_range: vec4<f32>,
};

struct Object {
    model: mat4x4<f32>,
    normal_matrix: mat4x4<f32>,
    color: vec4<f32>,
    // x: object index + 1 (0 means "no geometry" in the id target)
    id: vec4<u32>,
};

// Read-only storage rather than uniform buffers: see SCENE_BUFFER_USAGE in
// common/src/render.rs (a lavapipe leak). The data are the same.
@group(0) @binding(0) var<storage, read> camera: Camera;
@group(0) @binding(1) var<storage, read> light: Light;
@group(1) @binding(0) var<storage, read> object: Object;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
};

struct VertexOut {
    // invariant: the lit pass must reproduce the base pass's depth exactly.
    @invariant @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
};

@vertex
fn vs_scene(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    let world = object.model * vec4<f32>(v.position, 1.0);
    out.world = world.xyz;
    out.normal = (object.normal_matrix * vec4<f32>(v.normal, 0.0)).xyz;
    out.clip = camera.view_proj * world;
    return out;
}

struct BaseOut {
    @location(0) color: vec4<f32>,
    @location(1) id: u32,
};

// The base pass: depth, the unshadowed ambient term, and which object covers
// each pixel (the metrics compare surfaces by this id).
@fragment
fn fs_base(in: VertexOut) -> BaseOut {
    var out: BaseOut;
    out.color = vec4<f32>(camera.ambient.rgb * object.color.rgb, 1.0);
    out.id = object.id.x;
    return out;
}

// ANCHOR: vs_light_depth
// A shadow pass's vertex shader: the object seen from the light.
@vertex
fn vs_light_depth(v: VertexIn) -> @builtin(position) vec4<f32> {
    return light.view_proj * object.model * vec4<f32>(v.position, 1.0);
}
// ANCHOR_END: vs_light_depth

// Unit vector from a surface point towards the light.
fn to_light(p: vec3<f32>) -> vec3<f32> {
    if light.position_or_dir.w == 0.0 {
        return -normalize(light.position_or_dir.xyz);
    }
    return normalize(light.position_or_dir.xyz - p);
}

// The normal on the side the camera sees (open meshes are two-sided).
fn facing_normal(in: VertexOut) -> vec3<f32> {
    let n = normalize(in.normal);
    if dot(n, camera.eye.xyz - in.world) < 0.0 {
        return -n;
    }
    return n;
}

// Unshadowed direct light: Lambert, range falloff, spot cone.
fn direct_light(p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let l = to_light(p);
    var k = max(dot(n, l), 0.0);
    let kind = light.position_or_dir.w;
    if kind > 0.5 {
        let d = distance(light.position_or_dir.xyz, p);
        let range = light.color_range.w;
        let f = clamp(1.0 - d / range, 0.0, 1.0);
        k = k * f * f;
    }
    if kind > 1.5 && dot(-l, normalize(light.spot.xyz)) < light.spot.w {
        k = 0.0;
    }
    return light.color_range.rgb * k;
}

struct LitOut {
    @location(0) color: vec4<f32>,
    @location(1) visibility: f32,
};

// ANCHOR: lit_output
// What every lit pass returns: the light's contribution, added onto the
// frame, and the visibility the technique computed, for the metrics.
fn lit_output(in: VertexOut, visibility: f32) -> LitOut {
    var out: LitOut;
    let n = facing_normal(in);
    out.color = vec4<f32>(direct_light(in.world, n) * object.color.rgb * visibility, 1.0);
    out.visibility = visibility;
    return out;
}
// ANCHOR_END: lit_output
