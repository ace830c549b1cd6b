// lesson_02 exercises: the reference solutions (the starter is
// shaders/lesson_02/exercises.wgsl, with the same functions).

// ANCHOR: slope_bias
fn slope_bias(cos_t: f32) -> f32 {
    // tan θ from cos θ; the 1e-4 keeps it finite at 90°.
    let tan_t = sqrt(1.0 - cos_t * cos_t) / max(cos_t, 1e-4);
    // A tenth of a texel, plus tan θ texels (twice the tan θ / 2 that a
    // texel's depth error needs), clamped only where tan θ runs away
    // (θ above 89°): a clamp of a few texels brings the acne back at 85°.
    return 0.1 + min(tan_t, 64.0);
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
    let margin = 2e-6 + 0.5 * (abs(g.x) + abs(g.y)) / size.x;
    return vec3<f32>(s.xy, z_centre - margin);
}
// ANCHOR_END: grazing_bias
