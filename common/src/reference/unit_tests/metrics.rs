//! Unit tests of `common::reference::metrics` (kept apart so the module stays short).

use super::*;

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
        area_light: vec![false],
        horizon_clipped: vec![vec![false; pixels.len()]],
        ms: 0.0,
        shadow_rays: 0,
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
    let s = compare(&r, 0, &ids, &gpu, None).stats;
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
    let edge = compare(&r, 0, &ids, &gpu(6), None).stats;
    assert_eq!(edge.interior_receiver_pixels, 8);
    assert!((edge.misclassified_pct - 100.0 / 12.0).abs() < 1e-9);
    assert_eq!(edge.interior_misclassified_pct, 0.0);
    // Wrong at pixel 10, deep in the shadow: 1 of the 8 interior.
    let inside = compare(&r, 0, &ids, &gpu(10), None).stats;
    assert!((inside.interior_misclassified_pct - 12.5).abs() < 1e-9);
}

#[test]
fn no_receivers_gives_zeros() {
    let r = reference(
        3,
        1,
        &[(None, 0.0, 0.0), (Some(0), 1.0, 0.01), (Some(2), 1.0, 1.0)],
    );
    let c = compare(&r, 0, &[0, 1, 1], &[1.0, 0.0, 0.0], None);
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
            soft: None,
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
        None,
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

#[test]
fn pixel_states_use_compares_receivers_and_lit_test() {
    // Receiver lit/shadowed, grazing (N·L 0.05), another object on the GPU,
    // a miss, and a receiver the GPU gets wrong.
    let r = reference(
        6,
        1,
        &[
            (Some(0), 1.0, 0.8),
            (Some(0), 0.0, 0.8),
            (Some(0), 1.0, 0.05),
            (Some(1), 1.0, 0.9),
            (None, 0.0, 0.0),
            (Some(0), 0.0, 0.8),
        ],
    );
    let ids = [1, 1, 1, 1, 0, 1];
    let gpu = [0.5, 0.49, 1.0, 1.0, 1.0, 0.7];
    let states = pixel_states(&ReferenceStates::new(&r), 0, &ids, &gpu);
    let want = [
        Some((true, true)),
        Some((false, false)),
        None,
        None,
        None,
        Some((false, true)),
    ];
    assert_eq!(states, want);
    // The same receivers, and the same errors, as `compare`.
    let s = compare(&r, 0, &ids, &gpu, None).stats;
    assert_eq!(s.receiver_pixels, 3);
    assert!((s.false_lit_pct - 100.0 / 3.0).abs() < 1e-9);
}

#[test]
fn class_errors_break_the_error_down_per_class() {
    let names = vec!["near".to_string(), "far".to_string(), "empty".to_string()];
    // Two lights. Class 0: pixels 0, 1; class 1: pixels 2, 3.
    let class_of = [0, 0, 1, 1];
    let light0 = vec![
        Some((true, false)),
        Some((true, true)),
        None,
        Some((false, true)),
    ];
    let light1 = vec![
        Some((false, false)),
        None,
        Some((true, true)),
        Some((true, true)),
    ];
    let e = class_errors(&names, &class_of, &[light0, light1]).unwrap();
    // near: 3 receivers, 1 false shadow; far: 3 receivers, 1 false lit.
    assert_eq!((e[0].name.as_str(), e[0].pixels), ("near", 3));
    assert!((e[0].false_shadow_pct - 100.0 / 3.0).abs() < 1e-9);
    assert_eq!((e[0].false_lit_pct, e[1].false_shadow_pct), (0.0, 0.0));
    assert!((e[1].misclassified_pct - 100.0 / 3.0).abs() < 1e-9);
    assert_eq!((e[2].pixels, e[2].misclassified_pct), (0, 0.0));
    // A class list that does not fit is an error, not a panic.
    let short = class_errors(&names, &[0, 0], &[vec![None; 4]]).unwrap_err();
    assert_eq!(
        short.to_string(),
        "pixel_classes: 2 class indices for 4 pixels"
    );
    let bad = class_errors(&names[..1], &[0, 3], &[vec![None, Some((true, true))]]);
    assert!(bad.unwrap_err().to_string().contains("class index 3"));
}

#[test]
fn view_depth_is_the_distance_along_the_forward_axis() {
    let mut r = reference(2, 1, &[(Some(0), 1.0, 1.0), (None, 0.0, 0.0)]);
    if let Some(h) = r.hits[0].as_mut() {
        h.position = Vec3::new(3.0, 1.0, -5.0);
    }
    let d = view_depth(&r, Vec3::new(0.0, 1.0, 1.0), Vec3::NEG_Z);
    assert_eq!(d[0], 6.0);
    assert!(d[1].is_nan());
}

#[test]
fn soft_figures_count_the_penumbra_and_the_umbra_apart() {
    // Six receivers of an area light: two in the umbra (V = 0), two in the
    // penumbra (0 < V < 1), two lit; one pixel that is not a receiver.
    let px = [
        (Some(0), 0.0, 1.0),
        (Some(0), 0.0, 1.0),
        (Some(0), 0.25, 1.0),
        (Some(0), 0.75, 1.0),
        (Some(0), 1.0, 1.0),
        (Some(0), 1.0, 1.0),
        (Some(0), 0.5, 0.01),
    ];
    let mut r = reference(7, 1, &px);
    r.area_light = vec![true];
    // The umbra lit 0.6 (misclassified and bleeding) and 0.05 (neither);
    // the penumbra off by 0.25 and 0.05; the lit pixels right.
    let gpu = [0.6, 0.05, 0.5, 0.7, 1.0, 1.0, 0.0];
    let soft = compare(&r, 0, &[1; 7], &gpu, None)
        .stats
        .soft
        .expect("an area light");
    assert_eq!((soft.penumbra_pixels, soft.umbra_pixels), (2, 2));
    assert!((soft.penumbra_mean_abs - 0.15).abs() < 1e-6, "{soft:?}");
    assert_eq!(soft.umbra_misclassified_pct, 50.0);
    assert_eq!(soft.light_bleeding_pct, 50.0);
    // The new classes: the lit pair right, the umbra off by 0.6 and 0.05;
    // every umbra pixel within 3 px of the penumbra (rim, no deep umbra),
    // and both lit pixels within 3 px of it (fringe).
    assert_eq!(soft.lit_pixels, 2);
    assert_eq!(soft.lit_mean_abs, 0.0);
    assert!((soft.umbra_mean_abs - 0.325).abs() < 1e-6, "{soft:?}");
    assert_eq!((soft.deep_umbra_pixels, soft.leak_mean_abs), (0, 0.0));
    assert_eq!(soft.spill_pixels, 4);
    assert!((soft.spill_mean_abs - 0.65 / 4.0).abs() < 1e-6, "{soft:?}");
    assert_eq!(soft.horizon_clipped_pixels, 0);
    // The horizon flag goes through: the first umbra pixel counted apart.
    let flags = [true, false, false, false, false, false, false];
    let flagged = compare(&r, 0, &[1; 7], &gpu, Some(&flags))
        .stats
        .soft
        .expect("an area light");
    assert_eq!(
        (flagged.horizon_clipped_pixels, flagged.umbra_pixels),
        (1, 1)
    );
    assert!((flagged.horizon_clipped_mean_abs - 0.6).abs() < 1e-6);
    // The four classes partition the receivers.
    let classes = |s: &SoftError| {
        s.umbra_pixels + s.penumbra_pixels + s.lit_pixels + s.horizon_clipped_pixels
    };
    assert_eq!((classes(&soft), classes(&flagged)), (6, 6));
    // A hard light has none of these.
    r.area_light = vec![false];
    assert!(compare(&r, 0, &[1; 7], &gpu, None).stats.soft.is_none());
}

// Soft figures per class of receiver, on a 64 × 16 strip: every pixel a
// receiver of one object, every row alike. Along x: the umbra at x < 16,
// a linear penumbra V_ref = (x − 15)/33 at x = 16..48, lit at x ≥ 48.
// Umbra 16 columns (256 pixels), penumbra 32 (512), lit 16 (256). The
// umbra's rim is x = 13..16 (within 3 px of x = 16, the first V_ref > 0),
// the deep umbra x = 0..13 (13 columns, 208 pixels); the lit fringe is
// x = 48..51 (within 3 px of x = 47, the last V_ref < 1). The reference's
// 10 % contour is x = 19 (4/33 ≥ 0.1 > 3/33), its 90 % contour x = 45
// (30/33 ≥ 0.9 > 29/33).

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
