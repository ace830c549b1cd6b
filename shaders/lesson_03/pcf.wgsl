// lesson_03.wgsl: percentage-closer filtering. Compiled after common.wgsl and
// shadow_map.wgsl (the map at group 2, shadow_coords). The map's depths come
// with lesson 02's slope-scaled bias already added by the shadow pass.

// The same shadow map read as plain floats (for the depth-averaging variant;
// GL cannot load texels through a comparison binding).
@group(2) @binding(2) var shadow_depths: texture_2d<f32>;

// The filter, fixed when the pipeline is compiled (Rust: `Filter::mode` in
// lessons/lesson_03/pcf.rs): 0: N×N grid, 1: hardware 2×2, 2: rotated
// Poisson disk, 3: average depths; the exercises (exercises.wgsl):
// 4: exercise_pcf_kernel, 5: exercise_world_disk; 6: Bevy's Castaño
// 5×5 Gaussian. An `override`, not a field of `Filter`: a switch on a value
// read from a buffer keeps every case in the compiled shader, and a software
// rasteriser runs them all, masked, texture reads included (on lavapipe one
// bilinear tap cost as much as sixteen). A constant lets the compiler drop
// the cases this pipeline never takes.
override MODE: u32 = 0u;
// A renderer's receiver bias (peer_receiver) in this pipeline: the
// lesson's own filters compile without it (their bias fields are all 0).
override RENDERER_BIAS: bool = false;
// The grid's and the depth average's N (N×N taps), and whether each tap
// compares with the receiver's plane there (RPDB): constants too, so a
// grid's loops unroll (Rust: `Filter::grid_constants`).
override N: u32 = 3u;
override RECEIVER_PLANE: bool = false;
// Set by pcf_adaptive where its probes disagreed (fs_adaptive_count).
var<private> took_full_disk: bool = false;

// Rust: lessons/lesson_03/pcf.rs `FilterUniform`: a filter's continuous
// parameters (its switches and counts are the constants above).
struct Filter {
    _pad_a: u32,
    _pad_b: u32,
    _pad_c: u32,
    // Poisson disk: radius in texels.
    radius: f32,
    // A renderer's receiver bias (lesson 02's ShadowBias fields; 0 for ours):
    // LearnOpenGL's max(depth_slope × (1 − N·L), depth) of depth, Bevy's
    // world units towards the light and texels along the normal; texels
    // along the normal × (1 − cos θ) (Godot's) and × sin θ (Filament's).
    depth: f32,
    depth_slope: f32,
    toward_light_world: f32,
    normal_flat: f32,
    normal: f32,
    normal_sin: f32,
    _pad2: f32,
    _pad3: f32,
};
@group(3) @binding(0) var<storage, read> pcf: Filter;

// ANCHOR: receiver_plane
// How the receiver's depth changes across the map: d(depth)/d(u, v) of the
// plane through this pixel, from the screen-space derivatives of (u, v, depth).
// A tap at offset o then compares against depth + dot(gradient, o): the
// receiver's own plane there, instead of the centre's depth.
//
// (u, v, depth) = shadow_coords(world) is a projection, so its screen-space
// derivative follows from the world position's by the chain rule: with
// c = M·(p, 1), dc = M·(dp, 0) and d(c.xyz / c.w) = (dc.xyz − ndc·dc.w) / c.w.
// (Why not dpdx(shadow_coords(world)) directly: the light's matrix is read
// from a storage buffer, and on lavapipe the finite differences of values
// read from storage came out wrong: 5.0 % misclassified instead of 0.2 % on
// this lesson's scene. Differentiating the interpolated world position is
// exact to first order on every backend.)
// `c`: the light's clip coordinates of the point, light.view_proj · (world, 1).
fn shadow_coords_delta(c: vec4<f32>, d_world: vec3<f32>) -> vec3<f32> {
    let dc = light.view_proj * vec4<f32>(d_world, 0.0);
    let d_ndc = (dc.xyz - c.xyz / c.w * dc.w) / c.w;
    return vec3<f32>(0.5 * d_ndc.x, -0.5 * d_ndc.y, d_ndc.z);
}

