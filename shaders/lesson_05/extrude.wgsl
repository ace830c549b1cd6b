// extrude.wgsl: shadow volumes built by a compute shader (lesson 05,
// `Extrusion::Compute`, `lessons/lesson_05/compute.rs`).
//
// One invocation per edge and one per face of one chunk of a caster (a
// run of its edges and faces, `lessons/lesson_05/compute/chunks.rs`), for
// one light.
// It is the CPU route (`cpu_volume`) ported line for line: the same facing
// test, the same silhouette rule, the same vertices `(position, w)`, so
// `vs_volume_cpu` draws them unchanged. Only the order of the triangles
// differs (invocations append with atomicAdd), and the stencil count does
// not depend on the order.

struct Params {
    // Object space: xyz the point light's position, or the direction a
    // directional light travels; w = 1 point (and spot), 0 directional.
    light: vec4<f32>,
    // The w of extruded vertices: 0 is infinity (lesson 06's reach).
    reach_w: f32,
    edges: u32,
    faces: u32,
    // This (light, chunk)'s three draws in `args`: slot * 3 + 0, 1, 2.
    slot: u32,
    // Where each table starts in `mesh` (in u32 words).
    off_positions: u32,
    off_normals: u32,
    off_triangles: u32,
    off_edges: u32,
    off_edge_faces: u32,
    // Invocations per row of the dispatch (a 2-D grid past 65535 groups).
    row: u32,
    _pad0: u32,
    _pad1: u32,
};

// wgpu::util::DrawIndirectArgs, with the vertex count appended to.
struct DrawArgs {
    vertex_count: atomic<u32>,
    instance_count: u32,
    first_vertex: u32,
    first_instance: u32,
};

@group(0) @binding(0) var<uniform> params: Params;
// One chunk's adjacency, uploaded once: positions (3 f32 bits), face
// normals (3 f32 bits), triangles (3 ids), edges (v0, v1, first face use,
// uses), face uses (face << 1 | runs v0 → v1). Ids are the chunk's own; its
// `faces` own faces come first, the others are only tested for facing.
@group(0) @binding(1) var<storage, read> mesh: array<u32>;
// CpuVertex: (object-space position, w); this (light, chunk)'s own buffer.
@group(0) @binding(2) var<storage, read_write> volume: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> args: array<DrawArgs>;

const SIDES: u32 = 0u;
const FRONT_CAP: u32 = 1u;
const BACK_CAP: u32 = 2u;

fn vec3_at(offset: u32) -> vec3<f32> {
    return vec3<f32>(
        bitcast<f32>(mesh[offset]),
        bitcast<f32>(mesh[offset + 1u]),
        bitcast<f32>(mesh[offset + 2u]),
    );
}

fn position(v: u32) -> vec3<f32> {
    return vec3_at(params.off_positions + 3u * v);
}

fn triangle(f: u32) -> vec3<u32> {
    let o = params.off_triangles + 3u * f;
    return vec3<u32>(mesh[o], mesh[o + 1u], mesh[o + 2u]);
}

fn is_point_light() -> bool {
    return params.light.w != 0.0;
}

// ANCHOR: face_facing
// `face_facing` of silhouette.rs: n · (p − v0) > 0, or n · (−d) > 0, with
// the unnormalised normal; exactly 0 is not facing. The dot product is
// written out in the CPU's order ((x + y) + z).
fn face_facing(f: u32) -> bool {
    let n = vec3_at(params.off_normals + 3u * f);
    var to_light = -params.light.xyz;
    if is_point_light() {
        to_light = params.light.xyz - position(triangle(f).x);
    }
    return n.x * to_light.x + n.y * to_light.y + n.z * to_light.z > 0.0;
}
// ANCHOR_END: face_facing

// Reserves `count` vertices in one of this slot's draws; returns where they go.
fn append(part: u32, count: u32) -> u32 {
    let a = params.slot * 3u + part;
    return args[a].first_vertex + atomicAdd(&args[a].vertex_count, count);
}

// ANCHOR: extrude_edge
// `silhouette_edges_for`: +1 for each lit face running v0 → v1, −1 for each
// running v1 → v0; the edge is a side |sum| times, oriented by the sign.
fn extrude_edge(e: u32) {
    let o = params.off_edges + 4u * e;
    let v0 = mesh[o];
    let v1 = mesh[o + 1u];
    var sum = 0i;
    for (var j = 0u; j < mesh[o + 3u]; j++) {
        let use_ = mesh[params.off_edge_faces + mesh[o + 2u] + j];
        if face_facing(use_ >> 1u) {
            sum += select(-1i, 1i, (use_ & 1u) == 1u);
        }
    }
    if sum == 0i {
        return;
    }
    var a = v0;
    var b = v1;
    if sum < 0i {
        a = v1;
        b = v0;
    }
    let copies = u32(abs(sum));
    // Directional: a∞ = b∞, so one triangle per side (cpu_volume's rule).
    let per_side = select(3u, 6u, is_point_light());
    let at = append(SIDES, per_side * copies);
    let pa = position(a);
    let pb = position(b);
    let far = params.reach_w;
    for (var c = 0u; c < copies; c++) {
        let k = at + c * per_side;
        // b → a → a∞ → b∞, as two triangles: outward seen from outside.
        volume[k] = vec4<f32>(pa, 1.0);
        volume[k + 1u] = vec4<f32>(pb, far);
        volume[k + 2u] = vec4<f32>(pb, 1.0);
        if is_point_light() {
            volume[k + 3u] = vec4<f32>(pa, 1.0);
            volume[k + 4u] = vec4<f32>(pa, far);
            volume[k + 5u] = vec4<f32>(pb, far);
        }
    }
}
// ANCHOR_END: extrude_edge

// ANCHOR: cap_face
// The front cap: a light-facing triangle as it is. The back cap: the same
// at infinity, reversed (none for a directional light: it is one point).
fn cap_face(f: u32) {
    if !face_facing(f) {
        return;
    }
    let t = triangle(f);
    let p = array<vec3<f32>, 3>(position(t.x), position(t.y), position(t.z));
    let front = append(FRONT_CAP, 3u);
    for (var i = 0u; i < 3u; i++) {
        volume[front + i] = vec4<f32>(p[i], 1.0);
    }
    if is_point_light() {
        let back = append(BACK_CAP, 3u);
        volume[back] = vec4<f32>(p[0], params.reach_w);
        volume[back + 1u] = vec4<f32>(p[2], params.reach_w);
        volume[back + 2u] = vec4<f32>(p[1], params.reach_w);
    }
}
// ANCHOR_END: cap_face

@compute @workgroup_size(64)
fn extrude(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * params.row;
    if i < params.edges {
        extrude_edge(i);
    } else if i < params.edges + params.faces {
        cap_face(i - params.edges);
    }
}
