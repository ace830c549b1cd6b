//! Copying GPU results back to the CPU: buffers, textures and query
//! results.

use anyhow::{anyhow, Result};

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

/// What a readback copies: a texture (layer 0, this many bytes a texel),
/// or a whole buffer.
#[derive(Clone, PartialEq, Eq, Hash)]
pub enum Source {
    Texture(wgpu::Texture, u32),
    Buffer(wgpu::Buffer),
}

/// What a [`Source`] holds, whichever texture or buffer it is: a
/// texture's size, format and bytes a texel, or a buffer's size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    Texture(wgpu::Extent3d, wgpu::TextureFormat, u32),
    Buffer(u64),
}

impl Source {
    pub fn shape(&self) -> Shape {
        match self {
            Source::Texture(t, bpp) => Shape::Texture(t.size(), t.format(), *bpp),
            Source::Buffer(b) => Shape::Buffer(b.size()),
        }
    }

    /// Submits the copy to a buffer the CPU maps.
    pub fn start(&self, gpu: &Gpu) -> PendingRead {
        match self {
            Source::Texture(tex, bytes_per_pixel) => PendingRead::start(gpu, tex, *bytes_per_pixel),
            Source::Buffer(buf) => PendingRead::start_buffer(gpu, buf),
        }
    }
}

/// A texture's copy on its way to the CPU, read without blocking: what a
/// web page must do, where nothing may wait for the GPU, and what the
/// window does on the desktop too, so that its frames never wait for the
/// live reference's readback. [`PendingRead::start`] submits the copy,
/// [`PendingRead::map`] asks for the mapping, [`PendingRead::mapped`] says
/// when it is done (the browser maps by itself; the desktop when the device
/// is polled), and [`PendingRead::take`] gives the bytes.
pub struct PendingRead {
    buf: wgpu::Buffer,
    row: u32,
    padded: u32,
    height: u32,
    state: std::sync::Arc<std::sync::Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>,
}

impl PendingRead {
    /// Submits the copy of `tex` (`bytes_per_pixel` per texel) to a buffer
    /// the CPU maps; [`PendingRead::map`] asks for the mapping.
    pub fn start(gpu: &Gpu, tex: &wgpu::Texture, bytes_per_pixel: u32) -> PendingRead {
        let (w, h) = (tex.width(), tex.height());
        let row = w * bytes_per_pixel;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: padded as u64 * h as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_buffer(
            tex.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buf,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        gpu.queue.submit([enc.finish()]);
        PendingRead {
            buf,
            row,
            padded,
            height: h,
            state: Default::default(),
        }
    }

    /// Submits the copy of the whole of `source` to a buffer the CPU maps
    /// (one row, unpadded).
    pub fn start_buffer(gpu: &Gpu, source: &wgpu::Buffer) -> PendingRead {
        let size = source.size();
        let buf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(source, 0, &buf, 0, size);
        gpu.queue.submit([enc.finish()]);
        PendingRead {
            buf,
            row: size as u32,
            padded: size as u32,
            height: 1,
            state: Default::default(),
        }
    }

    fn size(&self) -> u64 {
        self.padded as u64 * self.height as u64
    }

    /// Asks for the mapping; the browser (or a poll of the device, on the
    /// desktop) answers later.
    pub fn map(&self) {
        let state = self.state.clone();
        self.buf
            .slice(..self.size())
            .map_async(wgpu::MapMode::Read, move |r| {
                *state.lock().expect("readback state") = Some(r);
            });
    }

    /// Whether the mapping is done (or failed): [`PendingRead::take`]
    /// then answers at once.
    pub fn mapped(&self) -> bool {
        self.state.lock().expect("readback state").is_some()
    }

    /// The texels, row by row without padding, once mapped; `None` while
    /// the mapping is under way.
    pub fn take(&self) -> Option<Result<Vec<u8>>> {
        let done = self.state.lock().expect("readback state").take()?;
        Some(match done {
            Err(e) => Err(anyhow!("texture readback: {e}")),
            Ok(()) => {
                let data = {
                    let view = self.buf.slice(..self.size()).get_mapped_range();
                    match view {
                        Ok(v) => Ok(self.unpad(&v)),
                        Err(e) => Err(anyhow!("texture readback: {e}")),
                    }
                };
                self.buf.unmap();
                data
            }
        })
    }

    /// The rows without their padding, a row at a time (a byte-wise
    /// iterator here took 16 % of lesson 09's headless run on lavapipe).
    fn unpad(&self, data: &[u8]) -> Vec<u8> {
        let rows = data.chunks_exact(self.padded as usize);
        let mut out = Vec::with_capacity(rows.len() * self.row as usize);
        for r in rows {
            out.extend_from_slice(&r[..self.row as usize]);
        }
        out
    }
}
