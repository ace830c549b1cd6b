// lesson_02/bias.wgsl: the lit pass with a receiver-side bias. Compiled after
// common.wgsl and lesson_01/shadow_map.wgsl, which hold the lookup.

// ANCHOR: shadow_bias
// Receiver-side bias (Rust: lesson_02::bias::ShadowBias). Lengths are in
// shadow-map texels measured along the receiver's depth gradient
// (`shadow_texel_size`), so one setting fits any scene size, map resolution
// and texel aspect: a receiver needs tan θ / 2 of them.
struct ShadowBias {
    // Subtracted from the receiver's depth, in depth units: the lwjgl book's
    // constant (with depth_slope: the least subtracted).
    depth: f32,
    // Move the receiver this many texels towards the light: a constant bias.
    toward_light: f32,
    // ... plus slope × tan θ texels, at most slope_max: slope-scaled.
    slope: f32,
    slope_max: f32,
    // Move it along its normal by normal × (1 − cos θ) texels: normal offset.
    normal: f32,
    // LearnOpenGL's: max(depth_slope × (1 − cos θ), depth) depth units instead.
    depth_slope: f32,
    // Bevy's: this many world units towards the light, and normal_flat
    // texels (the texel's larger side) along the normal.
    toward_light_world: f32,
    normal_flat: f32,
};
// ANCHOR_END: shadow_bias

// ANCHOR: biased_receiver
// The point whose depth is compared: the receiver moved off its surface.
// `n` is the unit normal on the side the light sees.
fn biased_receiver(world: vec3<f32>, n: vec3<f32>, b: ShadowBias) -> vec3<f32> {
    let l = to_light(world);
    let cos_t = clamp(dot(n, l), 0.0, 1.0);
    // tan θ of the angle between the normal and the light; 1e4 at grazing.
    let tan_t = sqrt(1.0 - cos_t * cos_t) / max(cos_t, 1e-4);
    let texel = shadow_texel_size(world, n);
    let along_light = b.toward_light + min(b.slope * tan_t, b.slope_max);
    let along_normal = b.normal * (1.0 - cos_t);
    // Bevy's offsets: world units along l, whole texels along n.
    let e = shadow_texel_extent(world);
    let bevy = b.toward_light_world * l + b.normal_flat * max(e.x, e.y) * n;
    // Along l a directional or spot light's ray stays the same: only depth changes.
    return world + texel * (along_light * l + along_normal * n) + bevy;
}

// The depth subtracted after the move: the lwjgl book's constant, or
// LearnOpenGL's max(0.05 × (1 − cos θ), 0.005) in depth units.
fn depth_bias(world: vec3<f32>, n: vec3<f32>, b: ShadowBias) -> f32 {
    let cos_t = clamp(dot(n, to_light(world)), 0.0, 1.0);
    return max(b.depth_slope * (1.0 - cos_t), b.depth);
}
// ANCHOR_END: biased_receiver

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
    // A fixed amount of depth, whatever the scene (the lwjgl book's, LearnOpenGL's).
    let z = s.z - depth_bias(world, n, b);
    return textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, z);
}
// ANCHOR_END: biased_visibility

// This variant's receiver-side bias (all zeros for the shadow-pass fixes).
@group(3) @binding(0) var<storage, read> bias: ShadowBias;

// ANCHOR: fs_lit
@fragment
fn fs_lit(in: VertexOut) -> LitOut {
    return lit_output(in, biased_visibility(in.world, light_side_normal(in), bias));
}
// ANCHOR_END: fs_lit
