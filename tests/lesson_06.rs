//! lesson_06 (z-fail with caps): snapshot of masks and error figures, the
//! missing-cap failure, and the proof that leaving out work changes no pixel.
//!
//! Run `cargo insta review` after a change to see what moved.

mod depth_formats;

use common::measure::counters::{
    CASTERS_SKIPPED, CASTERS_ZFAIL, CASTERS_ZPASS, DRAWS, OPEN_EDGES, SILHOUETTE_EDGES,
    STENCIL_UPDATES, VOLUME_FRAGMENTS, VOLUME_TRIANGLES,
};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_06");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

/// The default scene with every variant: the snapshot's run, which the
/// counters' test reads too (one run, not two).
fn default_run() -> Option<&'static support::LessonRun> {
    support::shared_run(BIN, "lesson_06_snapshot", &SIZE)
}

#[test]
fn lesson_06_snapshot() {
    let Some(run) = default_run() else {
        return;
    };
    let mut text =
        String::from("reference visibility, light 0 ('#' shadow, '.' lit, ' ' background):\n");
    text += &support::ascii_of(&run.out.join("reference_visibility_l0.png"), 64, 18);
    for v in ["zpass_quads", "zfail_quads", "zfail_no_back_cap"] {
        text += &format!("\n\n{v} visibility, light 0:\n");
        text += &support::ascii_of(&run.out.join(format!("{v}_visibility_l0.png")), 64, 18);
    }
    text += "\n\nerror against the reference (percent, 0.01 points):\n";
    for v in run.report["variants"].as_array().unwrap() {
        text += &support::error_line(v, 2);
        text += "\n";
    }
    text += &support::counter_lines(
        &run.report,
        &[DRAWS.name, VOLUME_TRIANGLES.name, VOLUME_FRAGMENTS.name],
    );
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(
            "lesson_06",
            support::tolerance::adapter_line(&run.report) + &text
        )
    });
}

/// The camera is in the roof's umbra: z-pass fails, z-fail is exact, and a
/// missing cap breaks it again, in the adapter's default depth format and
/// in Depth24PlusStencil8.
#[test]
fn lesson_06_zfail_is_exact_with_the_eye_in_shadow() {
    for format in depth_formats::DEPTH_FORMATS {
        let args = [&SIZE[..], &depth_formats::flag(format)].concat();
        let name = format!("lesson_06_exact_{format}");
        let Some(run) = support::run_lesson(BIN, &name, &args) else {
            return;
        };
        let (depth, storage) = depth_formats::used(&run.report, format);
        let zpass = support::misclassified(&run, "zpass_quads");
        let no_front = support::misclassified(&run, "zfail_no_front_cap");
        eprintln!(
            "{depth} ({storage}): zpass_quads {zpass:.3}%, zfail_no_front_cap {no_front:.3}%"
        );
        assert!(zpass > 10.0, "{depth}: z-pass must fail, {zpass:.2}%");
        for v in ["zfail_cpu", "zfail_quads", "zfail_selective"] {
            let m = support::misclassified(&run, v);
            assert!(m <= 0.5, "{depth}: {v}: {m:.3}% misclassified");
        }
        assert!(
            no_front > 10.0,
            "{depth}: without the front cap every lit caster face is counted: {no_front:.2}%"
        );
    }
}

/// Leaving out work (z-pass where the near plane is not shadowed, nothing
/// for casters whose volume misses the view) gives the same visibility,
/// pixel for pixel, as z-fail everywhere, for fewer fragments.
#[test]
fn lesson_06_selective_is_pixel_identical() {
    let args = [
        &SIZE[..],
        &["--variant", "zfail_quads", "--variant", "zfail_selective"],
    ]
    .concat();
    let Some(run) = support::run_lesson(BIN, "lesson_06_selective", &args) else {
        return;
    };
    for k in 0..2 {
        let a = image::open(run.out.join(format!("zfail_quads_visibility_l{k}.png")))
            .unwrap()
            .to_luma_alpha8();
        let b = image::open(run.out.join(format!("zfail_selective_visibility_l{k}.png")))
            .unwrap()
            .to_luma_alpha8();
        let differ = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
        assert_eq!(differ, 0, "light {k}: {differ} pixels differ");
    }
    let c = |v: &str, k: &str| support::variant(&run.report, v)["counters"][k].as_u64();
    assert!(
        c("zfail_selective", CASTERS_SKIPPED.name) >= Some(1),
        "the knot behind the camera is skipped"
    );
    assert!(
        c("zfail_selective", CASTERS_ZPASS.name) >= Some(1),
        "some casters use z-pass"
    );
    assert!(
        c("zfail_selective", CASTERS_ZFAIL.name) >= Some(1),
        "the roof needs z-fail"
    );
    // Fragment counts need PIPELINE_STATISTICS_QUERY (Vulkan); GL omits them.
    if let (Some(all), Some(sel)) = (
        c("zfail_quads", VOLUME_FRAGMENTS.name),
        c("zfail_selective", VOLUME_FRAGMENTS.name),
    ) {
        assert!(
            sel < all,
            "selective must rasterise fewer volume fragments: {sel} vs {all}"
        );
    }
}