fn receiver_plane_gradient(world: vec3<f32>) -> vec2<f32> {
    let c = light.view_proj * vec4<f32>(world, 1.0);
    let dx = shadow_coords_delta(c, dpdx(world));
    let dy = shadow_coords_delta(c, dpdy(world));
    let det = dx.x * dy.y - dx.y * dy.x;
    if abs(det) < 1e-20 {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det;
}
// ANCHOR_END: receiver_plane

// ANCHOR: pcf_grid
// N×N nearest comparisons around the receiver, averaged: the fraction of the
// taps whose stored depth is not in front of the receiver.
fn pcf_grid(s: vec3<f32>, n: i32, gradient: vec2<f32>) -> f32 {
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let r = n / 2;
    var lit = 0.0;
    for (var y = -r; y <= r; y++) {
        for (var x = -r; x <= r; x++) {
            let o = vec2<f32>(f32(x), f32(y)) * texel;
            lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
        }
    }
    return lit / f32(n * n);
}
// ANCHOR_END: pcf_grid

// ANCHOR: poisson
// 16 points of a Poisson disk in the unit circle (no two closer than 0.42).
const POISSON_DISK = array<vec2<f32>, 16>(
    vec2<f32>(0.4566, -0.5539), vec2<f32>(0.2625, 0.2274), vec2<f32>(-0.3396, 0.8718), vec2<f32>(-0.6309, 0.2422),
    vec2<f32>(0.7170, 0.0136), vec2<f32>(0.6324, 0.6501), vec2<f32>(-0.7837, -0.3495), vec2<f32>(-0.1228, -0.5643),
    vec2<f32>(-0.3798, -0.1711), vec2<f32>(0.2276, 0.9058), vec2<f32>(0.8729, -0.4201), vec2<f32>(0.2302, -0.9317),
    vec2<f32>(-0.3928, -0.9130), vec2<f32>(-0.2094, 0.4436), vec2<f32>(-0.7033, 0.6601), vec2<f32>(0.1568, -0.1990),
);

// Interleaved gradient noise (Jimenez 2014): a different angle per pixel, so
// that neighbouring pixels see different taps and the banding of a fixed
// pattern turns into fine noise.
fn rotation_angle(pixel: vec2<f32>) -> f32 {
    return 6.2831853 * fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715))));
}

// 16 bilinear (2×2) comparisons on the rotated disk.
fn pcf_poisson(s: vec3<f32>, pixel: vec2<f32>, gradient: vec2<f32>) -> f32 {
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let a = rotation_angle(pixel);
    let rot = mat2x2<f32>(cos(a), sin(a), -sin(a), cos(a));
    var lit = 0.0;
    // A constant trip count: the compiler unrolls the loop and the disk's
    // points become constants (an indexed array would live in memory).
    for (var i = 0u; i < 16u; i++) {
        let o = rot * POISSON_DISK[i] * pcf.radius * texel;
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
    }
    return lit / 16.0;
}
// ANCHOR_END: poisson

// ANCHOR: rim_probes
// 4 bilinear comparisons a quarter turn apart on a disk's rim, the first
// at angle `a`: the disk's radius is `radius` × `unit` in map coordinates
// (lesson 03: texels and the texel's size; lesson 10's PCSS: map units
// and 1). Returns how many of the 4 are lit: 0 or 4 where they agree.
fn rim_probes(s: vec3<f32>, radius: vec2<f32>, unit: f32, a: f32, gradient: vec2<f32>) -> f32 {
    var sum = 0.0;
    for (var i = 0u; i < 4u; i++) {
        let t = a + 1.5707963 * f32(i);
        let o = vec2<f32>(cos(t), sin(t)) * radius * unit;
        sum += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
    }
    return sum;
}
// ANCHOR_END: rim_probes

