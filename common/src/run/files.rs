//! A headless run's files: its PNGs and its `report.json`. These are
//! not generic (but for [`save`]'s few lines, which hand the bytes on),
//! so that the PNG encoder and the JSON writer are compiled once, here,
//! and not again in each lesson binary, whose generic runner
//! ([`crate::run::headless::run_headless`]) calls them. With the
//! window's event loop (`window/event_loop.rs`) and its scene's TOML
//! (`window/controls.rs`) out of the generic code too, lesson_05's
//! binary crate came to 119 k lines of LLVM IR against 282 k
//! (`cargo llvm-lines --release --bin lesson_05`), and the ten lesson
//! binaries compiled in 21.6 s against 43.1 s (`cargo build --release
//! --bins` after touching their `main.rs`, without LTO as in CI, 2 cores,
//! 2026-12-04), for byte-identical PNGs. The window's `--capture` writes
//! its own PNG (`window/frame.rs`, image's default encoder: a picture to
//! keep, not one of a run's many).

use std::path::Path;

use anyhow::{Context, Result};

use crate::measure::report::Report;

/// Saves an image as a PNG, naming the file on failure. Fast compression:
/// a run writes a few PNGs per variant and light, and the default's
/// adaptive filtering took about a tenth of a lesson 10 headless run's
/// time on lavapipe, the Sub filter 1.3 % of it, for files 14 % larger
/// with the same pixels.
pub fn save<P, C>(img: &image::ImageBuffer<P, C>, path: &Path) -> Result<()>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    use image::EncodableLayout;
    let (w, h) = img.dimensions();
    save_png(img.as_raw().as_bytes(), w, h, P::COLOR_TYPE, path)
}

/// [`save`]'s encoding, for any pixel type's bytes: not generic, so that
/// the PNG encoder is compiled once, here, and not again in each lesson
/// binary whose generic runner calls [`save`]. It writes the bytes image's
/// own `write_with_encoder` would.
fn save_png(
    bytes: &[u8],
    width: u32,
    height: u32,
    color: image::ExtendedColorType,
    path: &Path,
) -> Result<()> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    let write = || -> Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let png = PngEncoder::new_with_quality(file, CompressionType::Fast, FilterType::Sub);
        png.write_image(bytes, width, height, color)?;
        Ok(())
    };
    write().with_context(|| format!("cannot write {}", path.display()))
}

/// Writes `report.json` as pretty JSON, naming the file on failure; not
/// generic, so that serde_json's writer is compiled here once, not in
/// each lesson binary.
pub fn write_json(report: &Report, path: &Path) -> Result<()> {
    let json = serde_json::to_string_pretty(report)?;
    std::fs::write(path, json).with_context(|| format!("cannot write {}", path.display()))
}
