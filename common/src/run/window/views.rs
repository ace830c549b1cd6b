//! The image views' pictures (diff, buffer): uploading them and painting
//! them behind the overlay. The views themselves are
//! [`crate::run::view::View`].

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
