//! Putting a frame in the window: the chosen view and the overlay are drawn
//! into one image (the window's own picture, which `--capture` saves), and
//! that image is copied to the window's surface.

use anyhow::{Context, Result};

use crate::gpu::bindings::{self, float_texture_entry};
use crate::gpu::fullscreen::{draw_fullscreen, Fullscreen};
use crate::gpu::readback::read_texture;
use crate::gpu::targets::{render_texture, FrameTargets};
use crate::gpu::Gpu;
use crate::run::view::View;

const BLIT_WGSL: &str = r#"
@group(0) @binding(0) var src: texture_2d<f32>;
@fragment fn fs(in: FullscreenOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(src));
    return textureLoad(src, vec2<i32>(in.uv * size), 0);
}
// The visibility image (one channel): gray, as the visibility PNGs.
@fragment fn fs_gray(in: FullscreenOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(src));
    let v = textureLoad(src, vec2<i32>(in.uv * size), 0).r;
    return vec4<f32>(v, v, v, 1.0);
}
"#;

/// The overlay's triangles and texture changes for one frame.
pub struct Overlay {
    pub primitives: Vec<egui::ClippedPrimitive>,
    pub textures: egui::TexturesDelta,
    pub pixels_per_point: f32,
}

/// What draws the window's picture.
pub struct Present {
    format: wgpu::TextureFormat,
    /// The window's picture: the view, then the overlay.
    picture: wgpu::Texture,
    picture_view: wgpu::TextureView,
    layout: wgpu::BindGroupLayout,
    /// Into the picture: the frame (colour) and the visibility (gray).
    blit: wgpu::RenderPipeline,
    blit_gray: wgpu::RenderPipeline,
    frame_group: wgpu::BindGroup,
    visibility_group: wgpu::BindGroup,
    picture_group: wgpu::BindGroup,
    /// The diff view's image, pixel for pixel (the frame's size).
    diff: wgpu::Texture,
    diff_group: wgpu::BindGroup,
    egui: egui_wgpu::Renderer,
}

