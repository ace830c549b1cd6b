// shadow_volume.wgsl: the geometry of stencil shadow volumes (lessons 05-08).
// Appended to common.wgsl (camera, light, object); a lesson may append more.
//
// Two ways to build a volume, one vertex shader each:
// - vs_volume_cpu: the CPU found the silhouette (as Doom 3 did) and sends
//   (position, w): w = 1 stays where it is, w = 0 goes to infinity, and
//   0 < w < 1 goes 1/w times as far from the light (lesson 06, finite far).
// - vs_volume_quads: every edge was turned into a degenerate quad in
//   advance; the vertex shader adds up, from the normals of the edge's
//   faces, the edge's silhouette count, and opens the quad or collapses it.

struct VolumeOut {
    // invariant: the front cap must land on exactly the base pass's depths.
    @invariant @builtin(position) clip: vec4<f32>,
};

// ANCHOR: extrude_to_infinity
// A world point pushed away from the light, to infinity. w = 0 makes the
// result a direction: the projection sends it to the vanishing point.
fn extrude_to_infinity(world: vec3<f32>) -> vec4<f32> {
    if light.position_or_dir.w == 0.0 {
        // Directional: every point goes to the same point at infinity.
        return vec4<f32>(light.position_or_dir.xyz, 0.0);
    }
    // Point and spot: straight away from the light.
    return vec4<f32>(world - light.position_or_dir.xyz, 0.0);
}

// The clip position of a point at infinity. Under an exact infinite
// projection (glam's, which `far = "infinite"` scenes get) it lands on the
// far boundary, z = w, depth 1, with no margin: rounding can put it a hair
// outside, where it is clipped away and a back cap or side silently
// vanishes. Such points get the margin of lesson 07's infinite projection,
// depth 1 − ε with the same ε (`INFINITE_EPSILON`, 2⁻²²; a test keeps the
// two equal), as in the "nudged" projection of Everitt and Kilgard. A
// projection that already has the margin (lesson 07's) is left as it is,
// so there its ε decides; under a finite far plane z is well beyond w and
// this leaves it alone too (lesson 07's depth clamp handles that).
const INFINITE_EPSILON: f32 = 2.384185791015625e-7;

fn project_to_infinity(world: vec3<f32>) -> vec4<f32> {
    var clip = camera.view_proj * extrude_to_infinity(world);
    if abs(clip.z - clip.w) <= 1e-5 * abs(clip.w) {
        clip.z = min(clip.z, clip.w * (1.0 - INFINITE_EPSILON));
    }
    return clip;
}
// ANCHOR_END: extrude_to_infinity

// ANCHOR: extrude_to_reach
// A world point X pushed away from a point or spot light by the factor s = 1/w:
// L + s (X − L), written homogeneously as (X − L + w L, w). w = 0 is the
// point at infinity above; 0 < w < 1 a finite point, so the volume ends at a
// finite back cap, the caster's light-facing faces scaled by s about the
// light (lesson 06 under a finite far plane). The reach w is the same for
// every vertex of one caster's volume, so its pieces still meet.
fn project_extruded(world: vec3<f32>, w: f32) -> vec4<f32> {
    if w == 0.0 || light.position_or_dir.w == 0.0 {
        return project_to_infinity(world);
    }
    let l = light.position_or_dir.xyz;
    return camera.view_proj * vec4<f32>(world - l + w * l, w);
}
// ANCHOR_END: extrude_to_reach

// ANCHOR: vs_volume_cpu
@vertex
fn vs_volume_cpu(@location(0) position: vec3<f32>, @location(1) w: f32) -> VolumeOut {
    var out: VolumeOut;
    // The same expression as vs_scene, so finite vertices get the same depth.
    let world = object.model * vec4<f32>(position, 1.0);
    if w == 1.0 {
        out.clip = camera.view_proj * world;
    } else {
        out.clip = project_extruded(world.xyz, w);
    }
    return out;
}
// ANCHOR_END: vs_volume_cpu

// ANCHOR: faces_light
// Which side of a face (unnormalised object-space normal n, a point p0 on
// it) the light is on: > 0 in front. In world space through the normal
// matrix, which keeps the normal pointing out even when the model mirrors
// (det < 0). Exactly 0 is "not facing", so a degenerate face (n = 0)
// never faces the light, and neither does its twin.
fn light_side(n: vec3<f32>, p0: vec3<f32>) -> f32 {
    let nw = (object.normal_matrix * vec4<f32>(n, 0.0)).xyz;
    if light.position_or_dir.w == 0.0 {
        return dot(nw, -light.position_or_dir.xyz);
    }
    let pw = (object.model * vec4<f32>(p0, 1.0)).xyz;
    return dot(nw, light.position_or_dir.xyz - pw);
}

