// lesson_10/soft.wgsl: soft shadows from one shadow map. Compiled after
// common.wgsl, shadow_map.wgsl, lesson 03's exercises.wgsl and pcf.wgsl
// (its receiver_plane_gradient, rotation_angle and pcf_poisson); then, in
// an exercise's module, this lesson's exercises.wgsl and the exercise's
// part of exercise_hooks.wgsl; then peers.wgsl (the renderers' ports,
// and PCSS with their search). Group 2:
// the map (lesson 03's bindings) and
// binding 3, the blurred moments of the filterable maps (moments.wgsl),
// binding 4, the map's min/max mip chain (min_max.wgsl). Group 3: lesson 03's `pcf` filter at binding 0 and `soft` at binding 1.

@group(2) @binding(3) var<storage, read> moments: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read> min_max: array<vec2<f32>>;

// The variant, fixed when its pipeline is built (Rust: soft.rs
// `Technique::constants`): `override`s, not fields of `Soft`. A switch or a
// loop bound read from a buffer keeps every variant's path in every
// variant's pipeline, and a loop whose count is not known does not unroll;
// a software rasteriser runs every case, masked, texture reads included
// (lesson 03's `MODE` says more). With constants the compiler keeps only
// this variant's code.
// 0: lesson 03's Poisson PCF; 1: a fixed disk; 2: PCSS; 3: variance map;
// from 4: PCSS searching the light's size at the receiver, and the
// renderers' ports (peers.wgsl).
override SOFT_MODE: u32 = 2u;
override SEARCH_TAPS: u32 = 16u;
override FILTER_TAPS: u32 = 16u;
// (Each tap compares with the receiver's plane there: lesson 03's
// RECEIVER_PLANE.)
// PCSS's step 3 probes the filter disk's rim first (penumbra_pcf).
override ADAPTIVE: bool = false;
// The first of PCSS's two draws with the min/max chain: it answers where
// the chain tells lit or umbra (`pcss_decided`) and discards the rest,
// which the second draw, plain PCSS, takes where the stencil shows no
// answer (Rust: main.rs `Soft::render`). A branch would not do on a
// software rasteriser: it runs a branch's taps, masked, for pixels that
// skip it; a stencil test skips them before the shader.
override MIN_MAX: bool = false;
// Variance maps: the moments of exp(c (2z − 1)), z the linear depth
// (else plain); with NEGATIVE_WARP also of −exp(−c⁻ (2z − 1)) (EVSM4).
override EXPONENTIAL: bool = false;
override NEGATIVE_WARP: bool = false;
// (A renderer's receiver offsets: lesson 03's RENDERER_BIAS.)

// Rust: lessons/lesson_10/soft.rs `SoftUniform`, one per variant and light:
// the light's geometry and the variant's continuous parameters.
struct Soft {
    // Orthographic: world distance from the light's plane at depth 0 and 1.
    // Perspective: the near and far planes.
    near: f32,
    far: f32,
    // Orthographic: tan(angular radius); perspective: the emitter's radius.
    // A port: the renderer's own light size (peers.rs says which).
    size: f32,
    // The nearest caster's distance from the light (depth-plane units).
    nearest_caster: f32,
    // Map units per world unit across the light (orthographic, u and v),
    // or per radian of angle from the axis (perspective: 1 / (2 tan(fov/2))).
    uv_per: vec2<f32>,
    // A fixed disk's radius, in texels; the least filter radius, in texels.
    fixed_radius_texels: f32,
    min_filter_texels: f32,
    // Variance maps: the least variance, the light-bleeding cut
    // linstep(bleed_lo, bleed_hi, p), the exponent c.
    min_variance: f32,
    bleed_lo: f32,
    bleed_hi: f32,
    exponent: f32,
    // The negative warp's exponent c⁻ (EVSM4, with NEGATIVE_WARP).
    negative: f32,
    // A port's second size (Godot's soft_shadow_scale).
    scale: f32,
    // The light: 0 orthographic (directional), 1 perspective (spot): the
    // light's, not the variant's (one pipeline serves both).
    perspective: u32,
    _pad: u32,
    // Vogel's disk for n = 1 (`vogel`).
    disk: array<vec2<f32>, 64>,
};
@group(3) @binding(1) var<storage, read> soft: Soft;

