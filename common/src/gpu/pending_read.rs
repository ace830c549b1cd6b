//! A copy on its way from the GPU to the CPU, read without blocking
//! ([`PendingRead`]), and what it copies ([`Source`]): a texture or a
//! whole buffer. The blocking reads of [`super::readback`] and the reads a
//! frame later of [`super::read_later`] both start one.

use anyhow::{anyhow, Result};

use crate::gpu::Gpu;

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
    pub(super) buf: wgpu::Buffer,
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

    pub(super) fn size(&self) -> u64 {
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
    pub(super) fn unpad(&self, data: &[u8]) -> Vec<u8> {
        let rows = data.chunks_exact(self.padded as usize);
        let mut out = Vec::with_capacity(rows.len() * self.row as usize);
        for r in rows {
            out.extend_from_slice(&r[..self.row as usize]);
        }
        out
    }
}
