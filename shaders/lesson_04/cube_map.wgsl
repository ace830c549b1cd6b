// lesson_04/cube_map.wgsl: cube-map shadows for point lights. Appended to
// common.wgsl (bindings, vs_scene, vs_light_depth, lit_output).

@group(2) @binding(0) var cube_map: texture_depth_cube;
@group(2) @binding(1) var cube_compare: sampler_comparison;

// The variant's lookup, fixed when the pipeline is compiled (Rust:
// lesson_04::cube_map::LitKey). Constants, not buffer fields: a branch on
// a value read from a buffer stays in the compiled shader, and a software
// rasteriser runs every side of it, masked, cube taps included (on
// lavapipe the one-tap variants paid for all 49 taps of the four lookups).
//
// What the cube stores: 0 linear distance, 1 hardware depth, 2 hardware
// depth compared with the Euclidean distance (the naive mistake), 3
// hardware depth read as a 2D array by the chapter's exercise
// (fs_lit_faces, exercise_cube_texel in exercises.wgsl).
override STORAGE: u32 = 0u;
// A renderer's lookup instead (peers.wgsl): 0 none, 1 LearnOpenGL, 2 Bevy.
override PEER: u32 = 0u;
// 3D PCF (params.pcf texels) instead of one tap.
override FILTERED: bool = false;
// Receivers past the far plane compared at 1.0, so they read lit (the
// lesson's, Bevy's); false: behind the cleared cube, shadowed
// (no_range_clamp_1024, LearnOpenGL's). A variant's choice, not the scene's.
override CLAMP_RANGE: bool = true;

// Rust: lesson_04::cube_map::CubeParams.
struct CubeParams {
    near: f32,
    // 2 / face resolution: a texel's width 1 m from the light.
    texel_at_1m: f32,
    // The faces' far plane (m); 0: the light's range (a renderer's own
    // far plane otherwise).
    far: f32,
    // A constant bias (world units), a bias in texels, a slope bias in texels
    // (times tan θ), and the 3D PCF radius in texels (0: one tap).
    bias_world: f32,
    bias_texels: f32,
    slope: f32,
    pcf: f32,
    // A renderer's lookup's scale (LearnOpenGL: disk per (1 + view
    // distance / range); Bevy: normal bias per metre of major-axis distance).
    peer_scale: f32,
};
@group(2) @binding(2) var<storage, read> params: CubeParams;
const STORAGE_LINEAR: u32 = 0u;
const STORAGE_DEPTH_EUCLID: u32 = 2u;

// ANCHOR: linear_distance
// The linear-distance shadow pass: distance / range (the face uniform's
// range is the faces' far plane), written as the
// fragment's depth into the Depth32Float cube (R32Float is no render
// target on GL; a depth texture is, on every backend). The price: a fragment
// stage the hardware-depth pass does not have, and no early depth test
// (the shader decides the depth, so the test runs after it: late-Z).
struct LinearOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
};

@vertex
fn vs_cube_linear(v: VertexIn) -> LinearOut {
    var out: LinearOut;
    let world = object.model * vec4<f32>(v.position, 1.0);
    out.world = world.xyz;
    out.clip = light.view_proj * world;
    return out;
}

@fragment
fn fs_cube_linear(in: LinearOut) -> @builtin(frag_depth) f32 {
    return distance(in.world, light.position_or_dir.xyz) / light.color_range.w;
}
// ANCHOR_END: linear_distance

// The counting copy of fs_cube_linear (lesson_04::costs): the same depth,
// and 1.0 added into the tally target per fragment that passes the test.
struct LinearTallyOut {
    @builtin(frag_depth) depth: f32,
    @location(0) one: vec4<f32>,
};

@fragment
fn fs_cube_linear_tally(in: LinearOut) -> LinearTallyOut {
    let depth = distance(in.world, light.position_or_dir.xyz) / light.color_range.w;
    return LinearTallyOut(depth, vec4<f32>(1.0));
}

// The faces' far plane: the light's range, or a renderer's own.
fn cube_far() -> f32 {
    return select(light.color_range.w, params.far, params.far > 0.0);
}

// ANCHOR: receiver_depth
// What the cube would store for a point at distance `d` along `v` (v: from
// the light to the receiver), in the storage's units.
fn receiver_depth(v: vec3<f32>, d: f32) -> f32 {
    let far = cube_far();
    let near = params.near;
    var z = d / far;
    if STORAGE != STORAGE_LINEAR {
        // The face that holds v looks along v's major axis; its depth is a
        // function of the distance along that axis, not of |v|.
        let a = abs(v);
        var m = max(a.x, max(a.y, a.z)) * d / length(v);
        if STORAGE == STORAGE_DEPTH_EUCLID {
            m = d; // naive: right only where v is the face's axis
        }
        z = far * (m - near) / ((far - near) * m);
    }
    if CLAMP_RANGE {
        // Past the far plane (the range) the cube holds 1.0 (cleared, or
        // clamped): compare at 1.0, and "nothing in range" reads lit.
        z = min(z, 1.0);
    }
    return z;
}
// ANCHOR_END: receiver_depth

