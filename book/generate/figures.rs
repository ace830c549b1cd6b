//! Prepares every image the book shows for its white page, from the PNG a
//! lesson (or the window) wrote; the lessons' own files stay as they are.
//!
//! - Every image with a transparent pixel is composited onto
//!   [`dv_view::background`], a pale blue checker: "no geometry" reads
//!   neither as lit (white) nor as shadow (black, gray).
//! - A diff image (`*_diff*.png`: red false shadow, green false lit) gets
//!   each pixel of a sparse class drawn as a dot of radius [`MARK_RADIUS`],
//!   so that a few scattered errors show at page size. A class is sparse
//!   when its pixels are fewer than [`SPARSE_PCT`] % of the covered pixels
//!   ([`Count::marked`]): both classes when all the errors are sparse, and
//!   one class on its own when the other is not (25 green pixels among
//!   50 000 red ones, lesson 01's Figure 1.3).
//! - A ΔV image (`*_dv*.png`, [`dv_view`]) gets its colour key below it:
//!   ΔV from −1 (left) to +1 (right), a tick every 0.25.
//!
//! The counts (on the raw image, before any dot is drawn) go to
//! `generated/figures.json` ([`Count`]); `tests/book_images.rs` checks that
//! the caption of every sparse error figure gives its count, and that of a
//! diff with one sparse class the count of that class.
//!
//! The committed figures were made from the raw copies (`git show
//! 49310ab:<figure>`, before this step existed) by the ignored test
//! `prepare_committed_figures` of `tests/book_images.rs`.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, Result};
use common::reference::dv_view;
use common::reference::metrics::{FALSE_LIT, FALSE_SHADOW};
use image::{Rgb, RgbImage, Rgba, RgbaImage};
use serde::{Deserialize, Serialize};

/// An error figure is sparse below this share (%) of its covered pixels.
pub const SPARSE_PCT: f64 = 1.0;
/// A sparse diff's error pixels are drawn as dots of this radius (pixels).
pub const MARK_RADIUS: i32 = 3;
/// A ΔV figure's error pixels: receivers with |ΔV| at least this.
pub const DV_ERROR: f32 = 0.05;
/// The height (pixels) of a ΔV figure's colour key.
const KEY_HEIGHT: u32 = 22;

/// What an error figure holds, counted on the raw image.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Count {
    /// `diff` (classified at V = ½) or `dv` (|ΔV| ≥ [`DV_ERROR`]).
    pub kind: String,
    /// False shadow + false lit (`diff`); darker + lighter (`dv`).
    pub error_pixels: u64,
    /// False shadow (`diff`); the GPU darker by [`DV_ERROR`] or more (`dv`).
    pub darker: u64,
    /// False lit (`diff`); the GPU lighter by [`DV_ERROR`] or more (`dv`).
    pub lighter: u64,
    /// Pixels covered by geometry (the GPU's or the reference's).
    pub covered_pixels: u64,
    /// `error_pixels` under [`SPARSE_PCT`] % of `covered_pixels`: its
    /// caption must give the count, and a diff's errors are drawn as dots.
    pub sparse: bool,
}

impl Count {
    fn new(kind: &str, darker: u64, lighter: u64, covered: u64) -> Count {
        let error_pixels = darker + lighter;
        Count {
            kind: kind.into(),
            error_pixels,
            darker,
            lighter,
            covered_pixels: covered,
            sparse: few(error_pixels, covered),
        }
    }

    /// Which classes of a diff have their pixels drawn as dots: (false
    /// shadow, false lit), each when it has pixels and they are fewer than
    /// [`SPARSE_PCT`] % of the covered ones. Both when the whole figure is
    /// [`Count::sparse`]; one alone when only that class is few. A ΔV
    /// figure marks none.
    pub fn marked(&self) -> (bool, bool) {
        if self.kind != "diff" {
            return (false, false);
        }
        let marks = |n: u64| n > 0 && few(n, self.covered_pixels);
        (marks(self.darker), marks(self.lighter))
    }
}

/// Whether `n` pixels are under [`SPARSE_PCT`] % of `covered`.
pub fn few(n: u64, covered: u64) -> bool {
    (n as f64) < SPARSE_PCT / 100.0 * covered as f64
}

/// One figure made ready: the PNG to write, and the count of an error figure.
pub struct Prepared {
    pub png: Vec<u8>,
    pub count: Option<Count>,
}

/// Prepares the PNG `raw` for the figure `dest` (its path under
/// `figures/`, which says its kind).
pub fn prepare(dest: &str, raw: &[u8]) -> Result<Prepared> {
    let img = image::load_from_memory(raw).with_context(|| format!("{dest}: not an image"))?;
    let name = Path::new(dest)
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or(dest);
    let is_diff = name.contains("_diff");
    let is_dv = name.contains("_dv");
    let rgba = img.to_rgba8();
    if !is_diff && !is_dv && rgba.pixels().all(|p| p.0[3] == 255) {
        // Opaque already: the lesson's own bytes.
        return Ok(Prepared {
            png: raw.to_vec(),
            count: None,
        });
    }
    let (mut out, count) = (composite(&rgba), None);
    let count = if is_diff {
        let c = diff_count(&rgba);
        let (shadow, lit) = c.marked();
        let classes: Vec<Rgba<u8>> = [(shadow, FALSE_SHADOW), (lit, FALSE_LIT)]
            .into_iter()
            .filter_map(|(m, class)| m.then_some(class))
            .collect();
        mark_errors(&rgba, &mut out, &classes);
        Some(c)
    } else if is_dv {
        let c = dv_count(&rgba);
        out = with_key(&out);
        Some(c)
    } else {
        count
    };
    let mut png = Vec::new();
    out.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)?;
    Ok(Prepared { png, count })
}

