//! lesson_03 (PCF): the snapshot (error, mean |ΔV| and taps per variant),
//! the trade-off of taps against error, why a wide kernel needs the
//! receiver-plane depth bias, why averaging depths is wrong, and PCF on
//! lesson 02's extreme scenes.
//!
//! Run `cargo insta review` after a change to see what moved.

use common::measure::counters::{
    DRAWS, FILTER_TAPS, FILTER_TAPS_PER_PIXEL, FULL_DISK_PIXELS, PROBED_PIXELS, SHADOW_FRAGMENTS,
    TAPS, TEXELS_READ,
};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_03");
/// The variant with the fewest misclassified pixels on the default scene.
const BEST: &str = "poisson_16";
/// Every variant that filters the right way (comparisons, then average).
const SOUND: [&str; 6] = [
    "pcf_1x1",
    "pcf_3x3",
    "pcf_5x5",
    "pcf_7x7",
    "hw_2x2",
    "poisson_16",
];

fn run(name: &str, scene: Option<&str>, extra: &[&str]) -> Option<support::LessonRun> {
    support::run_small(BIN, name, scene, extra)
}

/// The default scene with every variant: the snapshot's run, which the
/// best-variant test reads too (one run, not two).
fn default_run() -> Option<&'static support::LessonRun> {
    support::shared_run(BIN, "lesson_03_snapshot", &support::SMALL)
}

/// Pixels of a visibility PNG that are neither 0 nor 1: a penumbra.
fn fractional_pixels(run: &support::LessonRun, variant: &str) -> usize {
    let (ids, vis, _, _) =
        support::read_visibility(&run.out.join(format!("{variant}_visibility_l0.png")));
    ids.iter()
        .zip(&vis)
        .filter(|&(&id, &v)| id != 0 && v > 0.0 && v < 1.0)
        .count()
}

#[test]
fn lesson_03_snapshot() {
    let Some(run) = default_run() else {
        return;
    };
    let mut text = String::from(
        "per variant: taps (depth comparisons per pixel), texels read, and the error against the\n",
    );
    text += "hard-edged reference: misclassified in percent (two decimals: the filters differ by\n";
    text +=
        "hundredths) and mean |V - V_ref| in percent (one decimal: it grows with the kernel)\n\n";
    for v in run.report["variants"].as_array().expect("variants") {
        let name = v["name"].as_str().unwrap();
        text += &format!(
            "{name:<14} taps {:>2}  texels {:>2}  misclassified {:>5.2}%{}  mean |dV| {:>4.1}%{}\n",
            support::counter(&run.report, name, TAPS.name),
            support::counter(&run.report, name, TEXELS_READ.name),
            support::error(&run.report, name, "misclassified_pct"),
            support::bound(v, "misclassified_pct", 1.0, 2),
            100.0 * support::error(&run.report, name, "mean_abs"),
            support::bound(v, "mean_abs", 100.0, 1),
        );
    }
    text += &support::counter_lines(
        &run.report,
        &[
            DRAWS.name,
            FILTER_TAPS_PER_PIXEL.name,
            SHADOW_FRAGMENTS.name,
        ],
    );
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(
            "lesson_03",
            support::tolerance::adapter_line(&run.report) + &text
        )
    });
}

/// The bar: on the default scene the best variant misclassifies at
/// most 1% of the receivers; so does every filter that averages comparisons.
#[test]
fn lesson_03_best_variant_is_within_one_percent() {
    let Some(run) = default_run() else {
        return;
    };
    for v in SOUND {
        let m = support::error(&run.report, v, "misclassified_pct");
        assert!(m <= 1.0, "{v}: misclassified {m:.3}%");
    }
    let best = SOUND.iter().min_by(|a, b| {
        support::error(&run.report, a, "misclassified_pct").total_cmp(&support::error(
            &run.report,
            b,
            "misclassified_pct",
        ))
    });
    assert_eq!(
        best,
        Some(&BEST),
        "the chapter names {BEST} the most accurate"
    );
}

