//! lesson_04 (cube-map point shadows): a snapshot of the default scene, the
//! culled frame against the unculled one, and one test per extreme case,
//! each with a measured pass criterion.
//!
//! Run `cargo insta review` after a change to see what moved.

use std::path::Path;

use common::measure::counters::{
    CASTER_DRAWS, DRAWS, FACES_RENDERED, FILTER_TAPS_PER_PIXEL, SHADOW_FRAGMENTS,
    SHADOW_TEXELS_WRITTEN, SLOPE_BIAS_MILLITEXELS, UNCLIPPED_DEPTH,
};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_04");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

fn scene(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
        .display()
        .to_string()
}

/// `--scene FILE --variant A --variant B ...` after the common size.
fn args<'a>(scene: &'a str, variants: &[&'a str]) -> Vec<&'a str> {
    let mut a = SIZE.to_vec();
    if !scene.is_empty() {
        a.extend(["--scene", scene]);
    }
    for v in variants {
        a.extend(["--variant", v]);
    }
    a
}

fn pct(run: &support::LessonRun, variant: &str, key: &str) -> f64 {
    support::variant(&run.report, variant)["error"][key]
        .as_f64()
        .unwrap()
}

fn counter(run: &support::LessonRun, variant: &str, key: &str) -> u64 {
    support::variant(&run.report, variant)["counters"][key]
        .as_u64()
        .unwrap_or_else(|| panic!("{variant}: counter {key} missing"))
}

/// Percentage of covered pixels where a variant's visibility PNG and the
/// reference's disagree (lit = v ≥ 0.5), over *all* covered pixels, not
/// only the metric's receivers (which stop at the light's range).
fn disagreement_pct(out: &Path, variant: &str) -> f64 {
    let (ids, vis, _, _) =
        support::read_visibility(&out.join(format!("{variant}_visibility_l0.png")));
    let (ref_ids, ref_vis, _, _) =
        support::read_visibility(&out.join("reference_visibility_l0.png"));
    let (mut covered, mut differ) = (0u64, 0u64);
    for p in 0..ids.len() {
        if ids[p] == 1 && ref_ids[p] == 1 {
            covered += 1;
            differ += u64::from((vis[p] >= 0.5) != (ref_vis[p] >= 0.5));
        }
    }
    100.0 * differ as f64 / covered.max(1) as f64
}

#[test]
fn lesson_04_snapshot() {
    let Some(run) = support::run_lesson(BIN, "lesson_04_snapshot", &SIZE) else {
        return;
    };
    let variants = run.report["variants"].as_array().expect("variants");
    assert_eq!(variants.len(), 14);
    let mut text =
        String::from("reference visibility, light 0 ('#' shadow, '.' lit, ' ' background):\n");
    text += &support::ascii_of(&run.out.join("reference_visibility_l0.png"), 64, 18);
    text += "\n\nlinear_1024 visibility, light 0:\n";
    text += &support::ascii_of(&run.out.join("linear_1024_visibility_l0.png"), 64, 18);
    text += "\n\nerror against the reference in percent (two decimals: the variants differ by\n";
    text += "hundredths), mean |V - V_ref| in percent, faces rendered, caster draws, slope bias\n";
    text += "(texels × tan θ):\n";
    for v in variants {
        let c = &v["counters"];
        text += &format!(
            "{}  mean |dV| {:.2}%  faces {}  draws {}  slope {}\n",
            support::error_line(v, 2),
            100.0 * v["error"]["mean_abs"].as_f64().unwrap_or(f64::NAN),
            c[FACES_RENDERED.name],
            c[CASTER_DRAWS.name],
            c[SLOPE_BIAS_MILLITEXELS.name].as_u64().unwrap_or(0) as f64 / 1000.0
        );
    }
    text += &support::counter_lines(&run.report, &[DRAWS.name, FILTER_TAPS_PER_PIXEL.name]);
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(
            "lesson_04",
            support::tolerance::adapter_line(&run.report) + &text
        )
    });
    // 3D PCF's raised slope bias is a reported parameter, not a silent one.
    assert_eq!(
        counter(&run, "pcf3d_1024", SLOPE_BIAS_MILLITEXELS.name),
        2500
    );
    assert_eq!(
        counter(&run, "pcf3d_slope1_1024", SLOPE_BIAS_MILLITEXELS.name),
        1000
    );
    // Done-when: the best variant is within 1% of the exact reference.
    let best = pct(&run, "linear_1024", "misclassified_pct");
    assert!(best <= 1.0, "linear_1024 misclassified {best}% > 1%");
}