/// The image over the background, opaque.
fn composite(img: &RgbaImage) -> RgbImage {
    RgbImage::from_fn(img.width(), img.height(), |x, y| {
        let [r, g, b, a] = img.get_pixel(x, y).0;
        let bg = dv_view::background(x, y).0;
        let a = a as f32 / 255.0;
        let mix = |c: u8, k: usize| (c as f32 * a + bg[k] as f32 * (1.0 - a)).round() as u8;
        Rgb([mix(r, 0), mix(g, 1), mix(b, 2)])
    })
}

/// A raw diff's counts.
fn diff_count(img: &RgbaImage) -> Count {
    let px = || img.pixels();
    let n = |c: Rgba<u8>| px().filter(|&&p| p == c).count() as u64;
    let covered = px().filter(|p| p.0[3] == 255).count() as u64;
    Count::new("diff", n(FALSE_SHADOW), n(FALSE_LIT), covered)
}

/// A raw ΔV image's counts.
fn dv_count(img: &RgbaImage) -> Count {
    let (mut darker, mut lighter, mut covered) = (0, 0, 0);
    for &p in img.pixels() {
        if dv_view::is_background(p) || p.0[3] != 255 {
            continue;
        }
        covered += 1;
        match dv_view::dv_of(p) {
            Some(dv) if dv <= -DV_ERROR => darker += 1,
            Some(dv) if dv >= DV_ERROR => lighter += 1,
            _ => {}
        }
    }
    Count::new("dv", darker, lighter, covered)
}

/// Draws each pixel of `raw` whose colour is one of `classes` as a dot of
/// its colour on `out`.
fn mark_errors(raw: &RgbaImage, out: &mut RgbImage, classes: &[Rgba<u8>]) {
    let (w, h) = (raw.width() as i32, raw.height() as i32);
    let r = MARK_RADIUS;
    for (x, y, &p) in raw.enumerate_pixels() {
        if !classes.contains(&p) {
            continue;
        }
        let c = Rgb([p.0[0], p.0[1], p.0[2]]);
        for dy in -r..=r {
            for dx in -r..=r {
                let (nx, ny) = (x as i32 + dx, y as i32 + dy);
                if dx * dx + dy * dy <= r * r + 1 && (0..w).contains(&nx) && (0..h).contains(&ny) {
                    out.put_pixel(nx as u32, ny as u32, c);
                }
            }
        }
    }
}

/// The ΔV image with its colour key below: a bar from ΔV = −1 (left)
/// through 0 (white, the middle) to +1 (right), ticks every 0.25.
fn with_key(img: &RgbImage) -> RgbImage {
    let (w, h) = (img.width(), img.height());
    let margin = 16;
    let bar = (w - 2 * margin).max(1);
    RgbImage::from_fn(w, h + KEY_HEIGHT, |x, y| {
        if y < h {
            return *img.get_pixel(x, y);
        }
        let (ky, inside) = (y - h, x >= margin && x < margin + bar);
        let white = Rgb([255, 255, 255]);
        if !inside || ky < 4 {
            return white;
        }
        let t = (x - margin) as f32 / (bar - 1).max(1) as f32;
        let tick = (0..=8).any(|i| (x - margin) == (i * (bar - 1)) / 8);
        match ky {
            4..=15 => {
                let c = dv_view::dv_colour(2.0 * t - 1.0).0;
                Rgb([c[0], c[1], c[2]])
            }
            16..=20 if tick => Rgb([0, 0, 0]),
            _ => white,
        }
    })
}

/// Prepares the PNG at `src` into `dest_path` (the figure `dest`), and
/// records its count in `counts`.
pub fn prepare_file(
    src: &Path,
    dest: &str,
    dest_path: &Path,
    counts: &mut BTreeMap<String, Count>,
) -> Result<()> {
    let raw = std::fs::read(src).with_context(|| format!("cannot read {}", src.display()))?;
    let p = prepare(dest, &raw)?;
    std::fs::write(dest_path, &p.png)
        .with_context(|| format!("cannot write {}", dest_path.display()))?;
    match p.count {
        Some(c) => counts.insert(dest.to_string(), c),
        None => counts.remove(dest),
    };
    Ok(())
}

/// The counts of `generated/figures.json` (empty when it is missing).
pub fn load_counts(generated: &Path) -> Result<BTreeMap<String, Count>> {
    let path = generated.join("figures.json");
    match std::fs::read_to_string(&path) {
        Ok(text) => {
            serde_json::from_str(&text).with_context(|| format!("{}: not counts", path.display()))
        }
        Err(_) => Ok(BTreeMap::new()),
    }
}

/// Writes `generated/figures.json`.
pub fn write_counts(generated: &Path, counts: &BTreeMap<String, Count>) -> Result<()> {
    let path = generated.join("figures.json");
    let text = serde_json::to_string_pretty(counts)? + "\n";
    std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))
}