/// Taps against error against time, as the report shows them: the counters
/// give the taps, and on the N×N grid each step up in N buys a wider
/// penumbra (mean |ΔV| against the hard reference rises) for more taps,
/// while the misclassified share stays put, and the lighting pass has a time.
#[test]
fn lesson_03_taps_error_and_time() {
    let args = ["--width", "640", "--height", "360", "--frames", "1"];
    let Some(run) = support::run_lesson_env(BIN, "lesson_03_taps", &args, support::TIMED) else {
        return;
    };
    let expect = [
        ("pcf_1x1", 1, 1),
        ("pcf_3x3", 9, 9),
        ("pcf_5x5", 25, 25),
        ("pcf_7x7", 49, 49),
        ("hw_2x2", 1, 4),
        ("poisson_16", 16, 64),
    ];
    for (v, taps, texels) in expect {
        assert_eq!(
            (
                support::counter(&run.report, v, TAPS.name),
                support::counter(&run.report, v, TEXELS_READ.name)
            ),
            (taps, texels),
            "{v}"
        );
        let t = support::variant(&run.report, v)["timing_ms"]["lighting"].as_f64();
        assert!(
            t.is_some_and(|t| t > 0.0),
            "{v}: timing_ms.lighting missing"
        );
    }
    let grid = ["pcf_1x1", "pcf_3x3", "pcf_5x5", "pcf_7x7"];
    let mean: Vec<f64> = grid
        .iter()
        .map(|v| support::error(&run.report, v, "mean_abs"))
        .collect();
    assert!(
        mean.windows(2).all(|w| w[1] > w[0]),
        "a wider kernel softens more: mean |dV| {mean:?}"
    );
    let mis: Vec<f64> = grid
        .iter()
        .map(|v| support::error(&run.report, v, "misclassified_pct"))
        .collect();
    assert!(
        mis.iter().all(|&m| (m - mis[0]).abs() < 0.3),
        "the 50% line stays near the edge: {mis:?}"
    );
    assert_eq!(
        fractional_pixels(&run, "pcf_1x1"),
        0,
        "one nearest comparison is 0 or 1"
    );
    assert!(
        fractional_pixels(&run, "pcf_3x3") > 1000,
        "a 3x3 average makes a penumbra"
    );
}

/// A 7×7 kernel reaches 3 texels from the receiver; on a sloped surface the
/// stored depths there are up to 3 texel-slopes nearer the light than the
/// receiver, more than lesson 02's bias covers. Without the receiver-plane
/// depth bias the partial acne comes back as a grey veil: mean |ΔV| many
/// times higher, while the 50% line (misclassified) hardly shows it.
#[test]
fn lesson_03_wide_kernel_needs_receiver_plane_bias() {
    let Some(run) = run(
        "lesson_03_rpdb",
        None,
        &["--variant", "pcf_7x7", "--variant", "pcf_7x7_flat"],
    ) else {
        return;
    };
    let (with, without) = (
        support::error(&run.report, "pcf_7x7", "mean_abs"),
        support::error(&run.report, "pcf_7x7_flat", "mean_abs"),
    );
    assert!(
        without > 5.0 * with && without > 0.1,
        "mean |dV|: {with:.4} with the receiver plane, {without:.4} without"
    );
    assert!(
        support::error(&run.report, "pcf_7x7_flat", "false_shadow_pct")
            > support::error(&run.report, "pcf_7x7", "false_shadow_pct")
    );
}

/// Filtering depth instead of comparisons: the 3×3 average of the stored
/// depths is a depth where no surface is, near every edge, and the answer is
/// still 0 or 1: no penumbra, and more false shadow than 3×3 PCF.
#[test]
fn lesson_03_averaging_depths_is_wrong() {
    let Some(run) = run(
        "lesson_03_depth_avg",
        None,
        &["--variant", "pcf_3x3", "--variant", "depth_avg_3x3"],
    ) else {
        return;
    };
    assert_eq!(
        fractional_pixels(&run, "depth_avg_3x3"),
        0,
        "one comparison of an averaged depth is 0 or 1"
    );
    let (pcf, avg) = (
        support::error(&run.report, "pcf_3x3", "false_shadow_pct"),
        support::error(&run.report, "depth_avg_3x3", "false_shadow_pct"),
    );
    assert!(
        avg > 2.0 * pcf,
        "false shadow: {pcf:.3}% for PCF, {avg:.3}% for averaged depths"
    );
}