// ANCHOR: distance
// The distance from the light of a point at map depth `depth` (what the
// map stores): linear for an orthographic map; for webgpu's perspective,
// depth = f (d − n) / (d (f − n)).
fn light_distance(depth: f32) -> f32 {
    if soft.perspective == 0u {
        return soft.near + depth * (soft.far - soft.near);
    }
    return soft.far * soft.near / (soft.far - depth * (soft.far - soft.near));
}
// ANCHOR_END: distance

// ANCHOR: penumbra
// The filter's radius in map units for a receiver at distance d_r and a
// blocker at d_b (parallel planes, Fernando 2005). The blocker's footprint
// that hides part of the emitter from the receiver: a disk of world radius
// (d_r − d_b) tan α (directional, cone α), or R (d_r − d_b) / d_r at
// distance d_b, which the map sees under the angle R (d_r − d_b) / (d_r d_b)
// (a spot's disk of radius R).
fn filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    let h = max(d_r - d_b, 0.0);
    if soft.perspective == 0u {
        return h * soft.size * soft.uv_per;
    }
    return soft.size * h / (d_r * max(d_b, 1e-6)) * soft.uv_per;
}
// ANCHOR_END: penumbra

// ANCHOR: vogel
// Point i of an n-point disk: Vogel's golden-angle spiral, radius
// sqrt((i + 0.5) / n), angle i × 2.39996323, turned by `rot`. Equal areas
// per point, no two close, for any n. The points are a table the lesson
// writes once (`soft.disk`, soft.rs `vogel_table`), scaled by 1/sqrt(n),
// a pipeline constant: no root, sine or cosine per tap. (A WGSL `const`
// array read at a loop's index is copied whole per read: 8 times the lit
// pass on lavapipe.)
fn disk_rotation(angle: f32) -> mat2x2<f32> {
    return mat2x2<f32>(cos(angle), sin(angle), -sin(angle), cos(angle));
}

fn vogel(i: u32, n: u32, rot: mat2x2<f32>) -> vec2<f32> {
    return rot * soft.disk[i] * inverseSqrt(f32(n));
}
// ANCHOR_END: vogel

// A blocker search's result: the mean blocker distance, and how many taps
// found one.
struct Blockers {
    distance: f32,
    count: u32,
};

// ANCHOR: blocker_search
// The taps of a disk of `radius` (map units) that see something in front of
// the receiver's plane, and their mean distance from the light.
fn blocker_search(s: vec3<f32>, radius: vec2<f32>, taps: u32, rot: mat2x2<f32>, gradient: vec2<f32>) -> Blockers {
    let size = vec2<f32>(textureDimensions(shadow_depths));
    var sum = 0.0;
    var count = 0u;
    for (var i = 0u; i < taps; i++) {
        let o = vogel(i, taps, rot) * radius;
        let texel = clamp(vec2<i32>(floor((s.xy + o) * size)), vec2<i32>(0), vec2<i32>(size) - 1);
        let depth = textureLoad(shadow_depths, texel, 0).r;
        if depth < s.z + dot(gradient, o) {
            sum += light_distance(depth);
            count += 1u;
        }
    }
    return Blockers(sum / max(f32(count), 1.0), count);
}
// ANCHOR_END: blocker_search

// ANCHOR: disk_pcf
// `taps` bilinear comparisons on a disk of `radius` (map units): the
// fraction of the taps the receiver's plane is not behind.
fn disk_pcf(s: vec3<f32>, radius: vec2<f32>, taps: u32, rot: mat2x2<f32>, gradient: vec2<f32>) -> f32 {
    var lit = 0.0;
    for (var i = 0u; i < taps; i++) {
        let o = vogel(i, taps, rot) * radius;
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + o, s.z + dot(gradient, o));
    }
    return lit / f32(taps);
}
// ANCHOR_END: disk_pcf

// ANCHOR: pcss
// Percentage-closer soft shadows: find the blockers, estimate the
// penumbra from their mean distance, filter that wide.
fn pcss(s: vec3<f32>, angle: f32, gradient: vec2<f32>) -> f32 {
    let d_r = light_distance(s.z);
    // 1. Blocker search, wherever blockers can be: the emitter seen
    // through the receiver, on the nearest caster's plane.
    let search = filter_radius(d_r, min(soft.nearest_caster, d_r));
    let blockers = blocker_search(s, search, SEARCH_TAPS, disk_rotation(angle), gradient);
    if blockers.count == 0u {
        return 1.0;
    }
    // 2. Penumbra estimate: the footprint on the blockers' mean plane.
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let radius = max(filter_radius(d_r, blockers.distance), vec2<f32>(soft.min_filter_texels * texel));
    // 3. Filter: a PCF that wide.
    return penumbra_pcf(s, radius, FILTER_TAPS, angle + 1.0, gradient);
}
// ANCHOR_END: pcss

