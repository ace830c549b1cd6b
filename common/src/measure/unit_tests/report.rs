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