// ---- lesson 06 under a finite far plane (issue 8) ----------------------

/// The z-fail variants, which must be exact.
const ZFAIL: [&str; 3] = ["zfail_cpu", "zfail_quads", "zfail_selective"];

/// Misclassified %: all, recounted from the diff PNG (red and green among
/// the receivers), and away from edges, the report's
/// `interior_misclassified_pct` (receivers more than 2 px from a change of
/// surface or of lit/shadowed in the reference).
fn interior_error(run: &support::LessonRun, variant: &str) -> (f64, f64) {
    let diff = image::open(run.out.join(format!("{variant}_diff_l0.png")))
        .unwrap()
        .to_rgba8();
    let (mut all, mut wrong) = (0u64, 0u64);
    for p in diff.pixels() {
        let [r, g, b, a] = p.0;
        let is_wrong = (r, g, b) == (255, 0, 0) || (r, g, b) == (0, 255, 0);
        if a == 255 && (is_wrong || (r == g && g == b && r >= 48)) {
            all += 1;
            wrong += u64::from(is_wrong);
        }
    }
    let inner = support::error(&run.report, variant, "interior_receiver_pixels");
    assert!(
        inner > 1000.0,
        "{variant}: only {inner} receiver pixels away from edges"
    );
    (
        100.0 * wrong as f64 / all.max(1) as f64,
        support::error(&run.report, variant, "interior_misclassified_pct"),
    )
}

/// Runs a finite-far scene and checks every z-fail variant against the
/// criterion: ≤ 0.5 % misclassified (the report's figure, which must agree
/// with the diff PNG), ≤ 0.05 % away from shadow edges.
fn finite_far_within_criterion(scene: &str, name: &str) -> Option<support::LessonRun> {
    let path = support::scene_path(scene);
    let args = [&SIZE[..], &["--scene", path.to_str().unwrap()]].concat();
    let run = support::run_lesson(BIN, name, &args)?;
    for v in ZFAIL {
        let reported = support::misclassified(&run, v);
        let (all, interior) = interior_error(&run, v);
        assert!(
            (all - reported).abs() < 0.01,
            "{v}: diff PNG {all:.3}% vs report {reported:.3}%"
        );
        assert!(
            reported <= 0.5,
            "{scene}, {v}: {reported:.3}% misclassified"
        );
        assert!(
            interior <= 0.05,
            "{scene}, {v}: {interior:.3}% misclassified away from edges"
        );
    }
    // The plan's z-pass casters (closed by their finite back cap) leave
    // the same pixels as z-fail everywhere.
    let vis = |v: &str| support::read_visibility(&run.out.join(format!("{v}_visibility_l0.png")));
    let (all, sel) = (vis("zfail_quads"), vis("zfail_selective"));
    let differ = all.1.iter().zip(&sel.1).filter(|(a, b)| a != b).count();
    assert_eq!(
        differ, 0,
        "{scene}: zfail_selective differs in {differ} pixels"
    );
    Some(run)
}

/// An open mesh (a generated tube), a point light, far = 200, and the eye
/// in the tube's shadow (z-pass is far off there).
#[test]
fn lesson_06_finite_far_open_mesh_eye_in_shadow() {
    let Some(run) = finite_far_within_criterion("lesson_06_finite_far_open.toml", "l06_far_open")
    else {
        return;
    };
    let zpass = support::misclassified(&run, "zpass_quads");
    assert!(
        zpass > 10.0,
        "the eye must be in shadow: z-pass {zpass:.2}%"
    );
    assert!(support::counter(&run.report, "zfail_quads", OPEN_EDGES.name) > 0);
}

/// A flat cut-out figure (a generated one-sided star), a spot light, far = 200.
#[test]
fn lesson_06_finite_far_cutout_spot() {
    finite_far_within_criterion("lesson_06_finite_far_cutout.toml", "l06_far_cutout");
}

/// A point light 0.3 above a caster, far = 200: the volume must reach
/// range / 0.3 times as far as the box top.
#[test]
fn lesson_06_finite_far_light_close_to_caster() {
    finite_far_within_criterion("lesson_06_finite_far_close_light.toml", "l06_far_close");
}

/// Runs lesson_06 on a scene and expects a refusal: non-zero exit, one line
/// on stderr that points to lesson 07.
fn expect_refusal(scene: &std::path::Path, name: &str) {
    let out = support::out_dir(name);
    let o = support::lesson_command(BIN)
        .args(["--headless", "--out", out.to_str().unwrap(), "--scene"])
        .arg(scene)
        .args(SIZE)
        .output()
        .expect("run lesson_06");
    let stderr = String::from_utf8_lossy(&o.stderr);
    if stderr.contains("no GPU adapter found") && !support::gpu_required() {
        eprintln!("SKIPPED {name}: no GPU adapter");
        return;
    }
    assert!(
        !o.status.success(),
        "{name}: exit 0 on a scene it cannot render exactly"
    );
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{name}: one line expected:\n{stderr}");
    assert!(
        lines[0].contains("camera.far") && lines[0].contains("lesson_07"),
        "{name}: {}",
        lines[0]
    );
}