// ANCHOR: region_min_max
// The nearest and farthest depth of the map's texels from `lo` to `hi`
// (inclusive): four blocks of the chain's level l, the first whose
// 2^l-texel blocks are as wide as the region, so that it spans two of them
// at most along each axis. Level l starts after levels 1 to l − 1, each
// a quarter of the one before.
fn region_min_max(lo: vec2<i32>, hi: vec2<i32>) -> vec2<f32> {
    let side = textureDimensions(shadow_depths).x;
    let width = u32(max(hi.x - lo.x, hi.y - lo.y));
    let top = countTrailingZeros(side);
    let l = clamp(32u - countLeadingZeros(width), 1u, top);
    let below = side >> (l - 1u);
    let start = (side * side - below * below) / 3u;
    let n = side >> l;
    let a = vec2<u32>(lo) >> vec2<u32>(l);
    let b = vec2<u32>(hi) >> vec2<u32>(l);
    let m00 = min_max[start + a.y * n + a.x];
    let m10 = min_max[start + a.y * n + b.x];
    let m01 = min_max[start + b.y * n + a.x];
    let m11 = min_max[start + b.y * n + b.x];
    return vec2<f32>(min(min(m00.x, m10.x), min(m01.x, m11.x)), max(max(m00.y, m10.y), max(m01.y, m11.y)));
}

// The texels a disk of `radius` (map units) around uv touches, a texel more
// on each side for rounding; `half` 0.5 for bilinear taps (their 2×2
// starts half a texel back), 0 for point loads.
fn texel_region(uv: vec2<f32>, radius: vec2<f32>, half: f32) -> array<vec2<i32>, 2> {
    let size = vec2<f32>(textureDimensions(shadow_depths));
    let last = vec2<i32>(size) - 1;
    let lo = vec2<i32>(floor((uv - radius) * size - half)) - 1;
    let hi = vec2<i32>(floor((uv + radius) * size - half)) + 2;
    return array<vec2<i32>, 2>(clamp(lo, vec2<i32>(0), last), clamp(hi, vec2<i32>(0), last));
}
// ANCHOR_END: region_min_max

// ANCHOR: pcss_decided
// What PCSS would answer, where the chain alone can tell: 1 where every
// texel the search can read is at or behind the receiver's plane (the
// search finds no blocker), 0 where every texel the search and then the
// widest filter its blockers allow can read is in front of it (every
// comparison is in shadow); −1 where it cannot tell. The plane's height
// over a box of half-widths r is at most |gradient| · r either way; the
// margin covers the rounding of the taps' own sums.
fn pcss_decided(s: vec3<f32>, gradient: vec2<f32>) -> f32 {
    let d_r = light_distance(s.z);
    let search = filter_radius(d_r, min(soft.nearest_caster, d_r));
    let tilt = dot(abs(gradient), search);
    let margin = 1e-6 + 1e-5 * tilt;
    let r = texel_region(s.xy, search, 0.0);
    let near_far = region_min_max(r[0], r[1]);
    if near_far.x >= s.z + tilt + margin {
        return 1.0;
    }
    if near_far.y >= s.z - tilt - margin {
        return -1.0;
    }
    // Every search tap finds a blocker, none nearer than the region's
    // nearest: the filter is no wider than that blocker makes it.
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let widest = max(filter_radius(d_r, light_distance(near_far.x)) * 1.001, vec2<f32>(soft.min_filter_texels * texel));
    let tilt_f = dot(abs(gradient), widest);
    let f = texel_region(s.xy, widest, 0.5);
    let far = region_min_max(f[0], f[1]).y;
    if far < min(s.z - tilt_f, 1.0) - 1e-6 - 1e-5 * tilt_f {
        return 0.0;
    }
    return -1.0;
}
// ANCHOR_END: pcss_decided

// ANCHOR: penumbra_pcf
// PCSS's filter. Adaptive: lesson 03's 4 probes on the disk's rim first
// (`rim_probes`, its radius already in map units); all lit or all in
// shadow, and the pixel is lit or in umbra, for 4 taps instead of the
// disk's 16. Only where they disagree, the full disk (a caster thinner
// than the disk between the probes is missed).
fn penumbra_pcf(s: vec3<f32>, radius: vec2<f32>, taps: u32, angle: f32, gradient: vec2<f32>) -> f32 {
    if ADAPTIVE {
        let sum = rim_probes(s, radius, 1.0, angle, gradient);
        if sum == 0.0 || sum == 4.0 {
            return sum / 4.0;
        }
    }
    return disk_pcf(s, radius, taps, disk_rotation(angle), gradient);
}
// ANCHOR_END: penumbra_pcf

