// lesson_10/peers.wgsl: the soft-shadow defaults of renderers people use,
// each written as its source writes it (the file, commit and lines are on
// its card, lessons/lesson_10/port_cards.rs). Compiled after soft.wgsl:
// light_distance, the map's bindings and `soft` are there. Filament, Bevy
// and Godot keep reversed depth (1 at the near plane), three.js forward
// depth by default; our map keeps forward depth z, and for the same near
// and far planes the reversed depth is exactly 1 − z (orthographic and
// perspective alike), so each reversed port turns our depths into its
// renderer's before its arithmetic.

// The peer's mode in `SOFT_MODE` (peers.rs `Peer::mode`; soft.rs
// `Technique::mode` for our PCSS with Filament's and Bevy's search), a
// constant of the variant's pipeline: it holds only its own port.
const PCSS_SEARCH_AT_RECEIVER: u32 = 4u;
const FILAMENT_PCSS: u32 = 7u;
const BEVY_PCSS: u32 = 8u;
const BEVY_CASTANO: u32 = 9u;
const GODOT_SOFT: u32 = 10u;
const THREEJS_PCF_SOFT: u32 = 5u;
const THREEJS_VSM: u32 = 6u;
const FILAMENT_PCF: u32 = 11u;
const GODOT_PCF: u32 = 12u;
const THREEJS_PCF: u32 = 13u;

fn peer(s: vec3<f32>, pixel: vec2<f32>, gradient: vec2<f32>) -> f32 {
    switch SOFT_MODE {
        case PCSS_SEARCH_AT_RECEIVER: { return pcss_search_at_receiver(s, rotation_angle(pixel), gradient); }
        case FILAMENT_PCSS: { return filament_pcss(s, pixel, gradient); }
        case BEVY_PCSS: { return bevy_pcss(s, pixel); }
        // Bevy with soft_shadow_size None (its default on a sun): its
        // default filter, lesson 03's Castaño 5×5.
        case BEVY_CASTANO: { return pcf_castano13(s); }
        case GODOT_SOFT: { return godot_soft(s, pixel); }
        // Its moments from soft.wgsl's buffer, as three.js's blur left them.
        case THREEJS_VSM: { return threejs_vsm(s, moments_at(s.xy)); }
        case FILAMENT_PCF: { return filament_pcf_low(s); }
        case GODOT_PCF: { return godot_pcf(s, pixel); }
        case THREEJS_PCF: { return three_pcf(s, pixel); }
        default: { return three_pcf_soft(s); }
    }
}

