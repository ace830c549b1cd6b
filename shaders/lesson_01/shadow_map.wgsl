// shadow_map.wgsl: the shadow-map lookup that lessons 01, 02 and 03 share.
// Compiled after common.wgsl and before the lesson's own WGSL
// (`lesson_01::shadow_map::shader_module`).

// ANCHOR: shadow_map_bindings
@group(2) @binding(0) var shadow_map: texture_depth_2d;
// A comparison sampler: the hardware does `receiver <= stored` per texel.
// Nearest filtering gives one 0-or-1 answer, linear the 2×2 average (lesson 03).
@group(2) @binding(1) var shadow_compare: sampler_comparison;
// ANCHOR_END: shadow_map_bindings

// ANCHOR: shadow_coords
// World position (origin-relative, see Scene::origin) -> (u, v, depth).
fn shadow_coords(world: vec3<f32>) -> vec3<f32> {
    let clip = light.view_proj * vec4<f32>(world, 1.0);
    let ndc = clip.xyz / clip.w;
    // NDC y points up, texture v points down: flip y. Depth is already in [0, 1].
    return vec3<f32>(ndc.x * 0.5 + 0.5, -ndc.y * 0.5 + 0.5, ndc.z);
}

// Outside the light's frustum nothing was rendered: such points are lit.
fn outside_shadow_map(world: vec3<f32>, s: vec3<f32>) -> bool {
    let behind_light = (light.view_proj * vec4<f32>(world, 1.0)).w <= 0.0;
    return behind_light || any(s.xy < vec2<f32>(0.0)) || any(s.xy >= vec2<f32>(1.0)) || s.z > 1.0;
}
// ANCHOR_END: shadow_coords

// ANCHOR: texel_size
// One shadow-map texel where `world` is, in world units, per axis: x along
// the map's u axis, y along v. x_ndc = (row 0 of view_proj · p) / w and a
// texel is 2/N of NDC, so a texel is 2w / (N |row 0|) wide and 2w / (N |row 1|)
// tall. The fit to the scene makes the two differ (a grazing light sees the
// scene flat: one side is many times the other). Constant for an
// orthographic light (w = 1); it grows with the distance for a spot light.
fn shadow_texel_extent(world: vec3<f32>) -> vec2<f32> {
    let w = (light.view_proj * vec4<f32>(world, 1.0)).w;
    let m = light.view_proj;
    let row0 = vec3<f32>(m[0].x, m[1].x, m[2].x);
    let row1 = vec3<f32>(m[0].y, m[1].y, m[2].y);
    let n = f32(textureDimensions(shadow_map).x);
    return 2.0 * w / (n * vec2<f32>(length(row0), length(row1)));
}

// "A texel" for a receiver with unit normal `n`: the texel's width along the
// direction in which the receiver's depth changes fastest across the map
// (n's part across the light). Its depth varies by this width × tan θ over
// one texel, whatever the texels' aspect. Head-on there is no such
// direction, and the larger side stands in.
fn shadow_texel_size(world: vec3<f32>, n: vec3<f32>) -> f32 {
    let e = shadow_texel_extent(world);
    let l = to_light(world);
    let g = n - dot(n, l) * l;
    if length(g) < 1e-4 {
        return max(e.x, e.y);
    }
    let m = light.view_proj;
    let u = normalize(vec3<f32>(m[0].x, m[1].x, m[2].x));
    let v = normalize(vec3<f32>(m[0].y, m[1].y, m[2].y));
    let gh = normalize(g);
    return e.x * abs(dot(gh, u)) + e.y * abs(dot(gh, v));
}
// ANCHOR_END: texel_size
