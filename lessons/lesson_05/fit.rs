//! Whether each route's buffers fit the adapter (lesson 05): their sizes,
//! counted from the casters' adjacency before anything is built, against
//! the adapter's limits. A route that does not fit is left out with one
//! line that names the limit and the size; the others still run.
//!
//! What each route keeps on the GPU, for a mesh of F faces and E edges:
//!
//! | route | buffer | size |
//! |---|---|---|
//! | `_cpu` | vertices, rewritten every frame | (6 × silhouette edges + 6 × lit faces) × 16 B per light, at worst (6 × E' + 6 F) × 16 B |
//! | `_quads` | vertices and indices, built once | (4 E'' + 6 F) × 76 B + (6 E'' + 6 F) × 4 B |
//! | `_compute` | vertices for the worst case, in chunks | (6 × E' + 6 F) × 16 B per light |
//!
//! E' counts an edge once per face it can be a silhouette for, E'' once per
//! quad ([`quad_sizes`]): E for a closed manifold mesh.
//!
//! The compute route has no row here to fail: it splits each caster into
//! chunks that each bind less than `max_storage_buffer_binding_size`
//! ([`chunks`](super::compute::chunks)), so only the device's memory bounds
//! it (and a device that cannot hold its buffers says so in one line).

use super::adjacency::Adjacency;
#[cfg(doc)]
use super::quads::quad_sizes;
use super::quads::QUAD_VERTEX_BYTES;
use common::gpu::Gpu;

/// Bytes per CPU-route or compute-route vertex (`CpuVertex`).
const CPU_VERTEX_BYTES: u64 = 16;

/// What one limit allows, and what a buffer needs of it.
fn over(gpu: &Gpu, what: &str, bytes: u64, limit: &str, allowed: u64) -> Option<String> {
    (bytes > allowed).then(|| {
        format!(
            "{what} needs {} ({bytes} bytes), more than {} on {} allows ({limit} = {} bytes)",
            mib(bytes),
            gpu.adapter_name(),
            gpu.backend_name(),
            allowed
        )
    })
}

fn mib(bytes: u64) -> String {
    format!("{:.0} MiB", bytes as f64 / (1u64 << 20) as f64)
}

/// Side vertices of `adj` when every edge is a silhouette as often as it
/// can be: per edge, max(faces running one way, the other way), 6 each.
pub fn max_side_vertices(adj: &Adjacency) -> u64 {
    let sides: u64 = (adj.edges.iter())
        .map(|e| {
            let faces = adj.faces_of(e);
            let forward = faces.iter().filter(|f| f.forward).count();
            forward.max(faces.len() - forward) as u64
        })
        .sum();
    6 * sides
}

/// The CPU and compute routes' vertices for every light at once, at worst:
/// every possible silhouette edge, and every face in both caps.
pub fn worst_case_vertices(casters: &[&Adjacency], lights: usize) -> u64 {
    let per_light: u64 = (casters.iter())
        .map(|a| max_side_vertices(a) + 6 * a.triangles.len() as u64)
        .sum();
    per_light * lights as u64
}

/// Why the quads route's buffers would pass a limit, or `None`: each
/// caster's vertex and index buffers (its name and [`quad_sizes`]) against
/// `max_buffer_size`.
pub fn quads_unfit(gpu: &Gpu, casters: &[(&str, (u64, u64))]) -> Option<String> {
    let max = gpu.device.limits().max_buffer_size;
    casters.iter().find_map(|&(name, (vertices, indices))| {
        let what = format!(
            "the quad route's vertex buffer for {name} ({vertices} vertices × {QUAD_VERTEX_BYTES} bytes)"
        );
        over(gpu, &what, vertices * QUAD_VERTEX_BYTES, "max_buffer_size", max).or_else(|| {
            let what = format!("the quad route's index buffer for {name}");
            over(gpu, &what, indices * 4, "max_buffer_size", max)
        })
    })
}

/// Why the CPU route's per-frame vertex buffer could pass
/// `max_buffer_size` (its worst case: every light, every silhouette it can
/// have), or `None`.
pub fn cpu_unfit(gpu: &Gpu, casters: &[(&str, &Adjacency)], lights: usize) -> Option<String> {
    let max = gpu.device.limits().max_buffer_size;
    let adjacency: Vec<&Adjacency> = casters.iter().map(|c| c.1).collect();
    let vertices = worst_case_vertices(&adjacency, lights);
    let what = format!(
        "the CPU route's worst-case vertex buffer ({vertices} vertices × {CPU_VERTEX_BYTES} bytes)"
    );
    over(
        gpu,
        &what,
        vertices * CPU_VERTEX_BYTES,
        "max_buffer_size",
        max,
    )
}
