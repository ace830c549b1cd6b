// lesson_10/min_max.wgsl: the shadow map's min/max mip chain (Dmitriev and
// Uralsky, "Soft shadows in games", GDC 2007): level 1 holds, for each 2×2
// block of the map, its nearest and its farthest depth; level l, those of
// each 2^l × 2^l block, made from level l − 1's 2×2. One compute pass per
// level, into one storage buffer of (min, max) pairs, level after level
// (Rust: lessons/lesson_10/min_max.rs). The lit pass reads it in
// soft.wgsl's `region_min_max`.

// Level 1 reads the map itself; every other level, the level below.
override FROM_DEPTH: bool = false;

// Rust: min_max.rs `LevelUniform`: where the level below starts in the
// buffer, where this one starts, and its side (the map's side >> level).
struct Level {
    below: u32,
    start: u32,
    side: u32,
    _pad: u32,
};
@group(0) @binding(0) var depth: texture_2d<f32>;
@group(0) @binding(1) var<storage, read> level: Level;
@group(0) @binding(2) var<storage, read_write> chain: array<vec2<f32>>;

// ANCHOR: reduce
@compute @workgroup_size(8, 8)
fn cs_reduce(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(level.side)) {
        return;
    }
    var lo = 1e30;
    var hi = -1e30;
    for (var k = 0u; k < 4u; k++) {
        let p = 2u * id.xy + vec2<u32>(k & 1u, k >> 1u);
        var m: vec2<f32>;
        if FROM_DEPTH {
            let d = textureLoad(depth, p, 0).r;
            m = vec2<f32>(d, d);
        } else {
            m = chain[level.below + p.y * 2u * level.side + p.x];
        }
        lo = min(lo, m.x);
        hi = max(hi, m.y);
    }
    chain[level.start + id.y * level.side + id.x] = vec2<f32>(lo, hi);
}
// ANCHOR_END: reduce