// ANCHOR: chebyshev
// Variance shadow maps (Donnelly and Lauritzen 2006): the blurred map holds
// the mean μ and the mean square of the depths around the texel; the
// one-tailed Chebyshev inequality bounds the share of them at or behind t:
// P(z ≥ t) ≤ σ² / (σ² + (t − μ)²) for t > μ. Exact for one planar blocker
// over a planar receiver; over two blockers at different depths the bound
// is loose, and light bleeds through.
fn chebyshev(m: vec2<f32>, t: f32, min_variance: f32) -> f32 {
    if t <= m.x {
        return 1.0;
    }
    let variance = max(m.y - m.x * m.x, min_variance);
    let behind = t - m.x;
    return variance / (variance + behind * behind);
}
// ANCHOR_END: chebyshev

// The moments of texel t (clamped to the map), from the blurred buffer.
fn moments_texel(t: vec2<i32>) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(shadow_depths));
    let c = clamp(t, vec2<i32>(0), size - 1);
    return moments[c.y * size.x + c.x];
}

// The moments at uv, blended bilinearly by hand (32-bit floats in a
// storage buffer: no filtering sampler reads them).
fn moments_at(uv: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(shadow_depths));
    let p = uv * size - 0.5;
    let f = fract(p);
    let i = vec2<i32>(floor(p));
    let t00 = moments_texel(i);
    let t10 = moments_texel(i + vec2<i32>(1, 0));
    let t01 = moments_texel(i + vec2<i32>(0, 1));
    let t11 = moments_texel(i + vec2<i32>(1, 1));
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}

// ANCHOR: variance_map
// Lauritzen's light-bleeding reduction: the tail of x below `lo` is cut,
// the rest stretched to [0, 1] (three.js: lo 0.3, hi 0.95).
fn linstep(lo: f32, hi: f32, x: f32) -> f32 {
    return clamp((x - lo) / (hi - lo), 0.0, 1.0);
}

fn variance_map(s: vec3<f32>) -> f32 {
    // The receiver's linear depth t in [0, 1], as the moments hold the
    // map's (moments.wgsl).
    let t = linear_depth(s.z);
    let m = moments_at(s.xy);
    var p_max = 1.0;
    if !EXPONENTIAL {
        p_max = chebyshev(m.xy, t, soft.min_variance);
    } else {
        // exp(c (2t − 1)); the least variance scales with it.
        let warped = exp(soft.exponent * (2.0 * t - 1.0));
        p_max = chebyshev(m.xy, warped, soft.min_variance * warped * warped);
        if NEGATIVE_WARP {
            let warped_neg = -exp(-soft.negative * (2.0 * t - 1.0));
            p_max = min(p_max, chebyshev(m.zw, warped_neg, soft.min_variance * warped_neg * warped_neg));
        }
    }
    return linstep(soft.bleed_lo, soft.bleed_hi, p_max);
}

// A map depth as a fraction of the light's near-to-far distance.
fn linear_depth(depth: f32) -> f32 {
    return (light_distance(depth) - soft.near) / (soft.far - soft.near);
}
// ANCHOR_END: variance_map

// ANCHOR: fs_soft
@fragment
fn fs_soft(in: VertexOut) -> LitOut {
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
    let angle = rotation_angle(in.clip.xy);
    var v = 1.0;
    if MIN_MAX {
        if !outside_shadow_map(r.xyz, s) {
            v = pcss_decided(s, gradient);
        }
        if v < 0.0 {
            discard;
        }
    } else if !outside_shadow_map(r.xyz, s) {
        switch SOFT_MODE {
            case 0u: { v = pcf_poisson(s, in.clip.xy, gradient); }
            case 1u: {
                let texel = 1.0 / f32(textureDimensions(shadow_map).x);
                v = disk_pcf(s, vec2<f32>(soft.fixed_radius_texels * texel), FILTER_TAPS, disk_rotation(angle), gradient);
            }
            case 2u: { v = pcss(s, angle, gradient); }
            case 3u: { v = variance_map(s); }
            default: { v = peer(s, in.clip.xy, gradient); }
        }
    }
    return lit_output(in, v);
}
// ANCHOR_END: fs_soft
