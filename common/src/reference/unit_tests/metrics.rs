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