impl Present {
    /// `format`: the surface's; the picture has the same.
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat, targets: &FrameTargets) -> Present {
        let layout = bindings::layout(gpu, "window blit", &[float_texture_entry(0)]);
        let pipeline = |entry| {
            Fullscreen::image("window blit", BLIT_WGSL, entry, &[&layout], format).pipeline(gpu)
        };
        let (blit, blit_gray) = (pipeline("fs"), pipeline("fs_gray"));
        let egui = egui_wgpu::Renderer::new(&gpu.device, format, Default::default());
        let (picture, picture_view, groups, diff) = sized(gpu, format, &layout, targets);
        let [frame_group, visibility_group, picture_group, diff_group] = groups;
        Present {
            format,
            picture,
            picture_view,
            layout,
            blit,
            blit_gray,
            frame_group,
            visibility_group,
            picture_group,
            diff,
            diff_group,
            egui,
        }
    }

    /// After the targets changed size.
    pub fn resize(&mut self, gpu: &Gpu, targets: &FrameTargets) {
        let (picture, picture_view, groups, diff) = sized(gpu, self.format, &self.layout, targets);
        let [frame_group, visibility_group, picture_group, diff_group] = groups;
        self.diff = diff;
        self.diff_group = diff_group;
        self.picture = picture;
        self.picture_view = picture_view;
        self.frame_group = frame_group;
        self.visibility_group = visibility_group;
        self.picture_group = picture_group;
    }

    /// Draws `view` and the overlay into the picture, and the picture into
    /// `surface` (the window's texture this frame).
    pub fn draw(&mut self, gpu: &Gpu, view: View, overlay: Overlay, surface: &wgpu::TextureView) {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        let (w, h) = (self.picture.width(), self.picture.height());
        match view {
            View::Frame => {
                draw_fullscreen(&mut enc, &self.picture_view, &self.blit, &self.frame_group)
            }
            View::Visibility => draw_fullscreen(
                &mut enc,
                &self.picture_view,
                &self.blit_gray,
                &self.visibility_group,
            ),
            View::Diff | View::Dv => {
                draw_fullscreen(&mut enc, &self.picture_view, &self.blit, &self.diff_group)
            }
            // The overlay paints the buffer over a dark background.
            View::Buffer => clear(&mut enc, &self.picture_view),
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [w, h],
            pixels_per_point: overlay.pixels_per_point,
        };
        for (id, deltas) in &overlay.textures.set {
            for delta in deltas {
                self.egui
                    .update_texture(&gpu.device, &gpu.queue, *id, delta);
            }
        }
        let extra = self.egui.update_buffers(
            &gpu.device,
            &gpu.queue,
            &mut enc,
            &overlay.primitives,
            &screen,
        );
        {
            let pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("overlay"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.picture_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            self.egui
                .render(&mut pass.forget_lifetime(), &overlay.primitives, &screen);
        }
        draw_fullscreen(&mut enc, surface, &self.blit, &self.picture_group);
        gpu.queue
            .submit(extra.into_iter().chain(std::iter::once(enc.finish())));
        for id in &overlay.textures.free {
            self.egui.free_texture(id);
        }
    }

    /// The diff view's image: the frame's size, or smaller (a coarse
    /// answer), then each of its pixels covers a block.
    pub fn set_diff(&self, gpu: &Gpu, image: &image::RgbaImage) {
        let (w, h) = (self.diff.width(), self.diff.height());
        let full;
        let image = if image.dimensions() == (w, h) {
            image
        } else {
            let nearest = image::imageops::FilterType::Nearest;
            full = image::imageops::resize(image, w, h, nearest);
            &full
        };
        gpu.queue.write_texture(
            self.diff.as_image_copy(),
            image.as_raw(),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * w),
                rows_per_image: Some(h),
            },
            self.diff.size(),
        );
    }

    /// The window's picture as it was last drawn, in RGBA.
    pub fn read_picture(&self, gpu: &Gpu) -> Result<image::RgbaImage> {
        let mut bytes = read_texture(gpu, &self.picture, 4)?;
        if matches!(
            self.format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        ) {
            for px in bytes.chunks_exact_mut(4) {
                px.swap(0, 2);
            }
        }
        let (w, h) = (self.picture.width(), self.picture.height());
        image::RgbaImage::from_raw(w, h, bytes).context("the window's picture has the wrong size")
    }
}

/// The picture and the diff image of the targets' size, and the bind
/// groups that read the frame, light 0's visibility, the picture and the diff.
fn sized(
    gpu: &Gpu,
    format: wgpu::TextureFormat,
    layout: &wgpu::BindGroupLayout,
    t: &FrameTargets,
) -> (
    wgpu::Texture,
    wgpu::TextureView,
    [wgpu::BindGroup; 4],
    wgpu::Texture,
) {
    let usage = wgpu::TextureUsages::TEXTURE_BINDING;
    let picture = render_texture(gpu, "window picture", t.width, t.height, format, usage);
    let picture_view = picture.create_view(&Default::default());
    let group = |v: &wgpu::TextureView| {
        bindings::group(
            gpu,
            "window blit",
            layout,
            &[wgpu::BindingResource::TextureView(v)],
        )
    };
    // A scene with no light has no visibility image: show the frame.
    let visibility = t.visibility_views.first().unwrap_or(&t.color_view);
    let diff = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("window diff"),
        size: wgpu::Extent3d {
            width: t.width,
            height: t.height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let diff_view = diff.create_view(&Default::default());
    let groups = [
        group(&t.color_view),
        group(visibility),
        group(&picture_view),
        group(&diff_view),
    ];
    (picture, picture_view, groups, diff)
}

/// Clears `view` to the overlay's dark background.
fn clear(enc: &mut wgpu::CommandEncoder, view: &wgpu::TextureView) {
    enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("clear window picture"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color {
                    r: 0.02,
                    g: 0.02,
                    b: 0.02,
                    a: 1.0,
                }),
                store: wgpu::StoreOp::Store,
            },
        })],
        ..Default::default()
    });
}
