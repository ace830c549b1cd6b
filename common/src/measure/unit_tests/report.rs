//! The report's table: times printed, or `unstable` where the protocol's
//! base-pass check failed.

use super::*;

fn report(stable_b: bool) -> Report {
    let error = serde_json::json!({
        "receiver_pixels": 100, "misclassified_pct": 1.0, "false_shadow_pct": 0.5,
        "false_lit_pct": 0.5, "mean_abs": 0.0, "coverage_mismatch_pct": 0.0,
        "interior_receiver_pixels": 90, "interior_misclassified_pct": 0.5
    });
    let check = |base: f64, stable: bool| {
        serde_json::json!({"warm_up_frames": 6, "warm_up_ms": 300.0, "settled": true,
                           "base_ms": base, "stable": stable})
    };
    let variant = |name: &str, base: f64, stable: bool| {
        serde_json::json!({
            "name": name, "error": error, "error_per_light": [error],
            "timing_ms": {"total": 1.5, "frame": 2.25, "cpu_total": 0.125, "base": base},
            "timing_source": "gpu_timestamps", "counters": {},
            "timing_check": check(base, stable)
        })
    };
    serde_json::from_value(serde_json::json!({
        "lesson": "lesson_99",
        "adapter": {"name": "test", "backend": "Vulkan"},
        "width": 64, "height": 36, "scene": "s", "reference_ms": 1.0, "frames": 5,
        "variants": [variant("a", 0.788, true), variant("b", 4.655, stable_b)],
        "baseline": {"timing_ms": {"total": 1.0, "frame": 1.5, "cpu_total": 0.05},
                     "timing_spread_ms": {}, "timing_samples_ms": {},
                     "blocks": [check(0.788, true), check(0.79, true)]},
        "timing_protocol": {"warm_up_min_ms": 300.0, "order": ["baseline", "a", "baseline", "b"],
                            "base_reference_ms": 0.788, "base_ratio_limit": 2.0,
                            "base_tolerance_ms": 0.02, "stable": stable_b}
    }))
    .expect("a report")
}

#[test]
fn stable_times_are_printed_with_frame_gpu_and_cpu_columns() {
    let t = report(true).table();
    assert!(t.contains("frame ms |   GPU ms |   CPU ms"), "{t}");
    let b = t.lines().find(|l| l.starts_with("b ")).expect("row b");
    assert!(b.contains("2.250 |    1.500 |    0.125"), "{b}");
    assert!(!t.contains("unstable"), "{t}");
    assert!(report(true).unstable_line().is_none());
}

#[test]
fn an_unstable_block_prints_no_gpu_number_and_says_why() {
    let r = report(false);
    let t = r.table();
    let b = t.lines().find(|l| l.starts_with("b ")).expect("row b");
    assert!(b.contains("unstable | unstable |    0.125"), "{b}");
    let a = t.lines().find(|l| l.starts_with("a ")).expect("row a");
    assert!(a.contains("2.250"), "{a}");
    let line = r.unstable_line().expect("a line");
    assert!(
        line.contains("b 4.655 ms") && line.contains("0.788 ms"),
        "{line}"
    );
    assert!(t.contains(&line), "the table ends with the line");
    // The report round-trips with its checks.
    let json = serde_json::to_string(&r).expect("serialises");
    let back: Report = serde_json::from_str(&json).expect("parses");
    assert!(!back.variants[1].timing_stable() && back.variants[0].timing_stable());
}

/// One light's soft figures: every count and mean given.
fn soft_light(umbra: u64, deep: u64, width: Option<f64>, contour: u64, x: f64) -> ErrorStats {
    ErrorStats {
        receiver_pixels: 1000,
        misclassified_pct: 0.0,
        false_shadow_pct: 0.0,
        false_lit_pct: 0.0,
        mean_abs: x,
        coverage_mismatch_pct: 0.0,
        interior_receiver_pixels: 0,
        interior_misclassified_pct: 0.0,
        soft: Some(SoftError {
            penumbra_pixels: 2 * umbra,
            penumbra_mean_abs: x,
            umbra_pixels: umbra,
            umbra_misclassified_pct: x,
            light_bleeding_pct: x,
            umbra_mean_abs: x,
            lit_pixels: 3 * umbra,
            lit_mean_abs: x,
            deep_umbra_pixels: deep,
            leak_mean_abs: x,
            leak_pct: x,
            spill_pixels: umbra - deep,
            spill_mean_abs: x,
            horizon_clipped_pixels: umbra / 10,
            horizon_clipped_mean_abs: x,
            contour_pixels: contour,
            penumbra_width_error_px: width,
        }),
    }
}

