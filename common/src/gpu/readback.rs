//! Copying GPU results back to the CPU: buffers, textures and query
//! results.

use anyhow::{anyhow, Result};

pub use crate::gpu::pending_read::{PendingRead, Shape, Source};
use crate::gpu::Gpu;

/// Maps the first `bytes` of a `MAP_READ` buffer and copies them out.
/// `what` names the data in the error ("timestamps", ...).
pub fn read_buffer(gpu: &Gpu, buf: &wgpu::Buffer, bytes: u64, what: &str) -> Result<Vec<u8>> {
    if cfg!(target_arch = "wasm32") {
        anyhow::bail!(
            "{what} readback: a web page cannot wait for the GPU (read a copy with read_buffer_copy or read_texture inside read_later::later: it comes back a frame or more later)"
        );
    }
    let slice = buf.slice(..bytes);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    gpu.wait()?;
    let out = {
        let view = slice
            .get_mapped_range()
            .map_err(|e| anyhow!("{what} readback: {e}"))?;
        view.to_vec()
    };
    buf.unmap();
    Ok(out)
}

/// The two buffers a query set is read back through: one it resolves
/// into, one the CPU maps. Holds `count` 64-bit results.
pub struct QueryReadback {
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    what: &'static str,
}

impl QueryReadback {
    pub fn new(gpu: &Gpu, count: u32, what: &'static str) -> QueryReadback {
        let buffer = |usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(what),
                size: 8 * count.max(1) as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        QueryReadback {
            resolve: buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read: buffer(wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
            what,
        }
    }

    /// Records the resolve of queries `0..n` and the copy to the mapped buffer.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder, set: &wgpu::QuerySet, n: u32) {
        encoder.resolve_query_set(set, 0..n, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 8 * n as u64);
    }

    /// The first `n` results, after the encoder with [`Self::resolve`] was submitted.
    pub fn read(&self, gpu: &Gpu, n: u32) -> Result<Vec<u64>> {
        let bytes = read_buffer(gpu, &self.read, 8 * n as u64, self.what)?;
        Ok(to_u64s(&bytes))
    }

    /// Asks for the mapping of the first `n` results without waiting for
    /// it (`done` is called once it is mapped): [`Self::take_mapped`] then.
    pub fn map(
        &self,
        n: u32,
        done: impl FnOnce(Result<(), wgpu::BufferAsyncError>) + wgpu::WasmNotSend + 'static,
    ) {
        self.read
            .slice(..8 * n.max(1) as u64)
            .map_async(wgpu::MapMode::Read, done);
    }

    /// The first `n` results of a mapping [`Self::map`] asked for, once
    /// it is done; unmaps the buffer.
    pub fn take_mapped(&self, n: u32) -> Result<Vec<u64>> {
        let out = {
            let view = (self.read.slice(..8 * n.max(1) as u64))
                .get_mapped_range()
                .map_err(|e| anyhow!("{} readback: {e}", self.what))?;
            to_u64s(&view[..8 * n as usize])
        };
        self.read.unmap();
        Ok(out)
    }
}

fn to_u64s(bytes: &[u8]) -> Vec<u64> {
    bytes
        .chunks_exact(8)
        .map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect()
}

/// Copies a 2D texture (layer 0) to the CPU, tightly packed.
/// In a web page, only inside [`super::read_later::later`], which reads it
/// a frame or more later.
pub fn read_texture(gpu: &Gpu, tex: &wgpu::Texture, bytes_per_pixel: u32) -> Result<Vec<u8>> {
    let source = Source::Texture(tex.clone(), bytes_per_pixel);
    if let Some(read) = super::read_later::read(gpu, &source) {
        return read;
    }
    let pending = PendingRead::start(gpu, tex, bytes_per_pixel);
    let data = read_buffer(gpu, &pending.buf, pending.size(), "texture")?;
    Ok(pending.unpad(&data))
}

/// A buffer's contents, through a staging copy (its own submit). In a web
/// page, only inside [`super::read_later::later`], as [`read_texture`].
pub fn read_buffer_copy(gpu: &Gpu, buffer: &wgpu::Buffer, what: &str) -> Result<Vec<u8>> {
    if let Some(read) = super::read_later::read(gpu, &Source::Buffer(buffer.clone())) {
        return read.map_err(|e| e.context(what.to_string()));
    }
    let pending = PendingRead::start_buffer(gpu, buffer);
    read_buffer(gpu, &pending.buf, pending.size(), what)
}
