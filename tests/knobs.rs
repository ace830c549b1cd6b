//! Knobs (`--knob NAME=VALUE`, `common::run::knobs`): each lesson's knob
//! moves the measured error the way its chapter says the parameter does,
//! the report carries the values a variant ran with, and a bad `--knob` is
//! one line on stderr naming the flag.
//!
//! Small runs (320×180, one frame) on the default scenes: the whole file
//! takes seconds on lavapipe. Run with `-- --nocapture` to see the figures.

use common::measure::counters::{
    CASCADES, FILTER_TAPS_PER_PIXEL, SCISSOR_PIXELS, SHADOW_FRAGMENTS, SHADOW_MAP_SIZE,
    SHADOW_TEXELS_WRITTEN, STENCIL_FRAGMENTS, TAPS, TEXELS_READ, TEXEL_UM_U, VOLUME_FRAGMENTS,
    VOLUME_TRIANGLES,
};
use support::LessonRun;

const L01: &str = env!("CARGO_BIN_EXE_lesson_01");
const L02: &str = env!("CARGO_BIN_EXE_lesson_02");
const L03: &str = env!("CARGO_BIN_EXE_lesson_03");
const L08: &str = env!("CARGO_BIN_EXE_lesson_08");
const L09: &str = env!("CARGO_BIN_EXE_lesson_09");

/// `bin` headless at 320×180, one frame, on `scene` (the default: `None`),
/// with `args` (`--variant`s and `--knob`s).
fn run(bin: &str, name: &str, scene: Option<&str>, args: &[&str]) -> Option<LessonRun> {
    let mut all = vec!["--width", "320", "--height", "180", "--frames", "1"];
    if let Some(s) = scene {
        all.extend(["--scene", s]);
    }
    all.extend(args);
    support::run_lesson(bin, name, &all)
}

/// The value of knob `knob` that `variant` ran with, from report.json.
fn knob(run: &LessonRun, variant: &str, knob: &str) -> f64 {
    support::variant(&run.report, variant)["knobs"][knob]
        .as_f64()
        .unwrap_or_else(|| panic!("{variant}: knobs.{knob} missing from report.json"))
}

fn err(run: &LessonRun, variant: &str, key: &str) -> f64 {
    support::error(&run.report, variant, key)
}

/// Chapter 01: "Resolution does not cure acne" (false shadow "stays near
/// half of the receivers at every size"); the texel "halves with each
/// doubling of N"; false lit "falls as the map grows"; the shadow pass's
/// fragments "grow with the map's texels". `res_256` with `map_size_log2`
/// at 12 must be `res_4096` in all of that.
#[test]
fn knobs_lesson_01_map_size_shrinks_the_texel_not_the_acne() {
    let Some(small) = run(L01, "knobs_01_256", None, &["--variant", "res_256"]) else {
        return;
    };
    let args = ["--variant", "res_256", "--knob", "map_size_log2=12"];
    let Some(big) = run(L01, "knobs_01_4096", None, &args) else {
        return;
    };
    assert_eq!(knob(&small, "res_256", "map_size_log2"), 8.0);
    assert_eq!(knob(&big, "res_256", "map_size_log2"), 12.0);
    let c = |r: &LessonRun, k| support::counter(&r.report, "res_256", k) as f64;
    let texel = c(&small, TEXEL_UM_U.name) / c(&big, TEXEL_UM_U.name);
    let fragments = c(&big, SHADOW_FRAGMENTS.name) / c(&small, SHADOW_FRAGMENTS.name);
    let (fs, fl) = (
        [&small, &big].map(|r| err(r, "res_256", "false_shadow_pct")),
        [&small, &big].map(|r| err(r, "res_256", "false_lit_pct")),
    );
    eprintln!("256² -> 4096²: texel / {texel:.2}, shadow fragments × {fragments:.1}, false shadow {fs:.3?} %, false lit {fl:.3?} %");
    assert!(
        (texel - 16.0).abs() < 0.1,
        "the texel must shrink 16 times: {texel}"
    );
    assert!(
        fragments > 128.0,
        "the shadow pass's fragments must grow with the texels: × {fragments}"
    );
    assert!(fs.iter().all(|&f| f > 40.0), "acne at every size: {fs:?}");
    assert!(fl[1] < 0.5 * fl[0], "false lit must fall: {fl:?}");
}