// Bilinear depth at uv, by hand from the four texels (a depth texture has no
// filtering sampler in WebGPU); what a linear sampler on the map returns.
fn depth_bilinear(uv: vec2<f32>) -> f32 {
    let size = vec2<i32>(textureDimensions(shadow_depths));
    let p = uv * vec2<f32>(size) - 0.5;
    let f = fract(p);
    let i = vec2<i32>(floor(p));
    let a = textureLoad(shadow_depths, clamp(i, vec2<i32>(0), size - 1), 0).r;
    let b = textureLoad(shadow_depths, clamp(i + vec2<i32>(1, 0), vec2<i32>(0), size - 1), 0).r;
    let c = textureLoad(shadow_depths, clamp(i + vec2<i32>(0, 1), vec2<i32>(0), size - 1), 0).r;
    let d = textureLoad(shadow_depths, clamp(i + vec2<i32>(1, 1), vec2<i32>(0), size - 1), 0).r;
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// The depth at the nearest texel to uv.
fn depth_nearest(uv: vec2<f32>) -> f32 {
    let size = vec2<i32>(textureDimensions(shadow_depths));
    let t = clamp(vec2<i32>(floor(uv * vec2<f32>(size))), vec2<i32>(0), size - 1);
    return textureLoad(shadow_depths, t, 0).r;
}

// Our PCSS (soft.wgsl's pcss) with the blocker search Filament and Bevy
// run: only the light's size at the receiver, not every blocker out to
// the nearest caster (the knob search_at_receiver). Steps 2 and 3 are ours.
fn pcss_search_at_receiver(s: vec3<f32>, angle: f32, gradient: vec2<f32>) -> f32 {
    let d_r = light_distance(s.z);
    // The light's size in map units (per radian at the receiver's distance,
    // for a spot).
    var search = soft.size * soft.uv_per;
    if soft.perspective == 1u {
        search = search / d_r;
    }
    let b = blocker_search(s, search, SEARCH_TAPS, disk_rotation(angle), gradient);
    if b.count == 0u {
        return 1.0;
    }
    let texel = 1.0 / f32(textureDimensions(shadow_map).x);
    let radius = max(filter_radius(d_r, b.distance), vec2<f32>(soft.min_filter_texels * texel));
    return penumbra_pcf(s, radius, FILTER_TAPS, angle + 1.0, gradient);
}

// ANCHOR: filament_pcss
// Filament (google/filament, shaders/src/surface_shadowing.fs,
// ShadowSample_PCSS): the first 16 points of its 64-point Poisson disk, the
// only ones its PCSS reads; they all lie in the upper half of the disk
// (every y > 0.036), turned per pixel by interleaved gradient noise.
const FILAMENT_POISSON_16 = array<vec2<f32>, 16>(
    vec2<f32>(0.511749, 0.547686), vec2<f32>(0.58929, 0.257224), vec2<f32>(0.165018, 0.57663), vec2<f32>(0.407692, 0.742285),
    vec2<f32>(0.707012, 0.646523), vec2<f32>(0.31463, 0.466825), vec2<f32>(0.801257, 0.485186), vec2<f32>(0.418136, 0.146517),
    vec2<f32>(0.579889, 0.0368284), vec2<f32>(0.79801, 0.140114), vec2<f32>(-0.0413185, 0.371455), vec2<f32>(-0.0529108, 0.627352),
    vec2<f32>(0.0821375, 0.882071), vec2<f32>(0.17308, 0.301207), vec2<f32>(-0.120452, 0.867216), vec2<f32>(0.371096, 0.916454),
);
const FILAMENT_PCSS_TAPS: u32 = 16u;

// Filament's penumbra ratio (getPenumbraRatio) on its reversed depths: for a
// directional light (z_b − z_r) / (1 − z_b); for a spot, whose depths go as
// 1/d, (k + z_b) / (k + z_r) − 1 with k = near / (far − near).
fn filament_penumbra_ratio(z_r: f32, z_b: f32) -> f32 {
    if soft.perspective == 0u {
        return (z_b - z_r) / (1.0 - z_b);
    }
    let k = soft.near / (soft.far - soft.near);
    return (k + z_b) / (k + z_r) - 1.0;
}

fn filament_pcss(s: vec3<f32>, pixel: vec2<f32>, gradient: vec2<f32>) -> f32 {
    let a = rotation_angle(pixel);
    let r = mat2x2<f32>(cos(a), sin(a), -sin(a), cos(a));
    // penumbraLs: the bulb's radius in map units (at the receiver's depth
    // along the axis, for a spot).
    var penumbra = soft.size * soft.uv_per;
    if soft.perspective == 1u {
        penumbra = penumbra / light_distance(s.z);
    }
    let z_rec = 1.0 - s.z;
    // blockerSearchAndFilter: the blockers' reversed depths, summed.
    var occluded = 0.0;
    var z_occ_sum = 0.0;
    for (var i = 0u; i < FILAMENT_PCSS_TAPS; i++) {
        let duv = r * (FILAMENT_POISSON_16[i] * penumbra);
        let z_occ = 1.0 - depth_nearest(s.xy + duv);
        // Receiver plane bias: the reversed depth falls where ours rises.
        let z_bias = -dot(gradient, duv);
        let o = select(0.0, 1.0, z_occ - z_rec >= z_bias);
        occluded += o;
        z_occ_sum += z_occ * o;
    }
    if z_occ_sum == 0.0 {
        return 1.0;
    }
    let ratio = filament_penumbra_ratio(z_rec, z_occ_sum / occluded);
    // filterPCSS: each tap a 2×2 bilinear comparison, the same points.
    var lit = 0.0;
    for (var i = 0u; i < FILAMENT_PCSS_TAPS; i++) {
        let duv = r * (FILAMENT_POISSON_16[i] * (penumbra * ratio));
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + duv, s.z + dot(gradient, duv));
    }
    return lit / f32(FILAMENT_PCSS_TAPS);
}
// ANCHOR_END: filament_pcss

