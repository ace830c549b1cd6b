//! The frame's render targets (colour, depth-stencil, object id, one
//! visibility image per light), reading them back, and texture helpers.

use anyhow::Result;

use crate::gpu::readback::{read_texture, PendingRead};
use crate::gpu::Gpu;

pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
pub const ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
/// 8-bit, like the visibility PNGs; R32Float is not renderable on downlevel GL.
pub const VISIBILITY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;
/// The frame's render targets: shaded colour, depth-stencil, object id, and
/// one visibility image per light.
pub struct FrameTargets {
    pub width: u32,
    pub height: u32,
    pub color: wgpu::Texture,
    pub color_view: wgpu::TextureView,
    pub depth: wgpu::Texture,
    pub depth_view: wgpu::TextureView,
    pub id: wgpu::Texture,
    pub id_view: wgpu::TextureView,
    pub visibility: Vec<wgpu::Texture>,
    pub visibility_views: Vec<wgpu::TextureView>,
}

/// A 2D texture to render into and copy from (`extra`: more usages).
pub fn render_texture(
    gpu: &Gpu,
    label: &str,
    w: u32,
    h: u32,
    format: wgpu::TextureFormat,
    extra: wgpu::TextureUsages,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC | extra,
        view_formats: &[],
    })
}

impl FrameTargets {
    /// Targets of `w × h` pixels with one visibility image for each of
    /// `lights` lights, depth-stencil in `depth_format`.
    pub fn new(
        gpu: &Gpu,
        (w, h): (u32, u32),
        depth_format: wgpu::TextureFormat,
        lights: usize,
    ) -> FrameTargets {
        let tb = wgpu::TextureUsages::TEXTURE_BINDING;
        let color = render_texture(gpu, "color", w, h, COLOR_FORMAT, tb);
        let depth = render_texture(gpu, "depth", w, h, depth_format, tb);
        let id = render_texture(gpu, "id", w, h, ID_FORMAT, wgpu::TextureUsages::empty());
        let visibility: Vec<_> = (0..lights)
            .map(|k| {
                render_texture(
                    gpu,
                    &format!("visibility {k}"),
                    w,
                    h,
                    VISIBILITY_FORMAT,
                    tb, // the window's visibility view reads it
                )
            })
            .collect();
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        FrameTargets {
            width: w,
            height: h,
            color_view: view(&color),
            depth_view: view(&depth),
            id_view: view(&id),
            visibility_views: visibility.iter().map(view).collect(),
            color,
            depth,
            id,
            visibility,
        }
    }

    /// A pass with no colour target that keeps the base pass's depth and
    /// starts the stencil at 0: every light's volume pass begins this way.
    pub fn stencil_pass<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        label: &str,
        ts: Option<wgpu::RenderPassTimestampWrites<'_>>,
        occlusion_query_set: Option<&wgpu::QuerySet>,
    ) -> wgpu::RenderPass<'e> {
        let keep = wgpu::Operations {
            load: wgpu::LoadOp::Load,
            store: wgpu::StoreOp::Store,
        };
        let zero = wgpu::Operations {
            load: wgpu::LoadOp::Clear(0),
            store: wgpu::StoreOp::Store,
        };
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth_view,
                depth_ops: Some(keep),
                stencil_ops: Some(zero),
            }),
            timestamp_writes: ts,
            occlusion_query_set,
            multiview_mask: None,
        })
    }

    pub fn color_attachment(
        &self,
        load: wgpu::LoadOp<wgpu::Color>,
    ) -> wgpu::RenderPassColorAttachment<'_> {
        wgpu::RenderPassColorAttachment {
            view: &self.color_view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load,
                store: wgpu::StoreOp::Store,
            },
        }
    }

    /// The frame's depth and stencil, loaded and kept: for the passes that
    /// test against the base pass's depth (lit passes, counting copies).
    pub fn depth_attachment_loaded(&self) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        wgpu::RenderPassDepthStencilAttachment {
            view: &self.depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            }),
        }
    }

    pub fn id_attachment(&self) -> wgpu::RenderPassColorAttachment<'_> {
        wgpu::RenderPassColorAttachment {
            view: &self.id_view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        }
    }

    /// Reads back the frame: colour (RGBA8), object ids, visibility per light.
    pub fn read(&self, gpu: &Gpu) -> Result<FrameImages> {
        let color = read_texture(gpu, &self.color, 4)?;
        Ok(FrameImages {
            color,
            ..self.read_measured(gpu)?
        })
    }

    /// What a comparison with the reference reads: object ids and
    /// visibility, without the colour (left empty), a third less to copy.
    pub fn read_measured(&self, gpu: &Gpu) -> Result<FrameImages> {
        let id: Vec<u32> = bytemuck::cast_slice(&read_texture(gpu, &self.id, 4)?).to_vec();
        let visibility = self
            .visibility
            .iter()
            .map(|t| read_texture(gpu, t, 1).map(|b| b.iter().map(|&v| v as f32 / 255.0).collect()))
            .collect::<Result<Vec<_>>>()?;
        Ok(FrameImages {
            width: self.width,
            height: self.height,
            color: Vec::new(),
            id,
            visibility,
        })
    }
}