/// Where neither the finite extrusion nor w = 0 is exact, lesson 06 says so:
/// the close-light scene with far = 40 (its volumes, extruded to cover the
/// range, reach past it), and a directional light with a finite far plane.
#[test]
fn lesson_06_refuses_finite_far_it_cannot_render() {
    let dir = support::out_dir("l06_far_40_scene");
    let text =
        std::fs::read_to_string(support::scene_path("lesson_06_finite_far_close_light.toml"))
            .unwrap();
    assert!(text.contains("far = 200.0"));
    let scene = dir.join("far_40.toml");
    std::fs::write(&scene, text.replace("far = 200.0", "far = 40.0")).unwrap();
    expect_refusal(&scene, "l06_far_40");
    expect_refusal(
        &support::scene_path("lesson_07.toml"),
        "l06_directional_far",
    );
}

/// A finite back cap can lie in front of the surface: the eye beyond the
/// card's volume looks back at its shadow through the cap. Z-fail meets the
/// criterion, and z-pass (the eye outside every volume) is exact too only
/// because it counts the finite back cap.
#[test]
fn lesson_06_finite_far_back_cap_in_front_of_the_surface() {
    let Some(run) =
        finite_far_within_criterion("lesson_06_finite_far_back_cap.toml", "l06_far_back_cap")
    else {
        return;
    };
    let zpass = support::misclassified(&run, "zpass_quads");
    assert!(zpass <= 0.5, "z-pass without the back cap: {zpass:.3}%");
}

/// Work saved shows in the counters: the selective plan rasterises fewer
/// volume fragments than z-fail everywhere; the CPU route submits fewer
/// triangles than the quads route; z-pass and z-fail update the stencil
/// at different fragments; every volume fragment is counted at most once
/// as an update.
#[test]
fn lesson_06_counters_show_work_saved() {
    let Some(run) = default_run() else {
        return;
    };
    let c = |v, k| support::counter(&run.report, v, k);
    let (selective, all) = (
        c("zfail_selective", VOLUME_FRAGMENTS.name),
        c("zfail_quads", VOLUME_FRAGMENTS.name),
    );
    assert!(
        selective < all,
        "zfail_selective rasterises {selective}, zfail_quads {all}"
    );
    assert!(
        c("zfail_cpu", VOLUME_TRIANGLES.name) < c("zfail_quads", VOLUME_TRIANGLES.name),
        "the CPU route submits only silhouettes"
    );
    assert_ne!(
        c("zpass_quads", STENCIL_UPDATES.name),
        c("zfail_quads", STENCIL_UPDATES.name)
    );
    for v in ["zpass_quads", "zfail_quads", "zfail_selective"] {
        assert!(
            c(v, STENCIL_UPDATES.name) <= c(v, VOLUME_FRAGMENTS.name),
            "{v}"
        );
        assert!(
            c(v, DRAWS.name) > 0 && c(v, VOLUME_TRIANGLES.name) > 0,
            "{v}"
        );
    }
}

/// The compute route (sides and both caps written by a compute shader,
/// drawn indirectly) leaves the CPU route's pixels and costs: on the
/// default scene (the eye in the roof's umbra, z-fail with caps) and on an
/// open mesh with a finite reach (far = 200).
#[test]
fn lesson_06_compute_matches_cpu() {
    for scene in ["lesson_06.toml", "lesson_06_finite_far_open.toml"] {
        let path = support::scene_path(scene);
        let args = [
            &SIZE[..],
            &["--scene", path.to_str().unwrap()],
            &["--variant", "zfail_cpu", "--variant", "zfail_compute"],
        ]
        .concat();
        let name = format!("lesson_06_compute_{}", scene.replace(".toml", ""));
        let Some(run) = support::run_lesson(BIN, &name, &args) else {
            return;
        };
        for file in ["", "_visibility_l0", "_diff_l0"] {
            let read = |v: &str| {
                image::open(run.out.join(format!("{v}{file}.png")))
                    .unwrap()
                    .to_rgba8()
                    .into_raw()
            };
            let (a, b) = (read("zfail_compute"), read("zfail_cpu"));
            let differ = a.iter().zip(&b).filter(|(p, q)| p != q).count();
            assert!(
                a.len() == b.len() && differ == 0,
                "{scene}{file}: {differ} bytes differ"
            );
        }
        for key in [
            VOLUME_FRAGMENTS.name,
            STENCIL_UPDATES.name,
            VOLUME_TRIANGLES.name,
            DRAWS.name,
            SILHOUETTE_EDGES.name,
        ] {
            let c = |v| support::counter(&run.report, v, key);
            assert_eq!(c("zfail_compute"), c("zfail_cpu"), "{scene}: {key}");
        }
        let m = support::misclassified(&run, "zfail_compute");
        assert!(m <= 0.5, "{scene}: {m:.3}% misclassified");
    }
}
