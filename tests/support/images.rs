//! A lesson's images: a visibility PNG read back ([`read_visibility`]), as
//! the text masks a snapshot holds ([`ascii_of`], [`ascii_levels`]), and a
//! frame compared with a committed reference PNG
//! ([`compare_with_reference`]).

use std::path::{Path, PathBuf};

/// Reads a visibility PNG (gray + alpha) as (object covered 0/1, visibility 0..1).
pub fn read_visibility(path: &Path) -> (Vec<u32>, Vec<f32>, u32, u32) {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_luma_alpha8();
    let (w, h) = img.dimensions();
    let ids = img.pixels().map(|p| u32::from(p.0[1] > 0)).collect();
    let vis = img.pixels().map(|p| p.0[0] as f32 / 255.0).collect();
    (ids, vis, w, h)
}

/// The coarse text mask a learner reads in `cargo insta review`.
pub fn ascii_of(path: &Path, cols: u32, rows: u32) -> String {
    let (ids, vis, w, h) = read_visibility(path);
    common::reference::metrics::ascii_mask(&ids, &vis, w, h, cols, rows)
}

/// A three-level text mask, stable across drivers where a surface is noisy:
/// per cell, '#' when under 15 % of its covered pixels are lit, '.' when over
/// 85 % are, ':' for mixed cells (acne, penumbrae, shadow edges), ' ' when
/// under half the cell is covered.
pub fn ascii_levels(path: &Path, cols: u32, rows: u32) -> String {
    let (ids, vis, w, h) = read_visibility(path);
    let mut out = String::new();
    for r in 0..rows {
        for c in 0..cols {
            let (x0, x1) = (c * w / cols, (c + 1) * w / cols);
            let (y0, y1) = (r * h / rows, (r + 1) * h / rows);
            let (mut covered, mut lit, mut n) = (0u32, 0f32, 0u32);
            for y in y0..y1 {
                for x in x0..x1 {
                    let i = (y * w + x) as usize;
                    n += 1;
                    if ids[i] != 0 {
                        covered += 1;
                        lit += vis[i];
                    }
                }
            }
            let ch = if covered * 2 < n {
                ' '
            } else {
                match lit / covered as f32 {
                    f if f < 0.15 => '#',
                    f if f > 0.85 => '.',
                    _ => ':',
                }
            };
            out.push(ch);
        }
        out.push('\n');
    }
    out
}

/// Compares a rendered frame with a committed reference PNG.
///
/// Both are box-filtered into `block`×`block` cells (so single-pixel raster
/// differences between drivers do not count); the test fails when more than
/// `max_bad_pct` % of the cells differ by more than `tol` (0–255) in any
/// channel. On failure, the actual image and a difference image are written
/// next to the reference as `*.actual.png` and `*.diff.png`. A missing
/// reference is a failure (with `WORKBOOK_BLESS=1` it is written instead).
pub fn compare_with_reference(
    actual: &Path,
    reference: &Path,
    block: u32,
    tol: u8,
    max_bad_pct: f64,
) {
    let a = image::open(actual)
        .unwrap_or_else(|e| panic!("{}: {e}", actual.display()))
        .to_rgba8();
    if std::env::var("WORKBOOK_BLESS").is_ok_and(|v| v == "1") {
        a.save(reference).expect("write reference image");
        eprintln!("blessed {}", reference.display());
        return;
    }
    let r = match image::open(reference) {
        Ok(r) => r.to_rgba8(),
        Err(e) => panic!(
            "reference image {} is missing or unreadable ({e}); render it with WORKBOOK_BLESS=1 and look at it before committing",
            reference.display()
        ),
    };
    assert_eq!(
        a.dimensions(),
        r.dimensions(),
        "image size differs from {}",
        reference.display()
    );
    let (w, h) = a.dimensions();
    let (cw, ch) = (w.div_ceil(block), h.div_ceil(block));
    let mut bad = 0u32;
    let mut diff = image::RgbaImage::new(w, h);
    for cy in 0..ch {
        for cx in 0..cw {
            let mut sa = [0f64; 4];
            let mut sr = [0f64; 4];
            let mut n = 0f64;
            for y in cy * block..((cy + 1) * block).min(h) {
                for x in cx * block..((cx + 1) * block).min(w) {
                    for c in 0..4 {
                        sa[c] += a.get_pixel(x, y).0[c] as f64;
                        sr[c] += r.get_pixel(x, y).0[c] as f64;
                    }
                    n += 1.0;
                }
            }
            let d = (0..4)
                .map(|c| ((sa[c] - sr[c]) / n).abs())
                .fold(0.0, f64::max);
            let is_bad = d > tol as f64;
            bad += is_bad as u32;
            for y in cy * block..((cy + 1) * block).min(h) {
                for x in cx * block..((cx + 1) * block).min(w) {
                    let g = (d * 4.0).min(255.0) as u8;
                    diff.put_pixel(
                        x,
                        y,
                        if is_bad {
                            image::Rgba([255, 0, 0, 255])
                        } else {
                            image::Rgba([g, g, g, 255])
                        },
                    );
                }
            }
        }
    }
    let pct = 100.0 * bad as f64 / (cw * ch) as f64;
    if pct > max_bad_pct {
        let stem = reference.with_extension("");
        let act = PathBuf::from(format!("{}.actual.png", stem.display()));
        let dif = PathBuf::from(format!("{}.diff.png", stem.display()));
        a.save(&act).expect("write actual image");
        diff.save(&dif).expect("write diff image");
        panic!(
            "{} differs from {}: {pct:.2}% of {block}x{block} cells off by more than {tol} (allowed {max_bad_pct}%); wrote {} and {}",
            actual.display(),
            reference.display(),
            act.display(),
            dif.display()
        );
    }
}