/// Chapter 02, "The trade-off: a sweep of constant biases": "False shadow
/// falls as the bias grows [...] False lit stays at the edge-aliasing floor
/// [...] until the bias exceeds the distance, along the light, from the
/// slab's top face [...] to the floor beneath it [...]; then it jumps:
/// light leaks under the slab". `bias_1tx` with `bias_texels` at 0.25 and
/// at 64 must measure what the named `bias_0.25tx` and `bias_64tx` do, and
/// show both ends of that trade.
#[test]
fn knobs_lesson_02_constant_bias_trades_acne_for_peter_panning() {
    let Some(low) = run(
        L02,
        "knobs_02_bias_0.25",
        None,
        &[
            "--variant",
            "bias_1tx",
            "--variant",
            "bias_0.25tx",
            "--knob",
            "bias_texels=0.25",
        ],
    ) else {
        return;
    };
    let Some(high) = run(
        L02,
        "knobs_02_bias_64",
        None,
        &[
            "--variant",
            "bias_1tx",
            "--variant",
            "bias_64tx",
            "--knob",
            "bias_texels=64",
        ],
    ) else {
        return;
    };
    assert_eq!(knob(&low, "bias_1tx", "bias_texels"), 0.25);
    assert_eq!(knob(&high, "bias_1tx", "bias_texels"), 64.0);
    let (fs_low, fl_low) = (
        err(&low, "bias_1tx", "false_shadow_pct"),
        err(&low, "bias_1tx", "false_lit_pct"),
    );
    let (fs_high, fl_high) = (
        err(&high, "bias_1tx", "false_shadow_pct"),
        err(&high, "bias_1tx", "false_lit_pct"),
    );
    eprintln!("bias_1tx at bias_texels 0.25: false shadow {fs_low:.3}%, false lit {fl_low:.3}%");
    eprintln!("bias_1tx at bias_texels 64:   false shadow {fs_high:.3}%, false lit {fl_high:.3}%");
    for (run, named) in [(&low, "bias_0.25tx"), (&high, "bias_64tx")] {
        for key in ["false_shadow_pct", "false_lit_pct"] {
            let (a, b) = (err(run, "bias_1tx", key), err(run, named, key));
            assert!(
                (a - b).abs() < 1e-9,
                "bias_1tx with {named}'s bias: {key} {a} != {b}"
            );
        }
    }
    assert!(
        fs_low > 10.0 && fs_high < 0.1,
        "acne must fall from over 10% to under 0.1%: {fs_low:.3}% -> {fs_high:.3}%"
    );
    assert!(
        fl_high > 0.2 && fl_high > 10.0 * fl_low,
        "Peter Panning must jump: false lit {fl_low:.3}% -> {fl_high:.3}%"
    );
}

/// Chapter 02, the rasteriser's slope-scaled bias: "the inequality asks
/// for ½(|∂x z| + |∂y z|) ≤ m, so `slope_scale` = 1 would do and 1.5 leaves
/// room; `constant` = 8 covers the rounding". With both at 0, `slope_hw`
/// stores the plain depths, and is lesson 01's acne again ("nearly half of
/// the lit receivers in false shadow"); its shadow pass is rebuilt, so it
/// writes as many texels as the unbiased pass.
#[test]
fn knobs_lesson_02_hardware_bias_at_zero_is_acne_again() {
    let args = [
        "--variant",
        "slope_hw",
        "--variant",
        "none",
        "--knob",
        "hw_slope_scale=0",
        "--knob",
        "hw_constant=0",
    ];
    let Some(off) = run(L02, "knobs_02_hw_off", None, &args) else {
        return;
    };
    assert_eq!(knob(&off, "slope_hw", "hw_slope_scale"), 0.0);
    assert_eq!(knob(&off, "slope_hw", "hw_constant"), 0.0);
    assert_eq!(knob(&off, "slope_hw", "hw_clamp_texels"), 16.0, "untouched");
    assert!(
        support::variant(&off.report, "none").get("knobs").is_none(),
        "none has no knobs, so no knobs in its report"
    );
    let fs = err(&off, "slope_hw", "false_shadow_pct");
    eprintln!("slope_hw with no hardware bias: false shadow {fs:.3}%");
    assert!(
        fs > 40.0,
        "slope_hw without its bias: false shadow {fs:.3}%"
    );
    let texels = |v| support::counter(&off.report, v, SHADOW_TEXELS_WRITTEN.name);
    assert_eq!(
        texels("slope_hw"),
        texels("none"),
        "the rebuilt pass, counted again"
    );
}

