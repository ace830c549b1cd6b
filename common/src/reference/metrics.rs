//! How wrong a GPU visibility image is, against the exact reference.
//!
//! Only *receiver* pixels count (the book's appendix "Interfaces",
//! `book/src/appendix/interfaces.md`): geometry covers the pixel,
//! its geometric normal faces the light (N·L > [`RECEIVER_MIN_N_DOT_L`], which
//! also leaves out pixels beyond a light's range or cone), and the GPU and the
//! reference see the same object there. The pixels where they do not are
//! counted apart ([`ErrorStats::coverage_mismatch_pct`]), so that a broken
//! image cannot hide behind a small receiver set.

use image::{GrayAlphaImage, LumaA, Rgba, RgbaImage};
use serde::Serialize;

use glam::Vec3;

use crate::reference::{PixelHit, Reference};

pub use crate::reference::soft_metrics::*;

/// Receivers face the light at least this much (geometric N·L).
pub const RECEIVER_MIN_N_DOT_L: f32 = 0.05;

/// The pixels that are receivers of some light in the reference alone
/// (geometry hit, N·L above [`RECEIVER_MIN_N_DOT_L`] inside the light's
/// reach): with none, no error figure means anything.
pub fn reference_receivers(reference: &Reference) -> u64 {
    let n = reference.hits.len();
    let receiver = |p: usize| {
        reference.hits[p].is_some() && reference.lit_by.iter().any(|l| l[p] > RECEIVER_MIN_N_DOT_L)
    };
    (0..n).filter(|&p| receiver(p)).count() as u64
}

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
    /// A light with a size (lesson 10): the soft shadow's own figures.
    #[serde(flatten, default, skip_serializing_if = "Option::is_none")]
    pub soft: Option<SoftError>,
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
/// `horizon_clipped[p]`, when given, flags the pixels where part of the
/// light's emitter lies below the receiver's own tangent plane: an area
/// light's [`SoftError`] counts them apart
/// ([`SoftError::horizon_clipped_pixels`]). `None` counts none apart.
///
/// Panics if the images (and the flags) are not `width × height` of the
/// reference.
pub fn compare(
    reference: &Reference,
    light: usize,
    gpu_object_id: &[u32],
    gpu_visibility: &[f32],
    horizon_clipped: Option<&[bool]>,
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
    // The receivers, for the soft figures.
    let mut receiver = vec![false; n];
    for p in 0..n {
        let hit = reference.hits[p];
        let same_surface = hit.is_some_and(|hit| gpu_object_id[p] == hit.object + 1);
        if hit.is_some() || gpu_object_id[p] != 0 {
            covered += 1;
            mismatched += u64::from(!same_surface);
        }
        let colour = if same_surface && lit_by[p] > RECEIVER_MIN_N_DOT_L {
            receivers += 1;
            receiver[p] = true;
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
    let near_edge = near_edge(reference, ref_vis);
    let (mut interior, mut interior_wrong) = (0u64, 0u64);
    for (p, colour) in diff.pixels().enumerate() {
        let wrong = *colour == FALSE_SHADOW || *colour == FALSE_LIT;
        if !wrong && (colour.0[3] != 255 || *colour == NOT_RECEIVER) {
            continue;
        }
        if !near_edge[p] {
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
        soft: reference.area_light[light].then(|| {
            let object_id = reference_object_ids(reference);
            let reference_receiver: Vec<bool> = (0..n)
                .map(|p| reference.hits[p].is_some() && lit_by[p] > RECEIVER_MIN_N_DOT_L)
                .collect();
            soft_error(&SoftImages {
                width: w,
                height: h,
                object_id: &object_id,
                receiver: &receiver,
                reference_receiver: &reference_receiver,
                exact: ref_vis,
                gpu: gpu_visibility,
                horizon_clipped,
            })
        }),
    };
    Comparison { stats, diff }
}

/// Per pixel: whether a pixel within [`EDGE_MARGIN_PX`] (in the image)
/// sees another surface, or the other side of the reference's
/// lit/shadowed boundary. Each pixel's class is a key; a pixel is near an
/// edge unless the least and the greatest key over its square window are
/// both its own, found a row and then a column at a time.
fn near_edge(reference: &Reference, ref_vis: &[f32]) -> Vec<bool> {
    let (w, h) = (reference.width as usize, reference.height as usize);
    let key: Vec<u64> = (0..w * h)
        .map(|p| {
            let object = reference.hits[p].map_or(0, |h| h.object as u64 + 1);
            object * 2 + u64::from(ref_vis[p] >= LIT_THRESHOLD)
        })
        .collect();
    let m = EDGE_MARGIN_PX as usize;
    // Least and greatest over [i − m, i + m] ∩ [0, len) of `at(i)`.
    let window =
        |len: usize, at: &dyn Fn(usize) -> (u64, u64), out: &mut dyn FnMut(usize, (u64, u64))| {
            for i in 0..len {
                let (lo, hi) = (i.saturating_sub(m), (i + m).min(len - 1));
                let both = (lo..=hi)
                    .map(at)
                    .fold((u64::MAX, 0), |(least, most), (l, m)| {
                        (least.min(l), most.max(m))
                    });
                out(i, both);
            }
        };
    let mut rows = vec![(0u64, 0u64); w * h];
    for y in 0..h {
        let row = &key[y * w..(y + 1) * w];
        window(w, &|x| (row[x], row[x]), &mut |x, r| rows[y * w + x] = r);
    }
    let mut near = vec![false; w * h];
    for x in 0..w {
        window(h, &|y| rows[y * w + x], &mut |y, (least, most)| {
            let k = key[y * w + x];
            near[y * w + x] = least != k || most != k;
        });
    }
    near
}
// ANCHOR_END: compare

/// The `*_visibility_l<k>.png` image ("Outputs of a headless run" in
/// `book/src/appendix/interfaces.md`): gray = round(255·v),
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

// ANCHOR: pixel_states
/// The reference cut down to what classifying a pixel needs, one byte a
/// pixel and light beside the object id (its hits take 40): a camera path
/// keeps one per frame.
#[derive(Clone, Debug)]
pub struct ReferenceStates {
    /// 0 where nothing was hit, else object + 1 ([`reference_object_ids`]).
    pub object_id: Vec<u32>,
    /// `lit[k][p]`: `None` where `p` cannot be a receiver of light `k`
    /// (nothing hit, or N·L at most [`RECEIVER_MIN_N_DOT_L`]), else whether
    /// the reference lights it.
    pub lit: Vec<Vec<Option<bool>>>,
}

impl ReferenceStates {
    pub fn new(reference: &Reference) -> ReferenceStates {
        let lit = (reference.visibility.iter().zip(&reference.lit_by))
            .map(|(vis, by)| {
                let state = |(&v, &n_dot_l): (&f32, &f32)| {
                    (n_dot_l > RECEIVER_MIN_N_DOT_L).then_some(v >= LIT_THRESHOLD)
                };
                vis.iter().zip(by).map(state).collect()
            })
            .collect();
        ReferenceStates {
            object_id: reference_object_ids(reference),
            lit,
        }
    }
}

/// A receiver's `(reference lit, technique lit)`; `None` for other pixels.
pub type PixelState = Option<(bool, bool)>;

/// One light's [`PixelState`] per pixel: the receivers and the lit test of
/// [`compare`] (the GPU sees the reference's surface, which faces the light).
///
/// Panics if the images are not the reference's size.
pub fn pixel_states(
    reference: &ReferenceStates,
    light: usize,
    gpu_object_id: &[u32],
    gpu_visibility: &[f32],
) -> Vec<PixelState> {
    let n = reference.object_id.len();
    assert!(
        gpu_object_id.len() == n && gpu_visibility.len() == n,
        "GPU images must have the reference's {n} pixels"
    );
    let ids = reference.object_id.iter().zip(gpu_object_id);
    (ids.zip(&reference.lit[light]).zip(gpu_visibility))
        .map(|(((&exact_id, &gpu_id), &exact_lit), &v)| {
            let same_surface = exact_id != 0 && gpu_id == exact_id;
            exact_lit
                .filter(|_| same_surface)
                .map(|e| (e, v >= LIT_THRESHOLD))
        })
        .collect()
}
// ANCHOR_END: pixel_states

/// The error over the pixels of one class (lesson 09: one cascade), all
/// lights pooled as in [`crate::measure::report::combine`]. Percentages are of
/// `pixels`, the receivers in the class.
#[derive(Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct ClassError {
    pub name: String,
    pub pixels: u64,
    pub misclassified_pct: f64,
    pub false_shadow_pct: f64,
    pub false_lit_pct: f64,
}

/// [`ClassError`] per class: `class_of[p]` indexes `names`, and
/// `per_light[k]` is light `k`'s [`pixel_states`]. A class list that does
/// not fit the image is the lesson's error, one line.
pub fn class_errors(
    names: &[String],
    class_of: &[u8],
    per_light: &[Vec<PixelState>],
) -> anyhow::Result<Vec<ClassError>> {
    // (receivers, false shadow, false lit) per class.
    let mut counts = vec![(0u64, 0u64, 0u64); names.len()];
    for states in per_light {
        if states.len() != class_of.len() {
            anyhow::bail!(
                "pixel_classes: {} class indices for {} pixels",
                class_of.len(),
                states.len()
            );
        }
        for (&c, s) in class_of.iter().zip(states) {
            let Some((exact, gpu)) = *s else { continue };
            let Some(n) = counts.get_mut(c as usize) else {
                anyhow::bail!(
                    "pixel_classes: class index {c}, but only {} class names",
                    names.len()
                );
            };
            n.0 += 1;
            n.1 += u64::from(exact && !gpu);
            n.2 += u64::from(!exact && gpu);
        }
    }
    let errors = names.iter().zip(counts);
    Ok(errors
        .map(|(name, (pixels, shadow, lit))| {
            let pct = |k: u64| 100.0 * k as f64 / pixels.max(1) as f64;
            ClassError {
                name: name.clone(),
                pixels,
                misclassified_pct: pct(shadow + lit),
                false_shadow_pct: pct(shadow),
                false_lit_pct: pct(lit),
            }
        })
        .collect())
}

/// Per pixel, the distance along the camera's unit `forward` axis from the
/// origin-relative `eye` to the reference's hit; NaN where nothing is hit.
pub fn view_depth(reference: &Reference, eye: Vec3, forward: Vec3) -> Vec<f32> {
    let depth = |h: &Option<PixelHit>| h.map_or(f32::NAN, |h| (h.position - eye).dot(forward));
    reference.hits.iter().map(depth).collect()
}

#[cfg(test)]
#[path = "unit_tests/metrics.rs"]
mod tests;
