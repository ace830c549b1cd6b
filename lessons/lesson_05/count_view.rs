//! The stencil count as a picture (lesson 05, reused by lessons 06–08):
//! the "buffer" view of the stencil techniques. Each light's volume pass
//! clears the stencil and counts into it, so after a frame it holds the
//! last light's count; this reads it back ([`read_stencil`]) and colours
//! each pixel by its count: 0 lit, 1, 2, ... shadowed.

use anyhow::Result;
use common::gpu::fullscreen::read_stencil;
use common::gpu::Gpu;
use common::run::instruments::BufferView;

/// The colours of counts 0, 1, 2, ...; a count past the last one is
/// [`MANY`].
const RAMP: [([u8; 3], &str); 6] = [
    ([0, 0, 0], "black"),
    ([220, 50, 40], "red"),
    ([240, 150, 30], "orange"),
    ([240, 230, 60], "yellow"),
    ([70, 200, 80], "green"),
    ([60, 200, 230], "cyan"),
];
const MANY: ([u8; 3], &str) = ([255, 255, 255], "white");
/// A count in the upper half of its range: below 0, wrapped (a z-pass
/// count the near plane cut, more "leave" than "enter").
const BELOW_ZERO: ([u8; 3], &str) = ([230, 60, 230], "magenta");

/// The colour of stencil count `count`, which wraps modulo `modulus`.
pub fn count_colour(count: u32, modulus: u32) -> [u8; 3] {
    let count = count % modulus;
    if count >= modulus / 2 {
        BELOW_ZERO.0
    } else {
        RAMP.get(count as usize).unwrap_or(&MANY).0
    }
}

/// The colours of [`count_colour`], in words: "black 0 (lit), red 1, ...".
pub fn count_legend(modulus: u32) -> String {
    let mut parts: Vec<String> = RAMP
        .iter()
        .enumerate()
        .map(|(n, (_, name))| format!("{name} {n}"))
        .collect();
    parts[0] += " (lit)";
    parts.push(format!("{} {}+", MANY.1, RAMP.len()));
    parts.push(format!(
        "{} {}+ (below 0, wrapped)",
        BELOW_ZERO.1,
        modulus / 2
    ));
    parts.join(", ")
}

/// The count the stencil of `depth_stencil` holds after light `light`'s
/// volume pass, in its bits `mask` (lessons 05–07: all 8; lesson 08: bits
/// 0–6, its bit 7 is the depth-bounds mark), as a picture. `what` names
/// the count in the title ("z-pass count").
pub fn count_view(
    gpu: &Gpu,
    depth_stencil: &wgpu::Texture,
    light: usize,
    mask: u8,
    what: &str,
) -> Result<BufferView> {
    let stencil = read_stencil(gpu, depth_stencil)?;
    let modulus = u32::from(mask) + 1;
    let (w, h) = (depth_stencil.width(), depth_stencil.height());
    let image = image::RgbaImage::from_fn(w, h, |x, y| {
        let s = stencil[(y * w + x) as usize] & mask;
        let [r, g, b] = count_colour(u32::from(s), modulus);
        image::Rgba([r, g, b, 255])
    });
    let title = format!(
        "stencil, {what} after light {light}'s volume pass (the last light; each light clears it): {}",
        count_legend(modulus)
    );
    Ok(BufferView { title, image })
}