// ANCHOR: adaptive
// Adaptive: 4 bilinear probes on the rotated disk's rim decide. All four
// lit: the pixel is lit; all four in shadow: umbra. Only where they
// disagree, a penumbra, the full 16-tap disk. Most pixels are far from an
// edge, so most pay 4 taps instead of 16; a caster thinner than the disk
// that falls between the probes is missed (the error the chapter measures).
fn pcf_adaptive(s: vec3<f32>, pixel: vec2<f32>, gradient: vec2<f32>) -> f32 {
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let sum = rim_probes(s, vec2<f32>(pcf.radius), texel, rotation_angle(pixel), gradient);
    if sum == 0.0 || sum == 4.0 {
        return sum / 4.0;
    }
    took_full_disk = true;
    return pcf_poisson(s, pixel, gradient);
}
// ANCHOR_END: adaptive

// ANCHOR: depth_average
// The wrong way: average the N×N stored depths, then compare once. Near a
// shadow's edge the average is a depth where no surface is (between the
// caster and the floor), and the answer is still 0 or 1.
fn depth_average(s: vec3<f32>, n: i32) -> f32 {
    let size = vec2<i32>(textureDimensions(shadow_depths));
    let centre = vec2<i32>(floor(s.xy * vec2<f32>(size)));
    let r = n / 2;
    var sum = 0.0;
    for (var y = -r; y <= r; y++) {
        for (var x = -r; x <= r; x++) {
            let t = clamp(centre + vec2<i32>(x, y), vec2<i32>(0), size - 1);
            sum += textureLoad(shadow_depths, t, 0).r;
        }
    }
    return select(0.0, 1.0, s.z <= sum / f32(n * n));
}
// ANCHOR_END: depth_average

// ANCHOR: castano
// Bevy's default filter (bevy_pbr shadow_sampling.wgsl,
// sample_shadow_map_castano_thirteen): a 5×5 tent-like Gaussian from 9
// bilinear comparisons, their weights and positions chosen so each bilinear
// tap stands for a 2×2 block of the kernel (Castaño, The Witness, 2013).
// Bevy's lines and names, so that they read against its source.
fn pcf_castano13(coords: vec3<f32>) -> f32 {
    let shadow_map_size = vec2<f32>(textureDimensions(shadow_map));
    let inv_shadow_map_size = 1.0 / shadow_map_size;
    let uv = coords.xy * shadow_map_size;
    var base_uv = floor(uv + 0.5);
    let s = (uv.x + 0.5 - base_uv.x);
    let t = (uv.y + 0.5 - base_uv.y);
    base_uv -= 0.5;
    base_uv *= inv_shadow_map_size;
    let uw0 = (4.0 - 3.0 * s);
    let uw1 = 7.0;
    let uw2 = (1.0 + 3.0 * s);
    let u0 = (3.0 - 2.0 * s) / uw0 - 2.0;
    let u1 = (3.0 + s) / uw1;
    let u2 = s / uw2 + 2.0;
    let vw0 = (4.0 - 3.0 * t);
    let vw1 = 7.0;
    let vw2 = (1.0 + 3.0 * t);
    let v0 = (3.0 - 2.0 * t) / vw0 - 2.0;
    let v1 = (3.0 + t) / vw1;
    let v2 = t / vw2 + 2.0;
    // Bevy's nine sums, as a loop: weight uw[i] × vw[j] at (u[i], v[j]).
    let uw = array<f32, 3>(uw0, uw1, uw2);
    let vw = array<f32, 3>(vw0, vw1, vw2);
    let u = array<f32, 3>(u0, u1, u2);
    let v = array<f32, 3>(v0, v1, v2);
    var sum = 0.0;
    for (var j = 0; j < 3; j++) {
        for (var i = 0; i < 3; i++) {
            let o = vec2<f32>(u[i], v[j]) * inv_shadow_map_size;
            sum += uw[i] * vw[j] * textureSampleCompareLevel(shadow_map, shadow_compare, base_uv + o, coords.z);
        }
    }
    return sum * (1.0 / 144.0);
}
// ANCHOR_END: castano