/// Chapter 03, "Two error measures": mean |ΔV| "grows with the penumbra's
/// width, about linearly in N"; "a grid makes N² comparisons per pixel and
/// reads N² texels"; and "Why a wider kernel needs more bias": without the
/// receiver plane "the acne comes back as a grey veil over every lit
/// slope" (`pcf_7x7_flat`: 25.7 % against the 7×7's 1.3 %). `pcf_3x3` at
/// `kernel_radius` r is the (2r + 1)² grid; at r = 3 it is `pcf_7x7`.
#[test]
fn knobs_lesson_03_wider_kernel_widens_the_penumbra() {
    let variants = ["--variant", "pcf_3x3", "--variant", "pcf_7x7_flat"];
    let Some(named) = run(L03, "knobs_03_named", None, &["--variant", "pcf_7x7"]) else {
        return;
    };
    let mut rows = Vec::new();
    for r in [0u32, 1, 3, 6] {
        let k = format!("kernel_radius={r}");
        let args = [&variants[..], &["--knob", &k]].concat();
        let Some(run) = run(L03, &format!("knobs_03_r{r}"), None, &args) else {
            return;
        };
        assert_eq!(knob(&run, "pcf_3x3", "kernel_radius"), r as f64);
        let n = 2 * r as u64 + 1;
        assert_eq!(support::counter(&run.report, "pcf_3x3", TAPS.name), n * n);
        assert_eq!(
            support::counter(&run.report, "pcf_3x3", FILTER_TAPS_PER_PIXEL.name),
            n * n
        );
        assert_eq!(
            support::counter(&run.report, "pcf_3x3", TEXELS_READ.name),
            n * n
        );
        let mean = err(&run, "pcf_3x3", "mean_abs");
        let flat = err(&run, "pcf_7x7_flat", "mean_abs");
        eprintln!(
            "N = {n:>2}: mean |dV| {:.3}%, without the receiver plane {:.3}%",
            100.0 * mean,
            100.0 * flat
        );
        if r == 3 {
            for key in ["mean_abs", "misclassified_pct"] {
                let (a, b) = (err(&run, "pcf_3x3", key), err(&named, "pcf_7x7", key));
                assert!(
                    (a - b).abs() < 1e-9,
                    "pcf_3x3 at radius 3 is pcf_7x7: {key} {a} != {b}"
                );
            }
            assert!(
                flat > 10.0 * mean,
                "the flat 7×7's veil: {flat:.4} against {mean:.4}"
            );
        }
        rows.push((n as f64, mean));
    }
    for w in rows.windows(2) {
        assert!(
            w[1].1 > 1.5 * w[0].1,
            "mean |dV| must grow with N: {rows:?}"
        );
    }
    // About linear: mean |ΔV| / N within a factor 2 of N = 3's, at every N.
    let per_n = rows[1].1 / rows[1].0;
    for &(n, m) in &rows {
        let ratio = m / n / per_n;
        assert!(
            (0.5..2.0).contains(&ratio),
            "not about linear in N at N = {n}: {rows:?}"
        );
    }
}

/// Lesson 09's default scene without its `[camera_path]` (the shimmer walk
/// is not what these runs measure, and it is most of their time).
fn lesson_09_scene_without_path() -> String {
    let text = std::fs::read_to_string(support::scene_path("lesson_09.toml")).unwrap();
    let cut = text
        .find("[camera_path]")
        .expect("lesson_09.toml has a camera path");
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join("knobs_lesson_09_no_path.toml");
    std::fs::write(&path, &text[..cut]).unwrap();
    path.display().to_string()
}