// One face's share of its edge's count: `runs` (+1 along the edge, −1
// against it, 0 no face) if the face faces the light; −runs if it is
// two-sided and its reversed twin faces the light (the twin's normal is
// exactly −n, so that is side < 0); else 0.
fn face_count(runs: i32, two_sided: u32, n: vec3<f32>, p0: vec3<f32>) -> i32 {
    let side = light_side(n, p0);
    if side > 0.0 {
        return runs;
    }
    if two_sided == 1u && side < 0.0 {
        return -runs;
    }
    return 0;
}
// ANCHOR_END: faces_light

// ANCHOR: quad_in
// Every vertex of an edge's quad carries the edge's faces (two at most), so
// all four add up the same count, as the CPU's silhouette_edges does.
// Copy k of the quad is drawn where |count| > k: its near corners stay,
// its far corners go to infinity, and a negative count swaps the quad's
// two ends (position <-> reversed), which reverses its winding. Elsewhere
// all four corners collapse to one point: zero area, nothing drawn. A cap
// triangle is the same with one face (runs = +1): the front cap stays, the
// back cap goes to infinity, and a two-sided face's cap is drawn by the
// side that faces the light.
//
// Rust: lessons/lesson_05/quads.rs `QuadVertex`; `flags` packs the small
// fields (`QuadFlags`): bit 0 far, bits 1–3 copy, bits 4–5 and 6–7 each
// face's runs + 1, bits 8 and 9 each face's two-sidedness.
struct QuadIn {
    @location(0) position: vec3<f32>,
    @location(1) flags: u32,
    @location(2) reversed: vec3<f32>,
    @location(3) normal_0: vec3<f32>,
    @location(4) normal_1: vec3<f32>,
    @location(5) point_0: vec3<f32>,
    @location(6) point_1: vec3<f32>,
};

fn quad_runs(flags: u32, k: u32) -> i32 {
    return i32((flags >> (4u + 2u * k)) & 3u) - 1;
}

fn quad_two_sided(flags: u32, k: u32) -> u32 {
    return (flags >> (8u + k)) & 1u;
}
// ANCHOR_END: quad_in

// ANCHOR: vs_volume_quads
@vertex
fn vs_volume_quads(v: QuadIn) -> VolumeOut {
    return volume_quad_vertex(v, 0.0);
}

fn volume_quad_vertex(v: QuadIn, reach_w: f32) -> VolumeOut {
    var out: VolumeOut;
    let count = face_count(quad_runs(v.flags, 0u), quad_two_sided(v.flags, 0u), v.normal_0, v.point_0)
        + face_count(quad_runs(v.flags, 1u), quad_two_sided(v.flags, 1u), v.normal_1, v.point_1);
    let copy = (v.flags >> 1u) & 7u;
    if abs(count) <= i32(copy) {
        out.clip = vec4<f32>(0.0, 0.0, 0.0, 1.0); // collapsed
        return out;
    }
    let p = select(v.position, v.reversed, count < 0);
    let world = object.model * vec4<f32>(p, 1.0);
    if (v.flags & 1u) == 0u {
        // The same expression as vs_scene: the front cap lands on its depths.
        out.clip = camera.view_proj * world;
    } else {
        out.clip = project_extruded(world.xyz, reach_w);
    }
    return out;
}
// ANCHOR_END: vs_volume_quads

// ANCHOR: vs_volume_quads_reach
// The same, extruded by the factor 1/reach_w (see project_extruded):
// reach_w is one value per caster and light, from a per-instance buffer.
@vertex
fn vs_volume_quads_reach(v: QuadIn, @location(10) reach_w: f32) -> VolumeOut {
    return volume_quad_vertex(v, reach_w);
}
// ANCHOR_END: vs_volume_quads_reach

// The fragment-counting copy of the volume pass writes one throw-away
// value, so that every rasterised fragment runs (and counts) a shader.
@fragment
fn fs_volume_count() -> @location(0) vec4<f32> {
    return vec4<f32>(1.0);
}

// ANCHOR: fs_stencil_lit
// The lit pass of a stencil technique: the stencil test (count == 0) has
// already decided; a fragment that gets here is lit.
@fragment
fn fs_stencil_lit(in: VertexOut) -> LitOut {
    return lit_output(in, 1.0);
}
// ANCHOR_END: fs_stencil_lit
