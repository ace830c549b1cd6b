//! How wrong a GPU visibility image is, against the exact reference.
//!
//! Only *receiver* pixels count (INTERFACES.md): geometry covers the pixel,
//! its geometric normal faces the light (N·L > [`RECEIVER_MIN_N_DOT_L`], which
//! also leaves out pixels beyond a light's range or cone), and the GPU and the
//! reference see the same object there. The pixels where they do not are
//! counted apart ([`ErrorStats::coverage_mismatch_pct`]), so that a broken
//! image cannot hide behind a small receiver set.

use image::{GrayAlphaImage, LumaA, Rgba, RgbaImage};
use serde::Serialize;

use crate::reference::Reference;

/// Receivers face the light at least this much (geometric N·L).
pub const RECEIVER_MIN_N_DOT_L: f32 = 0.05;

/// A pixel counts as lit from this visibility up.
pub const LIT_THRESHOLD: f32 = 0.5;

/// Error of one light's visibility. Percentages are of receiver pixels.
#[derive(Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct ErrorStats {
    pub receiver_pixels: u64,
    /// `false_shadow_pct + false_lit_pct`.
    pub misclassified_pct: f64,
    /// Lit in the reference, shadowed on the GPU (acne, over-darkening).
    pub false_shadow_pct: f64,
    /// Shadowed in the reference, lit on the GPU (leaks, Peter Panning).
    pub false_lit_pct: f64,
    /// Mean |GPU − reference| visibility.
    pub mean_abs: f64,
    /// Of the pixels that either the GPU or the reference covers, the share
    /// (%) where the two see different objects (or one sees nothing). They
    /// are left out of the receivers; above [`COVERAGE_WARN_PCT`] the run warns.
    pub coverage_mismatch_pct: f64,
    /// Receivers farther than [`EDGE_MARGIN_PX`] pixels from every edge of
    /// the reference image: a change of surface, or of lit and shadowed.
    pub interior_receiver_pixels: u64,
    /// Misclassified % of the interior receivers: the error that is not
    /// a matter of edge pixels (the pass criteria "away from silhouettes").
    pub interior_misclassified_pct: f64,
}

/// How far (pixels, in x and y) an interior receiver is from every edge.
pub const EDGE_MARGIN_PX: i64 = 2;

/// Above this coverage mismatch (%) a headless run prints a warning line.
pub const COVERAGE_WARN_PCT: f64 = 1.0;

/// The statistics and the picture of where the errors are.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub stats: ErrorStats,
    /// False shadow red, false lit green, other receivers grey (brighter where
    /// the reference is lit), other covered pixels dark, the rest transparent.
    pub diff: RgbaImage,
}

pub const FALSE_SHADOW: Rgba<u8> = Rgba([255, 0, 0, 255]);
pub const FALSE_LIT: Rgba<u8> = Rgba([0, 255, 0, 255]);
pub const NOT_RECEIVER: Rgba<u8> = Rgba([24, 24, 24, 255]);
pub const UNCOVERED: Rgba<u8> = Rgba([0, 0, 0, 0]);

/// A receiver the GPU got right: dim grey, 48 (shadowed) to 128 (lit).
pub fn agree_colour(reference_visibility: f32) -> Rgba<u8> {
    let g = 48 + (80.0 * reference_visibility.clamp(0.0, 1.0)).round() as u8;
    Rgba([g, g, g, 255])
}

/// The reference's object id image: 0 where nothing was hit, else object + 1
/// (the GPU's convention).
pub fn reference_object_ids(reference: &Reference) -> Vec<u32> {
    reference
        .hits
        .iter()
        .map(|h| h.map_or(0, |h| h.object + 1))
        .collect()
}