/// PCF on lesson 02's extreme scenes: grazing light at 85°, the thin plate,
/// 10 km from the origin, and a spot light whose frustum is much larger than
/// the scene. Every sound filter stays within 1%; the 7×7 grid without the
/// receiver-plane bias veils the grazing floor (mean |ΔV| over 10%).
#[test]
fn lesson_03_extreme_scenes() {
    for scene in [
        "lesson_02_grazing_85.toml",
        "lesson_02_thin_plate.toml",
        "lesson_02_far.toml",
        "lesson_02_spot_wide.toml",
    ] {
        let Some(run) = run(&format!("lesson_03_{scene}"), Some(scene), &[]) else {
            return;
        };
        for v in SOUND {
            let m = support::error(&run.report, v, "misclassified_pct");
            assert!(m <= 1.0, "{scene}: {v} misclassified {m:.3}%");
        }
        let veil = support::error(&run.report, "pcf_7x7_flat", "mean_abs");
        assert!(veil > 0.1, "{scene}: pcf_7x7_flat mean |dV| {veil:.3}");
    }
}

/// The renderers' defaults on the default scene. LearnOpenGL's bias, in
/// depth units, lets light under the thin rods: its false lit is several
/// times `pcf_3x3`'s, the same 3×3 filter after our bias. The wgpu
/// example's hardware 2×2 stays within 1%, and Bevy's Gaussian blends
/// (a penumbra of fractional pixels).
#[test]
fn lesson_03_renderer_defaults() {
    let variants = ["pcf_3x3", "learnopengl_pcf", "wgpu_example_hw2x2", "bevy"];
    let extra: Vec<&str> = variants.iter().flat_map(|v| ["--variant", v]).collect();
    let Some(run) = run("lesson_03_peers", None, &extra) else {
        return;
    };
    let (ours, logl) = (
        support::error(&run.report, "pcf_3x3", "false_lit_pct"),
        support::error(&run.report, "learnopengl_pcf", "false_lit_pct"),
    );
    assert!(
        logl > 0.5 && logl > 5.0 * ours,
        "false lit: learnopengl_pcf {logl:.3}%, pcf_3x3 {ours:.3}%"
    );
    let wgpu = support::error(&run.report, "wgpu_example_hw2x2", "misclassified_pct");
    assert!(wgpu <= 1.0, "wgpu_example_hw2x2 misclassified {wgpu:.3}%");
    let blended = fractional_pixels(&run, "bevy");
    assert!(blended > 1000, "bevy: {blended} fractional pixels");
}

/// The adaptive filter (`poisson_16_adaptive`): its 4 probes decide most
/// pixels, so only a small share takes the full disk, and where they decide
/// they agree with the disk: its error is `poisson_16`'s. Its counters add
/// up (4 taps per probed pixel, 16 more per full-disk pixel). Broken, it
/// fails: probes that never agree send every pixel to the disk (the share
/// is 1), probes that decide wrongly (a wrong early return) move the error.
#[test]
fn lesson_03_adaptive_filter_decides_most_pixels_with_four_taps() {
    let Some(run) = run(
        "lesson_03_adaptive",
        None,
        &[
            "--variant",
            "poisson_16",
            "--variant",
            "poisson_16_adaptive",
        ],
    ) else {
        return;
    };
    let v = "poisson_16_adaptive";
    let probed = support::counter(&run.report, v, PROBED_PIXELS.name);
    let full = support::counter(&run.report, v, FULL_DISK_PIXELS.name);
    let taps = support::counter(&run.report, v, FILTER_TAPS.name);
    assert!(probed > 10_000, "{v}: the lit pass probed {probed} pixels");
    assert_eq!(taps, 4 * probed + 16 * full, "{v}: filter_taps");
    let share = full as f64 / probed as f64;
    assert!(
        share > 0.01 && share < 0.25,
        "{v}: {full} of {probed} pixels took the full disk ({share:.3}): the penumbrae's share is a few %"
    );
    for figure in ["misclassified_pct", "false_shadow_pct", "false_lit_pct"] {
        let (a, b) = (
            support::error(&run.report, v, figure),
            support::error(&run.report, "poisson_16", figure),
        );
        assert!(
            (a - b).abs() <= 0.02,
            "{v}: {figure} {a} against poisson_16's {b}: the probes decide wrongly"
        );
    }
}
