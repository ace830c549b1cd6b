//! What the window shows: the frame, the variant's visibility, its
//! difference against the exact reference, or the lesson's own buffer.

use clap::ValueEnum;

/// The window's views (keys 1 to 4, Tab cycles, `--view` picks the first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum View {
    /// The shaded frame.
    Frame,
    /// The variant's visibility of light 0: white lit, black shadowed.
    Visibility,
    /// Against the exact reference (light 0): red false shadow, green false
    /// lit, gray where both agree (lighter lit), near black not a receiver.
    Diff,
    /// The lesson's own buffer: the shadow map, the cube map's cross, the
    /// stencil count or the cascades.
    Buffer,
}

impl View {
    pub const ALL: [View; 4] = [View::Frame, View::Visibility, View::Diff, View::Buffer];

    /// The key that shows it.
    pub fn key(self) -> char {
        match self {
            View::Frame => '1',
            View::Visibility => '2',
            View::Diff => '3',
            View::Buffer => '4',
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            View::Frame => "frame",
            View::Visibility => "visibility",
            View::Diff => "diff",
            View::Buffer => "buffer",
        }
    }

    /// The view after this one (Tab).
    pub fn next(self) -> View {
        let i = View::ALL.iter().position(|&v| v == self).unwrap_or(0);
        View::ALL[(i + 1) % View::ALL.len()]
    }

    /// The view a key shows, if any.
    pub fn of_key(c: &str) -> Option<View> {
        View::ALL.into_iter().find(|v| c == v.key().to_string())
    }
}

/// An image view's picture, as egui shows it, and what it shows.
pub struct Picture {
    pub texture: egui::TextureHandle,
    pub title: String,
    /// The `(scene_gen, image_gen)` it shows (the overlay says when it is
    /// older than the frame).
    pub stamp: (u64, u64),
}

/// Uploads `image` into `slot` (a new texture the first time, or when its
/// size changed).
pub fn upload(
    ctx: &egui::Context,
    slot: &mut Option<Picture>,
    name: &str,
    image: &image::RgbaImage,
    title: String,
    stamp: (u64, u64),
) {
    let size = [image.width() as usize, image.height() as usize];
    let colour = egui::ColorImage::from_rgba_unmultiplied(size, image.as_raw());
    let options = egui::TextureOptions::NEAREST;
    match slot {
        Some(p) if p.texture.size() == size => {
            p.texture.set(colour, options);
            p.title = title;
            p.stamp = stamp;
        }
        _ => {
            *slot = Some(Picture {
                texture: ctx.load_texture(name, colour, options),
                title,
                stamp,
            })
        }
    }
}

/// Paints `picture` behind the overlay, as large as fits in `screen` with
/// its aspect ratio kept.
pub fn paint_behind(ctx: &egui::Context, picture: &Picture, screen: egui::Rect) {
    let [w, h] = picture.texture.size();
    let scale = (screen.width() / w as f32).min(screen.height() / h as f32);
    let size = egui::vec2(w as f32 * scale, h as f32 * scale);
    let rect = egui::Rect::from_center_size(screen.center(), size);
    let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
    ctx.layer_painter(egui::LayerId::background()).image(
        picture.texture.id(),
        rect,
        uv,
        egui::Color32::WHITE,
    );
}