// ANCHOR: compare
/// Compares the GPU's visibility for `light` with the reference.
/// `gpu_object_id[p]` is 0 where the GPU covered nothing, else object + 1.
///
/// Panics if the images are not `width × height` of the reference.
pub fn compare(
    reference: &Reference,
    light: usize,
    gpu_object_id: &[u32],
    gpu_visibility: &[f32],
) -> Comparison {
    let (w, h) = (reference.width, reference.height);
    let n = w as usize * h as usize;
    assert_eq!(gpu_object_id.len(), n, "object id image is not {w}x{h}");
    assert_eq!(gpu_visibility.len(), n, "visibility image is not {w}x{h}");
    let (ref_vis, lit_by) = (&reference.visibility[light], &reference.lit_by[light]);

    let mut diff = RgbaImage::new(w, h);
    let (mut receivers, mut false_shadow, mut false_lit) = (0u64, 0u64, 0u64);
    let (mut covered, mut mismatched) = (0u64, 0u64);
    let mut abs_sum = 0.0f64;
    for p in 0..n {
        let hit = reference.hits[p];
        let same_surface = hit.is_some_and(|hit| gpu_object_id[p] == hit.object + 1);
        if hit.is_some() || gpu_object_id[p] != 0 {
            covered += 1;
            mismatched += u64::from(!same_surface);
        }
        let colour = if same_surface && lit_by[p] > RECEIVER_MIN_N_DOT_L {
            receivers += 1;
            let (gpu, exact) = (gpu_visibility[p], ref_vis[p]);
            abs_sum += (gpu - exact).abs() as f64;
            match (exact >= LIT_THRESHOLD, gpu >= LIT_THRESHOLD) {
                (true, false) => {
                    false_shadow += 1;
                    FALSE_SHADOW
                }
                (false, true) => {
                    false_lit += 1;
                    FALSE_LIT
                }
                _ => agree_colour(exact),
            }
        } else if hit.is_some() || gpu_object_id[p] != 0 {
            NOT_RECEIVER
        } else {
            UNCOVERED
        };
        diff.put_pixel(p as u32 % w, p as u32 / w, colour);
    }

    // Interior receivers: no pixel within EDGE_MARGIN_PX sees another
    // surface or the other side of the reference's lit/shadowed boundary.
    let class = |p: usize| {
        let object = reference.hits[p].map_or(0, |h| h.object + 1);
        (object, ref_vis[p] >= LIT_THRESHOLD)
    };
    let (mut interior, mut interior_wrong) = (0u64, 0u64);
    let m = EDGE_MARGIN_PX;
    for (p, colour) in diff.pixels().enumerate() {
        let wrong = *colour == FALSE_SHADOW || *colour == FALSE_LIT;
        if !wrong && (colour.0[3] != 255 || *colour == NOT_RECEIVER) {
            continue;
        }
        let (x, y) = ((p % w as usize) as i64, (p / w as usize) as i64);
        let c = class(p);
        let near_edge = (-m..=m).any(|dy| {
            (-m..=m).any(|dx| {
                let (nx, ny) = (x + dx, y + dy);
                (0..w as i64).contains(&nx)
                    && (0..h as i64).contains(&ny)
                    && class((ny * w as i64 + nx) as usize) != c
            })
        });
        if !near_edge {
            interior += 1;
            interior_wrong += u64::from(wrong);
        }
    }

    // With no receivers every count is 0, and so is every figure.
    let of = receivers.max(1) as f64;
    let pct = |count: u64| 100.0 * count as f64 / of;
    let stats = ErrorStats {
        receiver_pixels: receivers,
        misclassified_pct: pct(false_shadow + false_lit),
        false_shadow_pct: pct(false_shadow),
        false_lit_pct: pct(false_lit),
        mean_abs: abs_sum / of,
        coverage_mismatch_pct: 100.0 * mismatched as f64 / covered.max(1) as f64,
        interior_receiver_pixels: interior,
        interior_misclassified_pct: 100.0 * interior_wrong as f64 / interior.max(1) as f64,
    };
    Comparison { stats, diff }
}
// ANCHOR_END: compare

/// The `*_visibility_l<k>.png` image of INTERFACES.md: gray = round(255·v),
/// alpha 0 where no geometry covers the pixel, 255 elsewhere.
pub fn visibility_image(object_id: &[u32], visibility: &[f32], w: u32, h: u32) -> GrayAlphaImage {
    let n = w as usize * h as usize;
    assert!(
        object_id.len() == n && visibility.len() == n,
        "visibility images must be {w}x{h}"
    );
    GrayAlphaImage::from_fn(w, h, |x, y| {
        let p = (y * w + x) as usize;
        let gray = (255.0 * visibility[p].clamp(0.0, 1.0)).round() as u8;
        LumaA([gray, if object_id[p] == 0 { 0 } else { 255 }])
    })
}

/// [`visibility_image`] of the reference for `light`.
pub fn reference_visibility_image(reference: &Reference, light: usize) -> GrayAlphaImage {
    let ids = reference_object_ids(reference);
    visibility_image(
        &ids,
        &reference.visibility[light],
        reference.width,
        reference.height,
    )
}