// 3D PCF: the 20 directions to a cube's corners and edge midpoints.
fn pcf_offset(i: i32) -> vec3<f32> {
    var o = array<vec3<f32>, 20>(
        vec3<f32>(1.0, 1.0, 1.0), vec3<f32>(1.0, -1.0, 1.0), vec3<f32>(-1.0, -1.0, 1.0), vec3<f32>(-1.0, 1.0, 1.0),
        vec3<f32>(1.0, 1.0, -1.0), vec3<f32>(1.0, -1.0, -1.0), vec3<f32>(-1.0, -1.0, -1.0), vec3<f32>(-1.0, 1.0, -1.0),
        vec3<f32>(1.0, 1.0, 0.0), vec3<f32>(1.0, -1.0, 0.0), vec3<f32>(-1.0, -1.0, 0.0), vec3<f32>(-1.0, 1.0, 0.0),
        vec3<f32>(1.0, 0.0, 1.0), vec3<f32>(-1.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, -1.0), vec3<f32>(-1.0, 0.0, -1.0),
        vec3<f32>(0.0, 1.0, 1.0), vec3<f32>(0.0, -1.0, 1.0), vec3<f32>(0.0, -1.0, -1.0), vec3<f32>(0.0, 1.0, -1.0),
    );
    return o[i];
}

// ANCHOR: visibility
// 1 = lit, 0 = in shadow. `n`: the geometric normal, facing the camera.
fn visibility(world: vec3<f32>, n: vec3<f32>) -> f32 {
    let v = world - light.position_or_dir.xyz;
    let d = length(v);
    let cos_t = dot(n, -v / d);
    if cos_t <= 0.0 {
        return 0.0; // facing away: the surface shadows itself
    }
    // A texel is 2 / N wide 1 m from the light, and d times that at d:
    // the bias grows with distance, like the texels.
    let texel = params.texel_at_1m * d;
    let tan_t = min(sqrt(max(1.0 - cos_t * cos_t, 0.0)) / cos_t, 10.0);
    let bias = params.bias_world + texel * (params.bias_texels + params.slope * tan_t);
    let z = receiver_depth(v, d - bias);
    if !FILTERED {
        // The direction picks the face and the texel: no face logic here.
        return textureSampleCompareLevel(cube_map, cube_compare, v, z);
    }
    var lit = 0.0;
    for (var i = 0; i < 20; i++) {
        let dir = v + pcf_offset(i) * (params.pcf * texel);
        lit += textureSampleCompareLevel(cube_map, cube_compare, dir, z);
    }
    return lit / 20.0;
}
// ANCHOR_END: visibility

@fragment
fn fs_lit(in: VertexOut) -> LitOut {
    // The flat (geometric) normal, like the reference's: N·L ≤ 0 is shadow.
    var n = normalize(cross(dpdx(in.world), dpdy(in.world)));
    if dot(n, camera.eye.xyz - in.world) < 0.0 {
        n = -n;
    }
    if PEER != 0u && dot(n, light.position_or_dir.xyz - in.world) <= 0.0 {
        // Facing away, as in visibility: the renderers' diffuse term is
        // max(N·L, 0), so the surface is dark whatever their shadow test.
        return lit_output(in, 0.0);
    }
    if PEER == 1u {
        return lit_output(in, learnopengl_disk(in.world));
    }
    if PEER == 2u {
        // Bevy offsets along the mesh's interpolated normal, on the side
        // the camera sees (its single-sided material culls the other).
        var m = normalize(in.normal);
        if dot(m, camera.eye.xyz - in.world) < 0.0 {
            m = -m;
        }
        return lit_output(in, bevy_point(in.world, m));
    }
    return lit_output(in, visibility(in.world, n));
}

// The chapter's exercise (variant exercise_cube_faces): the same one-tap
// test as `visibility`, on hardware depth, but with no cube bound. The six
// faces are layers of a 2D array, and exercise_cube_texel (exercises.wgsl)
// picks the layer and the texel that the cube lookup would.
@group(2) @binding(3) var cube_faces: texture_depth_2d_array;

@fragment
fn fs_lit_faces(in: VertexOut) -> LitOut {
    var n = normalize(cross(dpdx(in.world), dpdy(in.world)));
    if dot(n, camera.eye.xyz - in.world) < 0.0 {
        n = -n;
    }
    let v = in.world - light.position_or_dir.xyz;
    let d = length(v);
    let cos_t = dot(n, -v / d);
    if cos_t <= 0.0 {
        return lit_output(in, 0.0);
    }
    let texel = params.texel_at_1m * d;
    let tan_t = min(sqrt(max(1.0 - cos_t * cos_t, 0.0)) / cos_t, 10.0);
    let bias = params.bias_world + texel * (params.bias_texels + params.slope * tan_t);
    let z = receiver_depth(v, d - bias);
    let st = exercise_cube_texel(v);
    let layer = clamp(i32(round(st.z)), 0, 5);
    return lit_output(in, textureSampleCompareLevel(cube_faces, cube_compare, st.xy, layer, z));
}