/// [`FrameTargets::read_measured`]'s images on their way to the CPU,
/// without blocking ([`crate::gpu::readback::PendingRead`]).
pub struct PendingFrame {
    width: u32,
    height: u32,
    id: PendingRead,
    visibility: Vec<PendingRead>,
    done: Vec<Option<Vec<u8>>>,
}

impl FrameTargets {
    /// Starts reading back what the error figure is measured on, as
    /// [`FrameTargets::read_measured`] reads it: ids and visibility.
    pub fn start_read_measured(&self, gpu: &Gpu) -> PendingFrame {
        let id = PendingRead::start(gpu, &self.id, 4);
        let visibility: Vec<_> = (self.visibility.iter())
            .map(|t| PendingRead::start(gpu, t, 1))
            .collect();
        for r in std::iter::once(&id).chain(&visibility) {
            r.map();
        }
        PendingFrame {
            width: self.width,
            height: self.height,
            done: vec![None; 1 + visibility.len()],
            id,
            visibility,
        }
    }
}

impl PendingFrame {
    /// Whether every image is mapped: [`PendingFrame::take`] then answers
    /// at once (and does the copying).
    pub fn mapped(&self) -> bool {
        let reads = std::iter::once(&self.id).chain(&self.visibility);
        (self.done.iter().zip(reads)).all(|(slot, r)| slot.is_some() || r.mapped())
    }

    /// The frame once every image is mapped; `None` while one is not.
    pub fn take(&mut self) -> Option<Result<FrameImages>> {
        let reads = std::iter::once(&self.id).chain(&self.visibility);
        for (slot, r) in self.done.iter_mut().zip(reads) {
            if slot.is_none() {
                match r.take() {
                    Some(Ok(bytes)) => *slot = Some(bytes),
                    Some(Err(e)) => return Some(Err(e)),
                    None => {}
                }
            }
        }
        if self.done.iter().any(Option::is_none) {
            return None;
        }
        let mut images = self.done.drain(..).map(|b| b.expect("checked above"));
        let id = bytemuck::cast_slice(&images.next().expect("ids")).to_vec();
        let visibility = images
            .map(|b| b.iter().map(|&v| v as f32 / 255.0).collect())
            .collect();
        Some(Ok(FrameImages {
            width: self.width,
            height: self.height,
            color: Vec::new(),
            id,
            visibility,
        }))
    }
}

/// A frame read back to the CPU.
pub struct FrameImages {
    pub width: u32,
    pub height: u32,
    pub color: Vec<u8>,
    pub id: Vec<u32>,
    pub visibility: Vec<Vec<f32>>,
}

// ANCHOR: depth_texture
/// A depth texture the lesson samples (shadow maps): `size` × `size`
/// texels, `layers` of them (1 for one map; more for a cube map or cascades).
pub fn depth_texture(
    gpu: &Gpu,
    label: &str,
    size: u32,
    layers: u32,
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        // A shadow pass renders into it; a lit pass samples it.
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}
// ANCHOR_END: depth_texture

/// One 2D view per array layer of `texture` (a cube map's faces, a
/// cascade's layers): what a pass renders into, one layer at a time.
pub fn layer_views(texture: &wgpu::Texture, layers: u32) -> Vec<wgpu::TextureView> {
    (0..layers)
        .map(|i| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: i,
                array_layer_count: Some(1),
                ..Default::default()
            })
        })
        .collect()
}