// ANCHOR: bevy_pcss
// Bevy (bevyengine/bevy, crates/bevy_pbr/src/render/shadow_sampling.wgsl,
// sample_shadow_map_pcss, as fetch_spot_shadow calls it): a spot's depth is
// reversed and infinite, near_z / d, so (z_b − z) / z is (d_r − d_b) / d_b;
// the search and the filter are sized in its own units.
const BEVY_SPOT_SHADOW_TEXEL_SIZE: f32 = 0.0134277345;
const BEVY_D3D_SAMPLE_POINT_POSITIONS = array<vec2<f32>, 8>(
    vec2<f32>(0.125, -0.375), vec2<f32>(-0.125, 0.375), vec2<f32>(0.625, 0.125), vec2<f32>(-0.375, -0.625),
    vec2<f32>(-0.625, 0.625), vec2<f32>(-0.875, -0.125), vec2<f32>(0.375, 0.875), vec2<f32>(0.875, -0.875),
);
const BEVY_SPIRAL_OFFSETS = array<vec2<f32>, 8>(
    vec2<f32>(-0.7071, 0.7071), vec2<f32>(-0.0000, -0.8750), vec2<f32>(0.5303, 0.5303), vec2<f32>(-0.6250, -0.0000),
    vec2<f32>(0.3536, -0.3536), vec2<f32>(-0.0000, 0.3750), vec2<f32>(-0.1768, -0.1768), vec2<f32>(0.1250, 0.0000),
);
// Bevy's near plane for point and spot lights (its depth is near_z / d).
const BEVY_NEAR_Z: f32 = 0.1;

fn bevy_depth(z: f32) -> f32 {
    return BEVY_NEAR_Z / light_distance(z);
}

// `map` in shadow_sampling.wgsl: value from [min1, max1] to [min2, max2].
fn bevy_map(min1: f32, max1: f32, min2: f32, max2: f32, value: f32) -> f32 {
    return min2 + (value - min1) * (max2 - min2) / (max1 - min1);
}

// interleaved_gradient_noise (bevy_pbr utils.wgsl) with frame 1, as
// random_rotation_matrix passes it when not temporal.
fn bevy_rotation(pixel: vec2<f32>) -> mat2x2<f32> {
    let xy = pixel + 5.588238 * f32(1u % 64u);
    let noise = fract(52.9829189 * fract(0.06711056 * xy.x + 0.00583715 * xy.y));
    let angle = 2.0 * 3.1415926535897932 * noise;
    let m = vec2<f32>(sin(angle), cos(angle));
    return mat2x2<f32>(m.y, -m.x, m.x, m.y);
}

fn bevy_pcss(s: vec3<f32>, pixel: vec2<f32>) -> f32 {
    let light_size = soft.size;
    let texel_size = BEVY_SPOT_SHADOW_TEXEL_SIZE;
    let shadow_map_size = f32(textureDimensions(shadow_map).x);
    let depth = bevy_depth(s.z);
    // search_for_blockers_in_shadow_map: 8 linear-filtered depths, a blocker
    // where the depth is nearer (reversed: greater or equal). Our depth is
    // affine in 1/d, so its bilinear blend is the blend of Bevy's.
    let search_scale = light_size / (texel_size * shadow_map_size);
    var sum = vec2<f32>(0.0);
    for (var i = 0u; i < 8u; i++) {
        let sampled = bevy_depth(depth_bilinear(s.xy + BEVY_D3D_SAMPLE_POINT_POSITIONS[i] * search_scale));
        sum += select(vec2<f32>(0.0), vec2<f32>(sampled, 1.0), sampled >= depth);
    }
    var z_blocker = 0.0;
    if sum.y != 0.0 {
        z_blocker = sum.x / sum.y;
    }
    // "Don't let the blur size go below 0.5": no blocker gives 0.5 too.
    let blur_size = max((z_blocker - depth) * light_size / depth, 0.5);
    // sample_shadow_map_jimenez_fourteen: 8 spiral taps, each a 2×2
    // hardware comparison, spaced by Bevy's fudge factor.
    let f = bevy_map(0.00390625, 0.022949219, 0.015, 0.035, texel_size);
    let uv_offset_scale = f * blur_size / (texel_size * shadow_map_size);
    let rotation = bevy_rotation(pixel);
    var lit = 0.0;
    for (var i = 0u; i < 8u; i++) {
        let offset = (rotation * BEVY_SPIRAL_OFFSETS[i]) * uv_offset_scale;
        lit += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + offset, s.z);
    }
    return lit / 8.0;
}
// ANCHOR_END: bevy_pcss

// ANCHOR: godot_soft
// Godot 4's positional and directional soft shadows (godotengine/godot,
// scene_forward_lights_inc.glsl): `taps` Vogel-disk taps to search and the
// same taps to filter, both turned per pixel, no receiver-plane bias.
// Its Vogel disk (renderer_scene_render_rd.cpp get_vogel_disk): golden
// angle 2.4, radius sqrt(i + 0.5) / sqrt(n).
fn godot_vogel(i: u32, n: u32) -> vec2<f32> {
    let r = sqrt(f32(i) + 0.5) / sqrt(f32(n));
    let theta = f32(i) * 2.4;
    return vec2<f32>(cos(theta) * r, sin(theta) * r);
}

