// lesson_02 exercises answered HALF RIGHT (tests/half_right/lesson_02.rs):
// each function has the mistake its comment names, which the grader must
// fail with that likely cause.

// ANCHOR: slope_bias
fn slope_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let s = shadow_coords(world);
    // One pixel's step across the screen, taken in world units and mapped:
    // (du, dv, dz). Not dpdx(s): s comes from the light's matrix, read from
    // a storage buffer, and on lavapipe its finite differences came out
    // wrong (acne over whole lit faces; chapter 03 meets the same).
    let dx = shadow_coords(world + dpdxFine(world)) - s;
    let dy = shadow_coords(world + dpdyFine(world)) - s;
    // g · dx.xy = dx.z and g · dy.xy = dy.z (Cramer's rule). The
    // determinant is 0 only where the map sees the triangle edge-on.
    let det = dx.x * dy.y - dx.y * dy.x;
    if abs(det) < 1e-30 {
        return s;
    }
    let g = vec2<f32>(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det;
    // The texel's centre is at most half a texel away in u and in v: the
    // plane's depth differs there by up to (|g_u| + |g_v|) / 2N. Twice
    // that, plus a little for rounding; no clamp: g is the triangle's own.
    let size = f32(textureDimensions(shadow_map).x);
    // THE MISTAKE: the slope along u only; a receiver that slopes along v
    // (seen by the light at a grazing angle that way) keeps its acne.
    return vec3<f32>(s.xy, s.z - 2e-6 - 2.0 * abs(g.x) / size);
}
// ANCHOR_END: slope_bias

// ANCHOR: grazing_bias
// Receiver-plane depth bias. The nearest texel stores the depth of what the
// light sees at the texel's CENTRE, not at the receiver: compare with the
// receiver's own plane extended to that centre, and acne (the half texel of
// slope) is gone without lifting the receiver. What is left is a margin of
// half a texel's depth change, for curved meshes (their interpolated normal
// is not their triangle's plane) and rounding: a third of a slope-scaled
// bias, so casters 3 times thinner keep their shadows.
fn grazing_bias(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let s = shadow_coords(world);
    // Two steps of one texel inside the receiver's plane, and where they
    // land on the map: (du, dv, dz) each.
    let texel = shadow_texel_size(world, n);
    var a = cross(n, vec3<f32>(0.0, 1.0, 0.0));
    if length(a) < 0.1 {
        a = cross(n, vec3<f32>(1.0, 0.0, 0.0));
    }
    a = normalize(a) * texel;
    let b = normalize(cross(n, a)) * texel;
    let da = shadow_coords(world + a) - s;
    let db = shadow_coords(world + b) - s;
    // The plane's depth gradient g = (dz/du, dz/dv): solve
    // g · da.xy = da.z and g · db.xy = db.z (Cramer's rule).
    let det = da.x * db.y - da.y * db.x;
    if abs(det) < 1e-20 {
        return s; // the light sees the plane edge-on: no receiver
    }
    let g = vec2<f32>(db.y * da.z - da.y * db.z, da.x * db.z - db.x * da.z) / det;
    // The centre of the texel that nearest filtering reads, and the plane's
    // depth there.
    let size = vec2<f32>(textureDimensions(shadow_map));
    let centre = (floor(s.xy * size) + 0.5) / size;
    let z_centre = s.z + dot(g, centre - s.xy);
    // THE MISTAKE: the receiver's plane at the texel's centre, and on top
    // of it the slope-scaled bias of exercise 1 as well: the receiver is
    // lifted past a thin caster again.
    let margin = 2e-6 + 2.0 * (abs(g.x) + abs(g.y)) / size.x;
    return vec3<f32>(s.xy, z_centre - margin);
}
// ANCHOR_END: grazing_bias