// ANCHOR: ascii_mask
/// A coarse text picture of a visibility image, for snapshot tests: `cols ×
/// rows` cells, rows joined by `'\n'`. A cell is `' '` when more than half of
/// its pixels are uncovered, else `'#'` when more covered pixels are shadowed
/// (v < 0.5) than lit, else `'.'` (ties go to the surface, then to lit).
pub fn ascii_mask(
    object_id: &[u32],
    visibility: &[f32],
    w: u32,
    h: u32,
    cols: u32,
    rows: u32,
) -> String {
    let n = w as usize * h as usize;
    assert!(
        object_id.len() == n && visibility.len() == n,
        "visibility images must be {w}x{h}"
    );
    let mut out = String::with_capacity(((cols + 1) * rows) as usize);
    for r in 0..rows {
        if r > 0 {
            out.push('\n');
        }
        // Cell edges at floor(k·size/cells): every pixel lands in exactly one cell.
        let (y0, y1) = (
            r as u64 * h as u64 / rows as u64,
            (r + 1) as u64 * h as u64 / rows as u64,
        );
        for c in 0..cols {
            let (x0, x1) = (
                c as u64 * w as u64 / cols as u64,
                (c + 1) as u64 * w as u64 / cols as u64,
            );
            let (mut uncovered, mut shadowed, mut lit) = (0u64, 0u64, 0u64);
            for y in y0..y1 {
                for x in x0..x1 {
                    let p = (y * w as u64 + x) as usize;
                    if object_id[p] == 0 {
                        uncovered += 1;
                    } else if visibility[p] < LIT_THRESHOLD {
                        shadowed += 1;
                    } else {
                        lit += 1;
                    }
                }
            }
            let covered = shadowed + lit;
            // An empty cell (more cells than pixels) is blank too.
            out.push(if covered == 0 || uncovered > covered {
                ' '
            } else if shadowed > lit {
                '#'
            } else {
                '.'
            });
        }
    }
    out
}
// ANCHOR_END: ascii_mask

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::reference::PixelHit;

    /// A one-light reference from per-pixel (object hit, visibility, N·L).
    fn reference(w: u32, h: u32, pixels: &[(Option<u32>, f32, f32)]) -> Reference {
        let hit = |object| PixelHit {
            object,
            triangle: 0,
            t: 1.0,
            position: Vec3::ZERO,
            normal: Vec3::Y,
        };
        Reference {
            width: w,
            height: h,
            hits: pixels.iter().map(|&(o, _, _)| o.map(hit)).collect(),
            visibility: vec![pixels.iter().map(|&(_, v, _)| v).collect()],
            lit_by: vec![pixels.iter().map(|&(_, _, l)| l).collect()],
            ms: 0.0,
        }
    }

    #[test]
    fn counts_false_shadow_and_false_lit_among_receivers() {
        // 10 receivers on object 0: 6 lit, 4 shadowed in the reference.
        let mut px = Vec::new();
        let mut gpu = Vec::new();
        for k in 0..10 {
            let exact = if k < 6 { 1.0 } else { 0.0 };
            px.push((Some(0), exact, 0.8));
            // Pixels 0 and 1: false shadow (0.25 off, 0.4 off); pixel 6: false lit (0.7 off).
            gpu.push(match k {
                0 => 0.25,
                1 => 0.4,
                6 => 0.7,
                _ => exact,
            });
        }
        // Not receivers: grazing light, a miss, an object mismatch, outside the light (N·L 0).
        px.extend([
            (Some(0), 1.0, 0.05),
            (None, 0.0, 0.0),
            (Some(1), 1.0, 0.9),
            (Some(0), 0.0, 0.0),
        ]);
        gpu.extend([0.0, 1.0, 0.0, 1.0]);
        let ids = [vec![1; 10], vec![1, 0, 3, 1]].concat(); // 3: the GPU sees object 2 there
        let r = reference(14, 1, &px);
        let s = compare(&r, 0, &ids, &gpu).stats;
        assert_eq!(s.receiver_pixels, 10);
        // 13 covered pixels (all but the miss), 1 where the GPU sees another object.
        assert!(
            (s.coverage_mismatch_pct - 100.0 / 13.0).abs() < 1e-9,
            "coverage mismatch {}",
            s.coverage_mismatch_pct
        );
        assert_eq!(
            (s.misclassified_pct, s.false_shadow_pct, s.false_lit_pct),
            (30.0, 20.0, 10.0)
        );
        assert!(
            (s.mean_abs - (0.75 + 0.6 + 0.7) / 10.0).abs() < 1e-7,
            "mean_abs {}",
            s.mean_abs
        );
    }

    #[test]
    fn interior_error_leaves_out_edge_pixels() {
        // One row of 12 receivers: lit in the reference at 0..6, shadowed at
        // 6..12. Interior (no other class within 2 px): 0..4 and 8..12.
        let px: Vec<_> = (0..12)
            .map(|k| (Some(0), if k < 6 { 1.0 } else { 0.0 }, 0.8))
            .collect();
        let r = reference(12, 1, &px);
        let ids = vec![1; 12];
        let gpu = |wrong: usize| -> Vec<f32> {
            (0..12)
                .map(|k| if (k < 6) != (k == wrong) { 1.0 } else { 0.0 })
                .collect()
        };
        // Wrong at the edge pixel 6 only: 1 of 12 overall, none inside.
        let edge = compare(&r, 0, &ids, &gpu(6)).stats;
        assert_eq!(edge.interior_receiver_pixels, 8);
        assert!((edge.misclassified_pct - 100.0 / 12.0).abs() < 1e-9);
        assert_eq!(edge.interior_misclassified_pct, 0.0);
        // Wrong at pixel 10, deep in the shadow: 1 of the 8 interior.
        let inside = compare(&r, 0, &ids, &gpu(10)).stats;
        assert!((inside.interior_misclassified_pct - 12.5).abs() < 1e-9);
    }

    #[test]
    fn no_receivers_gives_zeros() {
        let r = reference(
            3,
            1,
            &[(None, 0.0, 0.0), (Some(0), 1.0, 0.01), (Some(2), 1.0, 1.0)],
        );
        let c = compare(&r, 0, &[0, 1, 1], &[1.0, 0.0, 0.0]);
        assert_eq!(
            c.stats,
            ErrorStats {
                receiver_pixels: 0,
                misclassified_pct: 0.0,
                false_shadow_pct: 0.0,
                false_lit_pct: 0.0,
                mean_abs: 0.0,
                // Pixel 0 is covered by neither; pixels 1 (object 0 on both)
                // and 2 (object 2 in the reference, object 0 on the GPU) are
                // covered, and pixel 2 is a mismatch.
                coverage_mismatch_pct: 50.0,
                interior_receiver_pixels: 0,
                interior_misclassified_pct: 0.0,
            }
        );
    }

    #[test]
    fn diff_image_colours() {
        // false shadow, false lit, agree lit, agree shadowed, not a receiver, uncovered,
        // and covered on the GPU only.
        let r = reference(
            7,
            1,
            &[
                (Some(0), 1.0, 1.0),
                (Some(0), 0.0, 1.0),
                (Some(0), 1.0, 1.0),
                (Some(0), 0.0, 1.0),
                (Some(0), 1.0, 0.0),
                (None, 0.0, 0.0),
                (None, 0.0, 0.0),
            ],
        );
        let c = compare(
            &r,
            0,
            &[1, 1, 1, 1, 1, 0, 1],
            &[0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0],
        );
        let got: Vec<Rgba<u8>> = c.diff.pixels().copied().collect();
        assert_eq!(
            got,
            vec![
                FALSE_SHADOW,
                FALSE_LIT,
                Rgba([128, 128, 128, 255]),
                Rgba([48, 48, 48, 255]),
                NOT_RECEIVER,
                UNCOVERED,
                NOT_RECEIVER
            ]
        );
        assert_eq!(
            (
                c.stats.receiver_pixels,
                c.stats.false_shadow_pct,
                c.stats.false_lit_pct
            ),
            (4, 25.0, 25.0)
        );
    }

    #[test]
    fn visibility_images_follow_the_interface() {
        let img = visibility_image(&[0, 1, 2, 1], &[0.5, 1.0, 0.0, 0.2], 2, 2);
        let got: Vec<[u8; 2]> = img.pixels().map(|p| p.0).collect();
        assert_eq!(got, vec![[128, 0], [255, 255], [0, 255], [51, 255]]);
        let r = reference(2, 1, &[(None, 0.0, 0.0), (Some(3), 1.0, 1.0)]);
        let got: Vec<[u8; 2]> = reference_visibility_image(&r, 0)
            .pixels()
            .map(|p| p.0)
            .collect();
        assert_eq!(got, vec![[0, 0], [255, 255]]);
    }

    #[test]
    fn ascii_mask_majority_per_cell() {
        // 4x2 image in 2x1 cells of 2x2 pixels each... then a 1x2 grid.
        let ids = [0, 0, 1, 1, 0, 1, 1, 1];
        let vis = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0];
        // Left cell: 3 uncovered of 4 -> ' '. Right cell: 2 shadowed, 2 lit -> tie -> '.'.
        assert_eq!(ascii_mask(&ids, &vis, 4, 2, 2, 1), " .");
        // One column, two rows: top row 2 uncovered vs 2 covered (1 shadowed, 1 lit) -> '.';
        // bottom row 1 uncovered, 2 shadowed, 1 lit -> '#'.
        assert_eq!(ascii_mask(&ids, &vis, 4, 2, 1, 2), ".\n#");
        // More cells than pixels: empty cells are blank.
        assert_eq!(ascii_mask(&[1], &[0.0], 1, 1, 2, 2), "  \n #");
        assert_eq!(ascii_mask(&[1, 1], &[0.2, 0.9], 2, 1, 2, 1), "#.");
    }
}