/// Chapter 09: "with the same texels, more cascades are better (`k1` worse
/// than `k2`, `k2` worse than `k4`)", and the practical split, λ = 0.9,
/// "misclassifies less than both `k4_uniform` and `k4_log`, the two
/// schemes its split blends" (λ = 0 and λ = 1). `k4` with `cascades` at 1
/// and 2 and with `split_lambda` at 0 and 1 must show both; λ = 0 must be
/// exactly `k4_uniform`; and the per-cascade error classes, the counters and
/// the map size must follow the count.
#[test]
fn knobs_lesson_09_cascades_and_lambda() {
    let scene = lesson_09_scene_without_path();
    let s = Some(scene.as_str());
    let k4 = ["--variant", "k4"];
    let Some(base) = run(L09, "knobs_09_k4", s, &k4) else {
        return;
    };
    let base_mis = err(&base, "k4", "misclassified_pct");
    assert_eq!(knob(&base, "k4", "cascades"), 4.0); // not a counter: the knob
    assert_eq!(knob(&base, "k4", "split_lambda"), 0.9);
    let mut by_count = vec![];
    for k in [1u64, 2] {
        let a = format!("cascades={k}");
        let Some(run) = run(
            L09,
            &format!("knobs_09_k{k}"),
            s,
            &[&k4[..], &["--knob", &a]].concat(),
        ) else {
            return;
        };
        let v = support::variant(&run.report, "k4");
        assert_eq!(knob(&run, "k4", "cascades"), k as f64); // not a counter: the knob
        assert_eq!(support::counter(&run.report, "k4", CASCADES.name), k);
        let size = (2048.0 * 2048.0 / k as f64).sqrt().floor() as u64;
        assert_eq!(
            support::counter(&run.report, "k4", SHADOW_MAP_SIZE.name),
            size
        );
        let classes = v["classes"].as_array().expect("k4's classes");
        assert_eq!(classes.len() as u64, k, "one error class per cascade");
        by_count.push(err(&run, "k4", "misclassified_pct"));
    }
    by_count.push(base_mis);
    eprintln!("k4 with 1, 2, 4 cascades: misclassified {by_count:.3?} %");
    assert!(
        by_count[0] > 2.0 * by_count[1] && by_count[1] > 1.5 * by_count[2],
        "more cascades must be better: {by_count:?}"
    );

    let mut by_lambda = vec![];
    for (lambda, named) in [(0.0, "k4_uniform"), (1.0, "k4_log")] {
        let a = format!("split_lambda={lambda}");
        let args = [&k4[..], &["--variant", named, "--knob", &a]].concat();
        let Some(run) = run(L09, &format!("knobs_09_lambda{lambda}"), s, &args) else {
            return;
        };
        assert_eq!(knob(&run, "k4", "split_lambda"), lambda);
        let m = err(&run, "k4", "misclassified_pct");
        if lambda == 0.0 {
            let u = err(&run, named, "misclassified_pct");
            assert!(
                (m - u).abs() < 1e-9,
                "λ = 0 is the uniform split: {m} != {u}"
            );
        }
        by_lambda.push(m);
    }
    eprintln!("k4 at λ = 0, 1, 0.9: misclassified {by_lambda:.3?} %, {base_mis:.3} %");
    assert!(
        by_lambda.iter().all(|&m| base_mis < 0.7 * m),
        "the practical split must beat both ends: {base_mis:.3} against {by_lambda:?}"
    );
}