/// Culling faces and casters must not change a single visibility pixel, and
/// must draw less: the +Y face (nothing above the light) and the crate past
/// the range are left out.
#[test]
fn lesson_04_culling_changes_no_pixel_and_draws_less() {
    let Some(run) = support::run_lesson(
        BIN,
        "lesson_04_culling",
        &args("", &["linear_1024", "nocull_1024"]),
    ) else {
        return;
    };
    let culled = image::open(run.out.join("linear_1024_visibility_l0.png"))
        .unwrap()
        .to_luma_alpha8();
    let full = image::open(run.out.join("nocull_1024_visibility_l0.png"))
        .unwrap()
        .to_luma_alpha8();
    let differ = culled
        .pixels()
        .zip(full.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differ, 0,
        "culled and unculled visibility differ in {differ} pixels"
    );
    let (f, d) = (
        counter(&run, "linear_1024", FACES_RENDERED.name),
        counter(&run, "linear_1024", CASTER_DRAWS.name),
    );
    let (nf, nd) = (
        counter(&run, "nocull_1024", FACES_RENDERED.name),
        counter(&run, "nocull_1024", CASTER_DRAWS.name),
    );
    assert_eq!(nf, 6, "unculled renders all six faces");
    assert!(
        f < nf && d < nd,
        "culling must draw less: faces {f} vs {nf}, draws {d} vs {nd}"
    );
    // The standard costs: the unculled frame makes more draw calls and
    // rasterises more shadow fragments (the crate past the range), but
    // writes exactly the same texels: what culling leaves out writes nothing.
    let c = |v, k| counter(&run, v, k);
    assert!(
        c("nocull_1024", DRAWS.name) > c("linear_1024", DRAWS.name),
        "draws: unculled {} vs culled {}",
        c("nocull_1024", DRAWS.name),
        c("linear_1024", DRAWS.name)
    );
    assert!(
        c("nocull_1024", SHADOW_FRAGMENTS.name) > c("linear_1024", SHADOW_FRAGMENTS.name),
        "shadow fragments: unculled {} vs culled {}",
        c("nocull_1024", SHADOW_FRAGMENTS.name),
        c("linear_1024", SHADOW_FRAGMENTS.name)
    );
    assert_eq!(
        c("nocull_1024", SHADOW_TEXELS_WRITTEN.name),
        c("linear_1024", SHADOW_TEXELS_WRITTEN.name),
        "culling left out casters that write texels"
    );
}

/// Seams: the room casts too, and casters sit on a cube corner and edge
/// direction, so shadows straddle two or three faces. Criterion: ≤ 1%
/// misclassified with either storage; the naive hardware-depth comparison
/// (|v| instead of the major axis) must fail (≥ 50%).
#[test]
fn lesson_04_seams_edges_and_corners() {
    let s = scene("lesson_04_seams.toml");
    let Some(run) = support::run_lesson(
        BIN,
        "lesson_04_seams",
        &args(&s, &["linear_1024", "depth_1024", "depth_euclid_1024"]),
    ) else {
        return;
    };
    for v in ["linear_1024", "depth_1024"] {
        let e = pct(&run, v, "misclassified_pct");
        assert!(e <= 1.0, "{v}: {e}% misclassified across the seams");
    }
    let naive = pct(&run, "depth_euclid_1024", "false_shadow_pct");
    assert!(
        naive >= 50.0,
        "the Euclidean comparison should shadow the off-axis walls, got {naive}%"
    );
}

/// Each face's view matrix matches the sampler: a caster off-centre in each
/// of the six faces shadows the right spot (two mirrored scenes, three
/// faces each). Criterion: ≤ 0.5% misclassified.
#[test]
fn lesson_04_each_face_shadows_the_right_side() {
    for name in ["lesson_04_axes_neg.toml", "lesson_04_axes_pos.toml"] {
        let s = scene(name);
        let Some(run) = support::run_lesson(
            BIN,
            &format!("lesson_04_{name}"),
            &args(&s, &["linear_1024"]),
        ) else {
            return;
        };
        let e = pct(&run, "linear_1024", "misclassified_pct");
        let receivers = support::variant(&run.report, "linear_1024")["error"]["receiver_pixels"]
            .as_u64()
            .unwrap();
        assert!(receivers > 10_000, "{name}: the walls must be receivers");
        assert!(
            e <= 0.5,
            "{name}: {e}% misclassified: a face looks the wrong way"
        );
    }
}

