//! Reading the compute route's output back: the counts its draws used
//! (for the counters), and whole volumes (for the tests, which compare
//! them with the CPU route's triangles).

use anyhow::Result;
use common::gpu::readback::read_buffer_copy;
use common::gpu::Gpu;

use super::super::adjacency::Adjacency;
use super::super::extrusion::CpuVertex;
use super::super::silhouette::LightDir;
use super::{chunk_bytes, ComputeVolumes};

/// A buffer's contents as `u32`s, through a staging copy (its own submit).
pub(super) fn read_words(gpu: &Gpu, buffer: &wgpu::Buffer, what: &str) -> Result<Vec<u32>> {
    let bytes = read_buffer_copy(gpu, buffer, what)?;
    Ok(bytemuck::cast_slice(&bytes).to_vec())
}

/// One caster's volume for one light, built by the compute shader and
/// read back: (sides, front cap, back cap), each a triangle list in the
/// order the invocations appended it. [`cpu_volume_reaching`](super::extrusion::cpu_volume_reaching)'s
/// triangles, in another order (the tests compare the two).
pub fn extrude_once(
    gpu: &Gpu,
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
) -> Result<[Vec<CpuVertex>; 3]> {
    Ok(extrude_in_chunks(gpu, adj, light, reach_w, chunk_bytes(gpu))?.1)
}

/// [`extrude_once`] with chunks of at most `max_bytes`: how many chunks,
/// and the volume, every chunk's part after part.
pub fn extrude_in_chunks(
    gpu: &Gpu,
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
    max_bytes: u64,
) -> Result<(usize, [Vec<CpuVertex>; 3])> {
    let volumes = ComputeVolumes::in_chunks(gpu, &[adj], 1, max_bytes)?;
    let (params, dispatches) = volumes.params_of(gpu, &[(0, 0, light, reach_w)]);
    gpu.queue.write_buffer(&volumes.params, 0, &params);
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    volumes.record(&mut enc, None, &dispatches);
    gpu.queue.submit([enc.finish()]);
    let counts = volumes.read_counts(gpu)?;
    let mut parts: [Vec<CpuVertex>; 3] = Default::default();
    for (slot, s) in volumes.slots.iter().enumerate() {
        let words = read_words(gpu, &s.vertices, "compute volume")?;
        let all: &[CpuVertex] = bytemuck::cast_slice(&words);
        let firsts = volumes.chunks[s.chunk].firsts;
        for (p, part) in parts.iter_mut().enumerate() {
            let first = firsts[p] as usize;
            part.extend_from_slice(&all[first..first + counts[slot][p] as usize]);
        }
    }
    Ok((volumes.slots.len(), parts))
}
