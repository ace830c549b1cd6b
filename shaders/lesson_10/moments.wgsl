// lesson_10/moments.wgsl: a variance map from the shadow map, in two
// compute passes over the map, into storage buffers of 32-bit floats (a
// 32-bit float colour target is not renderable everywhere: wgpu's GL). The
// first turns each depth into the moments (z, z²) of its linear depth z,
// or those of exp(c (2z − 1)) for an exponential map, and averages 2r + 1
// of them along x; the second averages the first's along y: a (2r + 1)²
// box filter, separable.

// The pass, fixed when its pipeline is built (Rust: moments.rs
// `BlurKey`): which way it blurs, what it stores, how wide; a blur radius
// read from a buffer would keep the loop from unrolling, and a software
// rasteriser would run both directions' reads, masked, at every texel.
// 0: along x, from the depth map; 1: along y, from the first pass.
override VERTICAL: bool = false;
// The moments of exp(c (2z − 1)) (and of −exp(−c⁻ (2z − 1))), else of z.
override EXPONENTIAL: bool = false;
// The box's radius, texels: 2 RADIUS + 1 taps a pass.
override RADIUS: i32 = 4;
// three.js's blur (peers.rs `ThreeVsmBlur`): SAMPLES > 0 takes SAMPLES
// depths over ±`spread` texels, along y then along x, in place of the box.
override SAMPLES: u32 = 0u;

// Rust: lessons/lesson_10/moments.rs `BlurUniform`: the light's geometry
// and the warp's exponents.
struct Blur {
    perspective: u32,
    exponent: f32,
    near: f32,
    far: f32,
    // The negative warp's exponent (EVSM4); 0: none.
    negative: f32,
    // three.js's spread, texels.
    spread: f32,
    _pad1: u32,
    _pad2: u32,
};
@group(0) @binding(0) var depth: texture_2d<f32>;
@group(0) @binding(1) var<storage, read> first: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> blur: Blur;
@group(0) @binding(3) var<storage, read_write> out: array<vec4<f32>>;

// ANCHOR: moments
// The moments of a stored depth's linear depth z in [0, 1] (a perspective
// map's depths crowd near 1, where a variance of their squares is lost to
// rounding). An exponential map stores those of exp(c (2z − 1))
// (Filament's warp): the warp makes a receiver's test sharper, and the
// bound tighter, where blockers overlap; and with a negative exponent c⁻
// also those of −exp(−c⁻ (2z − 1)) in .zw (EVSM4), whose bound is tight
// where the positive one's mean is dragged by far texels.
fn depth_moments(stored: f32) -> vec4<f32> {
    var dist = blur.near + stored * (blur.far - blur.near);
    if blur.perspective == 1u {
        dist = blur.far * blur.near / (blur.far - stored * (blur.far - blur.near));
    }
    let z = (dist - blur.near) / (blur.far - blur.near);
    if !EXPONENTIAL {
        return vec4<f32>(z, z * z, 0.0, 0.0);
    }
    let warped = exp(blur.exponent * (2.0 * z - 1.0));
    let warped_neg = -exp(-blur.negative * (2.0 * z - 1.0));
    return vec4<f32>(warped, warped * warped, warped_neg, warped_neg * warped_neg);
}
// ANCHOR_END: moments

// ANCHOR: threejs_blur
// three.js's VSM blur (vsm.glsl.js): SAMPLES reads evenly spaced over
// ±spread texels; the first pass (along y) reads the map's own depth with
// nearest filtering (its depth texture's NearestFilter), the second (along
// x) the first's (mean, standard deviation), linearly filtered; both write
// (mean, standard deviation).
fn threejs_blur(p: vec2<i32>, size: vec2<i32>) -> vec4<f32> {
    let n = f32(SAMPLES);
    var stride = 0.0;
    var start = 0.0;
    if n > 1.0 {
        stride = 2.0 / (n - 1.0);
        start = -1.0;
    }
    var mean = 0.0;
    var squared_mean = 0.0;
    for (var i = 0u; i < SAMPLES; i++) {
        let offset = (start + f32(i) * stride) * blur.spread;
        let at = floor(offset);
        let f = offset - at;
        if !VERTICAL {
            // The nearest texel to the texel's centre plus the offset.
            let t = clamp(p + vec2<i32>(0, i32(floor(offset + 0.5))), vec2<i32>(0), size - 1);
            let d = textureLoad(depth, t, 0).r;
            mean += d;
            squared_mean += d * d;
        } else {
            let a = clamp(p + vec2<i32>(i32(at), 0), vec2<i32>(0), size - 1);
            let b = clamp(p + vec2<i32>(i32(at) + 1, 0), vec2<i32>(0), size - 1);
            let m = mix(first[a.y * size.x + a.x], first[b.y * size.x + b.x], f);
            mean += m.x;
            squared_mean += m.y * m.y + m.x * m.x;
        }
    }
    mean = mean / n;
    squared_mean = squared_mean / n;
    return vec4<f32>(mean, sqrt(max(0.0, squared_mean - mean * mean)), 0.0, 0.0);
}
// ANCHOR_END: threejs_blur

@compute @workgroup_size(8, 8)
fn cs_blur(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(depth));
    let p = vec2<i32>(id.xy);
    if any(p >= size) {
        return;
    }
    if SAMPLES > 0u {
        out[p.y * size.x + p.x] = threejs_blur(p, size);
        return;
    }
    var sum = vec4<f32>(0.0);
    for (var k = -RADIUS; k <= RADIUS; k++) {
        if !VERTICAL {
            let t = clamp(p + vec2<i32>(k, 0), vec2<i32>(0), size - 1);
            sum += depth_moments(textureLoad(depth, t, 0).r);
        } else {
            let t = clamp(p + vec2<i32>(0, k), vec2<i32>(0), size - 1);
            sum += first[t.y * size.x + t.x];
        }
    }
    out[p.y * size.x + p.x] = sum / f32(2 * RADIUS + 1);
}