/// A 2 cm caster 3 cm from the light, inside the 5 cm near plane.
/// Criterion: with unclipped depth (or the 1 mm near-plane fallback) ≤ 1%
/// misclassified; with near-plane clipping its shadow vanishes (≥ 5% false
/// lit), and so it does for the renderers' ports, which clip at their
/// sources' near planes (LearnOpenGL 1 m, Bevy 0.1 m: their cards).
#[test]
fn lesson_04_caster_inside_the_near_plane() {
    let s = scene("lesson_04_near_caster.toml");
    let ports = ["learnopengl_1tap", "learnopengl_pcf20", "bevy_point"];
    let variants = [
        &["linear_1024", "depth_1024", "clipped_1024"][..],
        &ports[..],
    ]
    .concat();
    let Some(run) = support::run_lesson(BIN, "lesson_04_near", &args(&s, &variants)) else {
        return;
    };
    for v in ports {
        let lost = pct(&run, v, "false_lit_pct");
        assert!(
            lost >= 5.0,
            "{v} clips at its source's near plane and should lose the near caster's shadow, false lit {lost}%"
        );
        assert_eq!(counter(&run, v, UNCLIPPED_DEPTH.name), 0, "{v}");
    }
    for v in ["linear_1024", "depth_1024"] {
        let e = pct(&run, v, "misclassified_pct");
        assert!(
            e <= 1.0,
            "{v}: {e}% misclassified with the caster inside the near plane"
        );
    }
    let clipped = pct(&run, "clipped_1024", "false_lit_pct");
    assert!(
        clipped >= 5.0,
        "clipping should lose the near caster's shadow, false lit {clipped}%"
    );
}

/// Receivers past the light's range. The metric skips them (no light
/// reaches them), so this compares every covered pixel's visibility with
/// the reference. Criterion: ≤ 1% disagree when the receiver depth is
/// clamped to the range; without the clamp ≥ 20% (all of it reads shadow).
#[test]
fn lesson_04_receiver_beyond_the_range() {
    let s = scene("lesson_04_beyond_range.toml");
    let Some(run) = support::run_lesson(
        BIN,
        "lesson_04_range",
        &args(&s, &["linear_1024", "depth_1024", "no_range_clamp_1024"]),
    ) else {
        return;
    };
    for v in ["linear_1024", "depth_1024"] {
        let e = disagreement_pct(&run.out, v);
        assert!(
            e <= 1.0,
            "{v}: {e}% of covered pixels disagree with the reference"
        );
    }
    let naive = disagreement_pct(&run.out, "no_range_clamp_1024");
    assert!(
        naive >= 20.0,
        "without the clamp, receivers past the range should read shadowed: {naive}%"
    );
}

/// The default scene moved 100 km from the world origin. Criterion: ≤ 1%
/// misclassified, and within 0.1 points of the same scene at the origin.
#[test]
fn lesson_04_light_far_from_the_origin() {
    let s = scene("lesson_04_far_origin.toml");
    let Some(far) = support::run_lesson(BIN, "lesson_04_far", &args(&s, &["linear_1024"])) else {
        return;
    };
    let Some(near) = support::run_lesson(BIN, "lesson_04_far_ref", &args("", &["linear_1024"]))
    else {
        return;
    };
    let (a, b) = (
        pct(&far, "linear_1024", "misclassified_pct"),
        pct(&near, "linear_1024", "misclassified_pct"),
    );
    assert!(a <= 1.0, "100 km out: {a}% misclassified");
    assert!(
        (a - b).abs() <= 0.1,
        "100 km out: {a}% vs {b}% at the origin"
    );
}

/// A directional light is refused with one line that names lessons 01-03.
#[test]
fn lesson_04_refuses_directional_lights() {
    let o = support::lesson_command(BIN)
        .args(["--headless", "--scene", &scene("lesson_01.toml"), "--out"])
        .arg(support::out_dir("lesson_04_directional"))
        .output()
        .expect("run lesson_04");
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.starts_with("error: lesson_04"))
        .collect();
    assert_eq!(lines.len(), 1, "one error line: {err}");
    assert!(
        lines[0].contains("lights[0]")
            && lines[0].contains("lesson_01")
            && lines[0].contains("lesson_03"),
        "{err}"
    );
}