// ANCHOR: peer_receiver
// A renderer's receiver bias: Bevy, Godot and Filament move the point
// (world units towards the light, texels along the normal: flat, or
// × (1 − cos θ), or × sin θ), LearnOpenGL subtracts depth after.
// xyz: the point to look up; w: the depth to subtract.
fn peer_receiver(world: vec3<f32>, normal: vec3<f32>) -> vec4<f32> {
    let l = to_light(world);
    var n = normalize(normal);
    if dot(n, l) < 0.0 {
        n = -n; // open meshes are two-sided: the side the light sees
    }
    let e = shadow_texel_extent(world);
    let cos_t = clamp(dot(n, l), 0.0, 1.0);
    let sin_t = sqrt(1.0 - cos_t * cos_t);
    let texels = pcf.normal_flat + pcf.normal * (1.0 - cos_t) + pcf.normal_sin * sin_t;
    let p = world + pcf.toward_light_world * l + texels * max(e.x, e.y) * n;
    return vec4<f32>(p, max(pcf.depth_slope * (1.0 - cos_t), pcf.depth));
}
// ANCHOR_END: peer_receiver

// ANCHOR: fs_lit
@fragment
fn fs_lit(in: VertexOut) -> LitOut {
    var r = vec4<f32>(in.world, 0.0);
    if RENDERER_BIAS {
        r = peer_receiver(in.world, in.normal);
    }
    var s = shadow_coords(r.xyz);
    s.z -= r.w;
    // Derivatives before any branch: they need all four pixels of the quad.
    var gradient = receiver_plane_gradient(in.world);
    if !RECEIVER_PLANE {
        gradient = vec2<f32>(0.0);
    }
    var v = 1.0;
    if !outside_shadow_map(r.xyz, s) {
        switch MODE {
            case 0u: { v = pcf_grid(s, i32(N), gradient); }
            // One tap; the sampler compares the 4 nearest texels and blends.
            case 1u: { v = textureSampleCompareLevel(shadow_map, shadow_compare, s.xy, s.z); }
            case 2u: { v = pcf_poisson(s, in.clip.xy, gradient); }
            // 4 and 5: the chapter's exercises (exercises.wgsl).
            case 4u, 5u: { v = coursework_filter(s, in, gradient); }
            case 6u: { v = pcf_castano13(s); }
            case 7u: { v = pcf_adaptive(s, in.clip.xy, gradient); }
            default: { v = depth_average(s, i32(N)); }
        }
    }
    return lit_output(in, v);
}
// ANCHOR_END: fs_lit

// The exercises' filters, MODE 4 and 5: the student's functions in
// exercises.wgsl, called as fs_lit would call a filter of the lesson.
fn coursework_filter(s: vec3<f32>, in: VertexOut, gradient: vec2<f32>) -> f32 {
    if MODE == 4u {
        return exercise_pcf_kernel(s, i32(N) / 2, gradient);
    }
    return exercise_world_disk(s, in.world, in.clip.xy, pcf.radius, gradient);
}

// Harness, not the technique: which path the adaptive filter took at each
// pixel its lit pass shades inside the map, as the visibility (1.0 the full
// disk, 0.5 the probes alone, 0 outside the map). A pipeline of its own,
// drawn once per variant in an untimed submit; the lesson sums the image
// into its counters `probed_pixels` and `full_disk_pixels`.
@fragment
fn fs_adaptive_count(in: VertexOut) -> LitOut {
    let s = shadow_coords(in.world);
    var gradient = receiver_plane_gradient(in.world);
    if !RECEIVER_PLANE {
        gradient = vec2<f32>(0.0);
    }
    var v = 0.0;
    if !outside_shadow_map(in.world, s) {
        _ = pcf_adaptive(s, in.clip.xy, gradient);
        v = select(0.5, 1.0, took_full_disk);
    }
    return lit_output(in, v);
}