/// Chapter 08: the limits cut work, not pixels ("The pixels are the same
/// in all six; the counters say how many volume triangles each one draws,
/// and how many fragments it rasterises and lets through to the stencil",
/// lessons/lesson_08/main.rs). `unbounded` with the three toggles on must
/// count what `cull_bounds_scissor` counts, and `cull_bounds_scissor` with
/// them off what `unbounded` does, with the same error throughout.
#[test]
fn knobs_lesson_08_toggles_cut_work_not_pixels() {
    let both = ["--variant", "unbounded", "--variant", "cull_bounds_scissor"];
    let Some(named) = run(L08, "knobs_08_named", None, &both) else {
        return;
    };
    let on = ["scissor=on", "depth_bounds=on", "cull=on"];
    let off = ["scissor=off", "depth_bounds=off", "cull=off"];
    let knobs = |v: &'static str, ks: [&'static str; 3]| {
        let mut a = vec!["--variant", v];
        for k in ks {
            a.extend(["--knob", k]);
        }
        a
    };
    let Some(all_on) = run(L08, "knobs_08_on", None, &knobs("unbounded", on)) else {
        return;
    };
    let Some(all_off) = run(
        L08,
        "knobs_08_off",
        None,
        &knobs("cull_bounds_scissor", off),
    ) else {
        return;
    };
    assert_eq!(knob(&all_on, "unbounded", "scissor"), 1.0);
    assert_eq!(knob(&all_off, "cull_bounds_scissor", "depth_bounds"), 0.0);
    let keys = [
        VOLUME_TRIANGLES.name,
        VOLUME_FRAGMENTS.name,
        STENCIL_FRAGMENTS.name,
        SCISSOR_PIXELS.name,
    ];
    for (run, v, like) in [
        (&all_on, "unbounded", "cull_bounds_scissor"),
        (&all_off, "cull_bounds_scissor", "unbounded"),
    ] {
        for k in keys {
            let (a, b) = (
                support::counter(&run.report, v, k),
                support::counter(&named.report, like, k),
            );
            eprintln!("{v} toggled like {like}: {k} {a} (named: {b})");
            assert_eq!(a, b, "{v} toggled like {like}: {k}");
        }
        let (a, b) = (
            err(run, v, "misclassified_pct"),
            err(&named, v, "misclassified_pct"),
        );
        assert!(
            (a - b).abs() < 1e-9,
            "{v}: the pixels must not change: {a} != {b}"
        );
    }
    let frags = |v| support::counter(&named.report, v, VOLUME_FRAGMENTS.name);
    assert!(
        frags("cull_bounds_scissor") * 2 < frags("unbounded"),
        "the limits must cut the fragments"
    );
}

/// Runs lesson 02 with `args`; it must fail with one stderr line, which is
/// returned. `None` when there is no adapter and none is required.
fn fails(name: &str, args: &[&str]) -> Option<String> {
    let out_dir = support::out_dir(name);
    let o = support::tiny_headless(L02, &out_dir, args)
        .output()
        .expect("run lesson_02");
    let stderr = String::from_utf8_lossy(&o.stderr).to_string();
    if stderr.contains("no GPU adapter found") && !support::gpu_required() {
        return None;
    }
    assert!(!o.status.success(), "{args:?} must fail; stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{args:?}: one line expected, got {stderr}");
    assert!(
        lines[0].contains("--knob"),
        "{args:?}: the line must name the flag: {stderr}"
    );
    Some(lines[0].to_string())
}

/// A bad `--knob` is one line naming the flag and what is wrong: an
/// unknown name (with the knobs there are), a value out of range (with the
/// range), a knob that none of the run's variants has, a fraction for a
/// whole number, and a line that is not NAME=VALUE.
#[test]
fn knobs_bad_knob_is_one_line_naming_the_flag() {
    let cases: [(&str, &[&str], &[&str]); 5] = [
        (
            "knobs_bad_unknown",
            &["--variant", "bias_1tx", "--knob", "bogus=1"],
            &["bogus", "bias_texels"],
        ),
        (
            "knobs_bad_range",
            &["--variant", "bias_1tx", "--knob", "bias_texels=100"],
            &["bias_texels", "0 to 64"],
        ),
        (
            "knobs_bad_variant",
            &["--variant", "none", "--knob", "bias_texels=1"],
            &["bias_texels", "none of the variants"],
        ),
        (
            "knobs_bad_int",
            &["--variant", "slope_hw", "--knob", "hw_constant=2.5"],
            &["hw_constant", "whole numbers"],
        ),
        (
            "knobs_bad_line",
            &["--variant", "bias_1tx", "--knob", "bias_texels"],
            &["NAME=VALUE"],
        ),
    ];
    for (name, args, says) in cases {
        let Some(line) = fails(name, args) else {
            return;
        };
        eprintln!("{line}");
        for s in says {
            assert!(line.contains(s), "{args:?}: {line:?} must say {s:?}");
        }
    }
}