fn godot_rotation(pixel: vec2<f32>) -> mat2x2<f32> {
    let r = rotation_angle(pixel);
    return mat2x2<f32>(vec2<f32>(cos(r), -sin(r)), vec2<f32>(sin(r), cos(r)));
}

fn godot_soft(s: vec3<f32>, pixel: vec2<f32>) -> f32 {
    let rotation = godot_rotation(pixel);
    let n = SEARCH_TAPS;
    // Reversed depth, as Godot's atlas holds it.
    let z = 1.0 - s.z;
    var uv_size: vec2<f32>;
    var z_norm = z;
    if soft.perspective == 1u {
        // A spot (light_process_spot): soft_shadow_size · z_norm ·
        // soft_shadow_scale, z_norm the distance along the axis over the
        // range; its penumbra then mixes this linear z_norm with the
        // reversed perspective depths, as the source does.
        z_norm = light_distance(s.z) / soft.far;
        uv_size = vec2<f32>(soft.size * z_norm * soft.scale);
    } else {
        // A directional light (the call of sample_directional_soft_shadow):
        // uv_scale · (range_pos − range_begin) · softshadow_angle ·
        // soft_shadow_scale, the cone's spread from the map's near plane.
        uv_size = soft.uv_per * (light_distance(s.z) - soft.near) * soft.size * soft.scale;
    }
    var blocker_count = 0.0;
    var blocker_average = 0.0;
    for (var i = 0u; i < n; i++) {
        let suv = s.xy + (rotation * godot_vogel(i, n)) * uv_size;
        let d = 1.0 - depth_bilinear(suv);
        if d > z {
            blocker_average += d;
            blocker_count += 1.0;
        }
    }
    if blocker_count == 0.0 {
        return 1.0;
    }
    blocker_average /= blocker_count;
    // A spot compares the linear z_norm with the reversed depths; a
    // directional light its reversed depth.
    let penumbra = (-z_norm + blocker_average) / (1.0 - blocker_average);
    uv_size *= penumbra;
    var shadow = 0.0;
    for (var i = 0u; i < n; i++) {
        let suv = s.xy + (rotation * godot_vogel(i, n)) * uv_size;
        shadow += textureSampleCompareLevel(shadow_map, shadow_compare, suv, s.z);
    }
    return shadow / f32(n);
}
// ANCHOR_END: godot_soft
// ANCHOR: three_pcf_soft
// three.js's PCFSoftShadowMap (shadowmap_pars_fragment.glsl.js at
// 99e4d38, SHADOWMAP_TYPE_PCF_SOFT; r182 deprecates it): 16 nearest
// comparisons on the 4×4 texel block around the point (the lesson binds
// the nearest-filtering comparison sampler for it), the outer rows and
// columns weighted by the point's fraction f within its texel: a
// 3×3-texel box, bilinearly smoothed, divided by 9. It has no light size:
// a fixed kernel. Every tap compares with the point's own depth: three.js
// draws the casters' back faces into the map, so a lit surface does not
// meet its own depth there.
fn three_pcf_soft(s: vec3<f32>) -> f32 {
    let size = vec2<f32>(textureDimensions(shadow_map));
    let texel = 1.0 / size;
    let f = fract(s.xy * size + 0.5);
    let uv = s.xy - f * texel;
    var sum = 0.0;
    for (var j = 0; j < 4; j++) {
        for (var i = 0; i < 4; i++) {
            let o = (vec2<f32>(f32(i), f32(j)) - 1.0) * texel;
            var w = 1.0;
            if i == 0 { w *= 1.0 - f.x; }
            if i == 3 { w *= f.x; }
            if j == 0 { w *= 1.0 - f.y; }
            if j == 3 { w *= f.y; }
            sum += w * textureSampleCompareLevel(shadow_map, shadow_compare, uv + o, s.z);
        }
    }
    return sum / 9.0;
}
// ANCHOR_END: three_pcf_soft

// ANCHOR: threejs_vsm
// three.js's VSM getShadow (r182, shadowmap_pars_fragment.glsl.js): `m`
// holds the blurred (mean, standard deviation) of the map's own depth; a
// hard test first, then Chebyshev's bound on a variance of at least 1e-7,
// cut by (p − 0.3) / 0.65, i.e. linstep(0.3, 0.95, p), the larger of the two.
fn threejs_vsm(s: vec3<f32>, m: vec4<f32>) -> f32 {
    let mean = m.x;
    var variance = m.y * m.y;
    let hard_shadow = step(s.z, mean);
    if hard_shadow == 1.0 {
        return 1.0;
    }
    variance = max(variance, 0.0000001);
    let d = s.z - mean;
    var p_max = variance / (variance + d * d);
    p_max = clamp((p_max - soft.bleed_lo) / (soft.bleed_hi - soft.bleed_lo), 0.0, 1.0);
    return max(hard_shadow, p_max);
}
// ANCHOR_END: threejs_vsm

