// shadow_map.wgsl: the shadow-map lookup that lessons 01, 02 and 03 share.
// Compiled after common.wgsl and before the lesson's own WGSL
// (`common::shadow_map::shader_module`).

@group(2) @binding(0) var shadow_map: texture_depth_2d;
// A comparison sampler: the hardware does `receiver <= stored` per texel.
// Nearest filtering gives one 0-or-1 answer, linear the 2×2 average (lesson 03).
@group(2) @binding(1) var shadow_compare: sampler_comparison;

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
// The width, in world units, of one shadow-map texel where `world` is.
// x_ndc = (row 0 of view_proj · p) / w and a texel is 2/N of NDC, so a texel
// is 2w / (N |row 0|) wide (and 2w / (N |row 1|) tall; the larger counts).
// That is constant for an orthographic light (w = 1) and grows with the
// distance for a spot light (w = distance along its axis).
fn shadow_texel_size(world: vec3<f32>) -> f32 {
    let w = (light.view_proj * vec4<f32>(world, 1.0)).w;
    let m = light.view_proj;
    let row0 = vec3<f32>(m[0].x, m[1].x, m[2].x);
    let row1 = vec3<f32>(m[0].y, m[1].y, m[2].y);
    let n = f32(textureDimensions(shadow_map).x);
    return 2.0 * w / (n * min(length(row0), length(row1)));
}
// ANCHOR_END: texel_size

// ANCHOR: shadow_bias
// Receiver-side bias (Rust: common::shadow_map::ShadowBias). Lengths are in
// shadow-map texels, so one setting fits any scene size and map resolution.
struct ShadowBias {
    // Subtracted from the receiver's depth, in depth units: the seeds' constant.
    depth: f32,
    // Move the receiver this many texels towards the light: a constant bias.
    toward_light: f32,
    // ... plus slope × tan θ texels, at most slope_max: slope-scaled.
    slope: f32,
    slope_max: f32,
    // Move it along its normal by normal × (1 − N·L) texels: normal offset.
    normal: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
};

// The point whose depth is compared: the receiver moved off its surface.
// `n` is the unit normal on the side the light sees.
fn biased_receiver(world: vec3<f32>, n: vec3<f32>, b: ShadowBias) -> vec3<f32> {
    let l = to_light(world);
    let cos_t = clamp(dot(n, l), 0.0, 1.0);
    // tan θ of the angle between the normal and the light; 1e4 at grazing.
    let tan_t = sqrt(1.0 - cos_t * cos_t) / max(cos_t, 1e-4);
    let texel = shadow_texel_size(world);
    let along_light = b.toward_light + min(b.slope * tan_t, b.slope_max);
    let along_normal = b.normal * (1.0 - cos_t);
    // Along l a directional or spot light's ray stays the same: only depth changes.
    return world + texel * (along_light * l + along_normal * n);
}
// ANCHOR_END: shadow_bias

// The receiver's normal on the light's side (open meshes are two-sided).
fn light_side_normal(in: VertexOut) -> vec3<f32> {
    let n = normalize(in.normal);
    if dot(n, to_light(in.world)) < 0.0 {
        return -n;
    }
    return n;
}

// ANCHOR: biased_visibility
// 1 = lit, 0 = in shadow: one comparison, after the bias.
fn biased_visibility(world: vec3<f32>, n: vec3<f32>, b: ShadowBias) -> f32 {
    let p = biased_receiver(world, n, b);
    let s = shadow_coords(p);
    if outside_shadow_map(p, s) {
        return 1.0;
    }
    // The seeds' bias: a fixed amount of depth, whatever the scene.
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z - b.depth);
}
// ANCHOR_END: biased_visibility
