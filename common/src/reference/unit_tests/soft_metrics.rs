//! Unit tests of `common::reference::soft_metrics`: the soft figures per
//! class of receiver on a synthetic strip (umbra, a linear penumbra, lit),
//! the leak and the spill, the contours' width error, horizon-clipped
//! receivers, and the distance transform.

use super::*;
#[allow(unused_imports)]
use crate::reference::metrics::*;

const SW: u32 = 64;
const SH: u32 = 16;

/// The strip's exact visibility at column `x` (any row).
fn strip(x: f32) -> f32 {
    ((x - 15.0) / 33.0).clamp(0.0, 1.0)
}

/// The strip's image of `f(x, y)`.
fn strip_image(f: impl Fn(usize, usize) -> f32) -> Vec<f32> {
    (0..(SW * SH) as usize)
        .map(|p| f(p % SW as usize, p / SW as usize))
        .collect()
}

/// The soft figures of `gpu` against the strip.
fn strip_soft(gpu: &[f32], horizon_clipped: Option<&[bool]>) -> SoftError {
    let n = (SW * SH) as usize;
    let exact = strip_image(|x, _| strip(x as f32));
    let (ids, all) = (vec![1; n], vec![true; n]);
    soft_error(&SoftImages {
        width: SW,
        height: SH,
        object_id: &ids,
        receiver: &all,
        reference_receiver: &all,
        exact: &exact,
        gpu,
        horizon_clipped,
    })
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

#[test]
fn soft_classes_partition_the_strip() {
    let s = strip_soft(&strip_image(|x, _| strip(x as f32)), None);
    assert_eq!(
        (s.umbra_pixels, s.penumbra_pixels, s.lit_pixels),
        (256, 512, 256)
    );
    assert_eq!((s.deep_umbra_pixels, s.spill_pixels), (208, 96));
    assert_eq!(s.horizon_clipped_pixels, 0);
    let means = [
        s.umbra_mean_abs,
        s.penumbra_mean_abs,
        s.lit_mean_abs,
        s.leak_mean_abs,
        s.leak_pct,
        s.spill_mean_abs,
        s.light_bleeding_pct,
        s.umbra_misclassified_pct,
    ];
    assert!(means.iter().all(|&m| m == 0.0), "{s:?}");
    // Two contours of 16 pixels in each image.
    assert_eq!(
        (s.contour_pixels, s.penumbra_width_error_px),
        (64, Some(0.0))
    );
}

#[test]
fn a_hard_edge_in_the_middle_errs_in_the_penumbra_alone() {
    // V = 0 left of x = 32 (V_ref 16/33 < 0.5), 1 from there (17/33).
    let s = strip_soft(&strip_image(|x, _| if x < 32 { 0.0 } else { 1.0 }), None);
    // Per row: Σ k/33 for k = 1..16 on each side of the edge, over 32 columns.
    assert!(close(s.penumbra_mean_abs, 272.0 / (33.0 * 32.0)), "{s:?}");
    assert_eq!((s.umbra_mean_abs, s.lit_mean_abs), (0.0, 0.0));
    assert_eq!(
        (s.leak_mean_abs, s.leak_pct, s.spill_mean_abs),
        (0.0, 0.0, 0.0)
    );
    assert_eq!(s.light_bleeding_pct, 0.0);
    // Both of its contours at x = 32: 13 px from x = 19 and from x = 45.
    assert_eq!(s.penumbra_width_error_px, Some(13.0));
    assert_eq!(s.contour_pixels, 64);
}

#[test]
fn a_blur_too_wide_errs_in_the_umbra_and_on_the_lit_side() {
    // A ramp over the whole strip, V = (x + 0.5)/64: twice the penumbra.
    let blur = |x: usize| (x as f32 + 0.5) / 64.0;
    let s = strip_soft(&strip_image(|x, _| blur(x)), None);
    // Umbra: mean of (x + 0.5)/64 over x = 0..16; lit: of (63.5 − x)/64
    // over x = 48..64.
    assert!(close(s.umbra_mean_abs, 0.125), "{s:?}");
    assert!(close(s.lit_mean_abs, 0.125), "{s:?}");
    // Deep umbra x = 0..13: mean 6.5/64; lit above 0.1 from x = 6 (6.5/64).
    assert!(close(s.leak_mean_abs, 6.5 / 64.0), "{s:?}");
    assert!(close(s.leak_pct, 100.0 * 7.0 / 13.0), "{s:?}");
    // Umbra above 0.1 at x = 6..16: 10 of 16 columns; none above 0.5.
    assert!(close(s.light_bleeding_pct, 62.5), "{s:?}");
    assert_eq!(s.umbra_misclassified_pct, 0.0);
    // Rim x = 13, 14, 15 and fringe x = 48, 49, 50: 13.5 + 14.5 + 15.5
    // sixty-fourths on each side.
    assert!(close(s.spill_mean_abs, 2.0 * 43.5 / 64.0 / 6.0), "{s:?}");
    // The penumbra figure alone prefers the blur to a well-placed edge.
    let penumbra: f64 = (16..48)
        .map(|x| (blur(x) as f64 - (x as f64 - 15.0) / 33.0).abs())
        .sum::<f64>()
        / 32.0;
    assert!(close(s.penumbra_mean_abs, penumbra), "{s:?}");
    assert!(penumbra < 272.0 / (33.0 * 32.0));
    // Its 10 % contour at x = 6 (13 px out), its 90 % at x = 58 (13 px).
    assert_eq!(s.penumbra_width_error_px, Some(13.0));
}

#[test]
fn light_deep_in_the_umbra_is_a_leak_and_at_its_rim_a_spill() {
    // A 4 × 4 block at V = 0.5: x = 2..6, rows 4..8, deep in the umbra.
    let block = |x0: usize| {
        strip_image(move |x, y| {
            if (x0..x0 + 4).contains(&x) && (4..8).contains(&y) {
                0.5
            } else {
                strip(x as f32)
            }
        })
    };
    let deep = strip_soft(&block(2), None);
    assert!(close(deep.leak_mean_abs, 8.0 / 208.0), "{deep:?}");
    assert!(close(deep.leak_pct, 100.0 * 16.0 / 208.0), "{deep:?}");
    assert_eq!(deep.spill_mean_abs, 0.0);
    assert!(close(deep.umbra_mean_abs, 8.0 / 256.0), "{deep:?}");
    assert!(close(deep.light_bleeding_pct, 100.0 * 16.0 / 256.0));
    assert_eq!(deep.umbra_misclassified_pct, 0.0, "0.5 is not lit");
    // The block's 12 edge pixels join the 10 % contour, 14 to 17 px from
    // x = 19: (4·17 + 2·16 + 2·15 + 4·14) over 16 + 28 + 32 contour pixels.
    assert_eq!(deep.contour_pixels, 76);
    let width = deep.penumbra_width_error_px.expect("contours");
    assert!(close(width, 186.0 / 76.0), "{width}");
    // A 3 × 4 block in the rim, x = 13..16: spill, no leak.
    let rim = strip_soft(
        &strip_image(|x, y| {
            if (13..16).contains(&x) && (4..8).contains(&y) {
                0.5
            } else {
                strip(x as f32)
            }
        }),
        None,
    );
    assert_eq!((rim.leak_mean_abs, rim.leak_pct), (0.0, 0.0), "{rim:?}");
    assert!(close(rim.spill_mean_abs, 12.0 * 0.5 / 96.0), "{rim:?}");
    assert!(close(rim.light_bleeding_pct, 100.0 * 12.0 / 256.0));
}

#[test]
fn shadow_on_the_lit_side_is_spill_near_the_penumbra_and_lit_error_everywhere() {
    // The fringe x = 48..51 at 0.7, acne at x = 60 (0.4).
    let gpu = strip_image(|x, _| match x {
        48..=50 => 0.7,
        60 => 0.4,
        _ => strip(x as f32),
    });
    let s = strip_soft(&gpu, None);
    assert!(close(s.spill_mean_abs, 48.0 * 0.3 / 96.0), "{s:?}");
    assert!(
        close(s.lit_mean_abs, (48.0 * 0.3 + 16.0 * 0.6) / 256.0),
        "{s:?}"
    );
    assert_eq!((s.umbra_mean_abs, s.leak_mean_abs), (0.0, 0.0));
    assert_eq!(s.penumbra_mean_abs, 0.0);
    assert_eq!(s.lit_pixels, 256);
}

#[test]
fn a_shifted_penumbra_scores_its_shift() {
    for shift in [5.0, -4.0, 2.5] {
        let s = strip_soft(&strip_image(|x, _| strip(x as f32 - shift)), None);
        let width = s.penumbra_width_error_px.expect("contours");
        // Whole shifts exactly; 2.5 moves the 10 % contour by 2 pixels and
        // the 90 % one by 3.
        assert!(
            (width - shift.abs() as f64).abs() <= 0.5,
            "shift {shift}: {width}"
        );
        if shift.fract() == 0.0 {
            assert_eq!(width, shift.abs() as f64);
        }
    }
}

#[test]
fn a_missing_contour_gives_no_width_error() {
    // The technique lights everything: no contour where the reference has two.
    let lit = strip_soft(&vec![1.0; (SW * SH) as usize], None);
    assert_eq!(lit.penumbra_width_error_px, None);
    assert_eq!(lit.contour_pixels, 32, "the reference's two contours");
    // Neither has a contour: an all-lit reference and technique.
    let n = (SW * SH) as usize;
    let (ids, all, one) = (vec![1; n], vec![true; n], vec![1.0f32; n]);
    let im = SoftImages {
        width: SW,
        height: SH,
        object_id: &ids,
        receiver: &all,
        reference_receiver: &all,
        exact: &one,
        gpu: &one,
        horizon_clipped: None,
    };
    let none = soft_error(&im);
    assert_eq!(
        (none.contour_pixels, none.penumbra_width_error_px),
        (0, None)
    );
    // A reference with only a 90 % contour and a technique that agrees:
    // the 10 % level, empty in both, is left out.
    let light = strip_image(|x, _| if x < 32 { 0.5 } else { 1.0 });
    let soft = soft_error(&SoftImages {
        exact: &light,
        gpu: &light,
        ..im
    });
    assert_eq!(
        (soft.contour_pixels, soft.penumbra_width_error_px),
        (32, Some(0.0))
    );
    // A contour between two objects is no contour.
    let two = strip_image(|x, _| if x < 32 { 0.0 } else { 1.0 });
    let objects: Vec<u32> = (0..n)
        .map(|p| 1 + u32::from(p % SW as usize >= 32))
        .collect();
    let apart = soft_error(&SoftImages {
        object_id: &objects,
        exact: &two,
        gpu: &two,
        ..im
    });
    assert_eq!(
        (apart.contour_pixels, apart.penumbra_width_error_px),
        (0, None)
    );
}

#[test]
fn horizon_clipped_receivers_are_counted_apart() {
    // Flagged: the penumbra column x = 30 (V_ref 15/33), which the
    // technique lights fully, and the lit column x = 60, which it halves.
    let gpu = strip_image(|x, _| match x {
        30 => 1.0,
        60 => 0.5,
        _ => strip(x as f32),
    });
    let flags: Vec<bool> = (0..(SW * SH) as usize)
        .map(|p| matches!(p % SW as usize, 30 | 60))
        .collect();
    let s = strip_soft(&gpu, Some(&flags));
    assert_eq!(s.horizon_clipped_pixels, 32);
    let off = 18.0 / 33.0;
    assert!(
        close(s.horizon_clipped_mean_abs, (off + 0.5) / 2.0),
        "{s:?}"
    );
    assert_eq!(
        (s.penumbra_pixels, s.lit_pixels, s.umbra_pixels),
        (496, 240, 256)
    );
    assert_eq!((s.penumbra_mean_abs, s.lit_mean_abs), (0.0, 0.0));
    // Kept out of the contours too.
    assert_eq!(s.penumbra_width_error_px, Some(0.0));
    // Without the flag they are penumbra and lit receivers like any other.
    let none = strip_soft(&gpu, None);
    assert_eq!(
        (none.horizon_clipped_pixels, none.horizon_clipped_mean_abs),
        (0, 0.0)
    );
    assert_eq!((none.penumbra_pixels, none.lit_pixels), (512, 256));
    assert!(
        close(none.penumbra_mean_abs, 16.0 * off / 512.0),
        "{none:?}"
    );
    assert!(close(none.lit_mean_abs, 8.0 / 256.0), "{none:?}");
    assert!(none.penumbra_width_error_px.expect("contours") > 0.0);
}

#[test]
fn distance_to_is_the_euclidean_distance_to_the_nearest_site() {
    let (w, h) = (9, 7);
    let sites = [(1, 1), (7, 2), (4, 6)];
    let site: Vec<bool> = (0..w * h)
        .map(|p| sites.contains(&(p % w, p / w)))
        .collect();
    let d = distance_to(&site, w, h);
    for (p, &got) in d.iter().enumerate() {
        let (x, y) = ((p % w) as f32, (p / w) as f32);
        let brute = sites
            .iter()
            .map(|&(sx, sy)| ((x - sx as f32).powi(2) + (y - sy as f32).powi(2)).sqrt())
            .fold(f32::INFINITY, f32::min);
        assert!((got - brute).abs() < 1e-5, "pixel {p}: {got} vs {brute}");
    }
    assert!(distance_to(&[false; 6], 3, 2)
        .iter()
        .all(|d| d.is_infinite()));
}