// ANCHOR: filament_pcf
// Filament's default, ShadowType::PCF (surface_shadowing.fs,
// ShadowSample_PCF_Low, "hardware assisted PCF + 3x3 gaussian filter",
// Castaño 2013): 4 bilinear comparisons, weighted, over 16. Filament's
// lines and names, our forward depth in its reversed place.
fn filament_pcf_low(position: vec3<f32>) -> f32 {
    let size = vec2<f32>(textureDimensions(shadow_map));
    let texel_size = vec2<f32>(1.0) / size;
    let depth = position.z;
    let offset = vec2<f32>(0.5);
    let uv = (clamp(position.xy, vec2<f32>(-1.0), vec2<f32>(2.0)) * size) + offset;
    let base = (floor(uv) - offset) * texel_size;
    let st = fract(uv);
    let uw = vec2<f32>(3.0 - 2.0 * st.x, 1.0 + 2.0 * st.x);
    let vw = vec2<f32>(3.0 - 2.0 * st.y, 1.0 + 2.0 * st.y);
    var u = vec2<f32>((2.0 - st.x) / uw.x - 1.0, st.x / uw.y + 1.0);
    var v = vec2<f32>((2.0 - st.y) / vw.x - 1.0, st.y / vw.y + 1.0);
    u *= texel_size.x;
    v *= texel_size.y;
    var sum = 0.0;
    sum += uw.x * vw.x * textureSampleCompareLevel(shadow_map, shadow_compare, base + vec2<f32>(u.x, v.x), depth);
    sum += uw.y * vw.x * textureSampleCompareLevel(shadow_map, shadow_compare, base + vec2<f32>(u.y, v.x), depth);
    sum += uw.x * vw.y * textureSampleCompareLevel(shadow_map, shadow_compare, base + vec2<f32>(u.x, v.y), depth);
    sum += uw.y * vw.y * textureSampleCompareLevel(shadow_map, shadow_compare, base + vec2<f32>(u.y, v.y), depth);
    return sum * (1.0 / 16.0);
}
// ANCHOR_END: filament_pcf

// ANCHOR: godot_pcf
// Godot's default, a light of size 0 (scene_forward_lights_inc.glsl,
// sample_pcf_shadow): `taps` bilinear comparisons on its Vogel disk
// (soft_shadow_kernel), turned per pixel by quick_hash, on a disk of
// soft_shadow_scale (shadow_blur × the quality's radius) texels, averaged.
fn godot_pcf(s: vec3<f32>, pixel: vec2<f32>) -> f32 {
    let n = FILTER_TAPS;
    let texel = 1.0 / vec2<f32>(textureDimensions(shadow_map));
    let shadow_pixel_size = soft.scale * texel;
    let disk_rotation = godot_rotation(pixel);
    var avg = 0.0;
    for (var i = 0u; i < n; i++) {
        avg += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + shadow_pixel_size * (disk_rotation * godot_vogel(i, n)), s.z);
    }
    return avg * (1.0 / f32(n));
}
// ANCHOR_END: godot_pcf

// ANCHOR: three_pcf
// three.js's default, PCFShadowMap (r182, shadowmap_pars_fragment.glsl.js):
// 5 bilinear comparisons on its Vogel disk (golden angle 2.399963229728653,
// r = sqrt((i + 0.5) / 5)), turned per pixel by interleaved gradient noise,
// on a disk of `radius` (1) texel, × 0.2.
fn three_vogel(i: u32, n: u32, phi: f32) -> vec2<f32> {
    let golden_angle = 2.399963229728653;
    let r = sqrt((f32(i) + 0.5) / f32(n));
    let theta = f32(i) * golden_angle + phi;
    return vec2<f32>(cos(theta), sin(theta)) * r;
}

fn three_pcf(s: vec3<f32>, pixel: vec2<f32>) -> f32 {
    let texel_size = vec2<f32>(1.0) / vec2<f32>(textureDimensions(shadow_map));
    let radius = 1.0 * texel_size.x;
    let phi = fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715)))) * 6.28318530718;
    var shadow = 0.0;
    for (var i = 0u; i < 5u; i++) {
        shadow += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + three_vogel(i, 5u, phi) * radius, s.z);
    }
    return shadow * 0.2;
}
// ANCHOR_END: three_pcf
