// lesson_10/exercises.wgsl: the chapter's exercises, the starter code.
// Appended to soft.wgsl: light_distance, vogel, Blockers and the `soft`
// parameters are there. The variants exercise_blocker_search and
// exercise_penumbra run PCSS with one of these in place of the lesson's own,
// each in a module without the lesson's function it replaces: calling
// blocker_search (or filter_radius) there calls your own function, which
// WGSL refuses (lessons/lesson_10/exercise_shaders.rs).

// ANCHOR: blocker_search
// Exercise 1: the blocker search. Of `soft.search_taps` taps on a disk of
// `radius` (map units) around s.xy, turned by `angle` (vogel(i, n, angle)),
// return how many see a depth in front of the receiver's plane there
// (s.z + dot(gradient, o)), and their mean distance from the light
// (light_distance of each depth read with textureLoad from shadow_depths).
fn exercise_blocker_search(s: vec3<f32>, radius: vec2<f32>, angle: f32, gradient: vec2<f32>) -> Blockers {
    // Starter: one tap at the centre.
    let size = vec2<f32>(textureDimensions(shadow_depths));
    let texel = clamp(vec2<i32>(floor(s.xy * size)), vec2<i32>(0), vec2<i32>(size) - 1);
    let depth = textureLoad(shadow_depths, texel, 0).r;
    if depth < s.z {
        return Blockers(light_distance(depth), 1u);
    }
    return Blockers(0.0, 0u);
}
// ANCHOR_END: blocker_search

// ANCHOR: filter_radius
// Exercise 2: the penumbra estimate. For a receiver at distance d_r from
// the light and blockers at mean distance d_b, return the PCF's radius in
// map units (u, v): the footprint of the emitter on the blockers' plane,
// seen from the receiver. soft.perspective says which light: 0 a cone of
// directions (soft.size = tan of its half-angle, soft.uv_per = map units
// per world unit), 1 a disk of radius soft.size at the light (soft.uv_per =
// map units per radian).
fn exercise_filter_radius(d_r: f32, d_b: f32) -> vec2<f32> {
    // Starter: a fixed 4 texels, whatever the light and the blockers.
    return vec2<f32>(4.0 / f32(textureDimensions(shadow_map).x));
}
// ANCHOR_END: filter_radius
