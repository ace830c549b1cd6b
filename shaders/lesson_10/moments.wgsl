// lesson_10/moments.wgsl: a variance map from the shadow map, in two
// full-screen passes over the map (appended to fullscreen.wgsl). The first
// turns each depth into the moments (z̃, z̃²) of its linear depth z̃, or those of exp(c (2 z̃ − 1))
// for an exponential map, and averages 2r + 1 of them along x; the second
// averages the first's along y: a (2r + 1)² box filter, separable.

// Rust: lessons/lesson_10/moments.rs `BlurUniform`.
struct Blur {
    radius: i32,
    // 0: along x, from the depth map; 1: along y, from the first pass.
    vertical: u32,
    exponential: u32,
    perspective: u32,
    exponent: f32,
    near: f32,
    far: f32,
    _pad: f32,
};
@group(0) @binding(0) var depth: texture_2d<f32>;
@group(0) @binding(1) var first: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> blur: Blur;

// ANCHOR: moments
// A depth's moments, of the linear depth z̃ in [0, 1] (a perspective map's
// depths crowd near 1, where a variance of their squares is lost to
// rounding). An exponential map stores those of exp(c (2 z̃ − 1))
// (Filament's warp): the warp makes a receiver's test sharper, and the
// bound tighter, where blockers overlap.
fn depth_moments(z: f32) -> vec2<f32> {
    var d = blur.near + z * (blur.far - blur.near);
    if blur.perspective == 1u {
        d = blur.far * blur.near / (blur.far - z * (blur.far - blur.near));
    }
    var x = (d - blur.near) / (blur.far - blur.near);
    if blur.exponential == 1u {
        x = exp(blur.exponent * (2.0 * x - 1.0));
    }
    return vec2<f32>(x, x * x);
}
// ANCHOR_END: moments

@fragment
fn fs_blur(in: FullscreenOut) -> @location(0) vec4<f32> {
    let size = vec2<i32>(textureDimensions(depth));
    let p = vec2<i32>(in.pos.xy);
    var sum = vec2<f32>(0.0);
    for (var k = -blur.radius; k <= blur.radius; k++) {
        if blur.vertical == 0u {
            let t = clamp(p + vec2<i32>(k, 0), vec2<i32>(0), size - 1);
            sum += depth_moments(textureLoad(depth, t, 0).r);
        } else {
            let t = clamp(p + vec2<i32>(0, k), vec2<i32>(0), size - 1);
            sum += textureLoad(first, t, 0).xy;
        }
    }
    return vec4<f32>(sum / f32(2 * blur.radius + 1), 0.0, 1.0);
}