#[test]
fn soft_figures_pool_by_their_own_counts() {
    // Light 0: umbra 100 (deep 10), figures 1; light 1: umbra 300 (deep
    // 90), figures 2. Every figure weighs by its own count.
    let a = soft_light(100, 10, Some(4.0), 30, 1.0);
    let b = soft_light(300, 90, Some(8.0), 10, 2.0);
    let s = combine(&[a.clone(), b]).soft.expect("soft");
    assert_eq!(
        (s.umbra_pixels, s.penumbra_pixels, s.lit_pixels),
        (400, 800, 1200)
    );
    assert_eq!((s.deep_umbra_pixels, s.spill_pixels), (100, 300));
    assert_eq!((s.horizon_clipped_pixels, s.contour_pixels), (40, 40));
    // By umbra (penumbra, lit: the same ratio): (100 + 600)/400.
    for m in [
        s.umbra_mean_abs,
        s.penumbra_mean_abs,
        s.lit_mean_abs,
        s.light_bleeding_pct,
        s.umbra_misclassified_pct,
    ] {
        assert!((m - 1.75).abs() < 1e-12, "{s:?}");
    }
    // By the deep umbra: (10 + 180)/100; by the spill: (90 + 420)/300.
    assert!((s.leak_mean_abs - 1.9).abs() < 1e-12, "{s:?}");
    assert!((s.leak_pct - 1.9).abs() < 1e-12, "{s:?}");
    assert!((s.spill_mean_abs - 1.7).abs() < 1e-12, "{s:?}");
    assert!((s.horizon_clipped_mean_abs - 1.75).abs() < 1e-12, "{s:?}");
    // The width by contour pixels: (30·4 + 10·8)/40.
    assert_eq!(s.penumbra_width_error_px, Some(5.0));
    // A light without a width is left out of it; none with one: None.
    let c = soft_light(100, 10, None, 50, 3.0);
    let s = combine(&[a, c.clone()]).soft.expect("soft");
    assert_eq!(s.penumbra_width_error_px, Some(4.0));
    assert_eq!(
        combine(&[c]).soft.expect("soft").penumbra_width_error_px,
        None
    );
}

#[test]
fn a_soft_table_shows_every_figure_with_its_count_and_a_legend() {
    let mut r = report(true);
    let light = soft_light(270, 200, Some(1.25), 64, 0.5);
    r.variants[0].error = combine(std::slice::from_ref(&light));
    r.variants[1].error = combine(&[soft_light(270, 200, None, 64, 0.5)]);
    let t = r.table();
    let head = t.lines().find(|l| l.starts_with("variant")).expect("head");
    let names = [
        "mean |dV|",
        "n umbra",
        "umbra |dV|",
        "n penumbra",
        "penumbra |dV|",
        "n lit",
        "lit |dV|",
        "bleeding %",
        "n deep",
        "leak |dV|",
        "leak %",
        "n spill",
        "spill |dV|",
        "n horizon",
        "horizon |dV|",
        "n contour",
        "width err px",
    ];
    let cells = |l: &str| -> Vec<String> { l.split(" | ").map(|c| c.trim().to_string()).collect() };
    let head = cells(head);
    assert_eq!(&head[7..], &names, "{t}");
    let a = cells(t.lines().find(|l| l.starts_with("a ")).expect("row a"));
    let want = [
        "0.5000", "270", "0.5000", "540", "0.5000", "810", "0.5000", "0.500", "200", "0.5000",
        "0.500", "70", "0.5000", "27", "0.5000", "64", "1.25",
    ];
    assert_eq!(&a[7..], &want, "{t}");
    let b = cells(t.lines().find(|l| l.starts_with("b ")).expect("row b"));
    assert_eq!(b.last().map(String::as_str), Some("-"), "no width: -");
    // Header, rule and rows line up.
    let lines: Vec<&str> = t
        .lines()
        .take_while(|l| !l.starts_with("What"))
        .skip(3)
        .collect();
    let len = lines[0].chars().count();
    assert!(lines.iter().all(|l| l.chars().count() == len), "{t}");
    // Every column has a line in the legend.
    let legend = &t[t.find("What each soft column means").expect("legend")..];
    for n in names {
        assert!(legend.contains(n), "{n} not in the legend:\n{legend}");
    }
    // A table without soft figures has neither.
    let hard = report(true).table();
    assert!(
        !hard.contains("n umbra") && !hard.contains("What each soft"),
        "{hard}"
    );
}
