//! lesson_06 (z-fail with caps): snapshot of masks and error figures, the
//! missing-cap failure, and the proof that leaving out work changes no pixel.
//!
//! Run `cargo insta review` after a change to see what moved.

mod support;

const BIN: &str = env!("CARGO_BIN_EXE_lesson_06");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

#[test]
fn lesson_06_snapshot() {
    let Some(run) = support::run_lesson(BIN, "lesson_06_snapshot", &SIZE) else {
        return;
    };
    let mut text =
        String::from("reference visibility, light 0 ('#' shadow, '.' lit, ' ' background):\n");
    text += &support::ascii_of(&run.out.join("reference_visibility_l0.png"), 64, 18);
    for v in ["zpass_quads", "zfail_quads", "zfail_no_back_cap"] {
        text += &format!("\n\n{v} visibility, light 0:\n");
        text += &support::ascii_of(&run.out.join(format!("{v}_visibility_l0.png")), 64, 18);
    }
    text += "\n\nerror against the reference (1 decimal):\n";
    for v in run.report["variants"].as_array().unwrap() {
        text += &support::error_line(v, 1);
        text += "\n";
    }
    insta::assert_snapshot!("lesson_06", text);
}

/// The camera is in the roof's umbra: z-pass fails, z-fail is exact, and a
/// missing cap breaks it again.
#[test]
fn lesson_06_zfail_is_exact_with_the_eye_in_shadow() {
    let Some(run) = support::run_lesson(BIN, "lesson_06_exact", &SIZE) else {
        return;
    };
    assert!(support::misclassified(&run, "zpass_quads") > 10.0);
    for v in ["zfail_cpu", "zfail_quads", "zfail_selective"] {
        let m = support::misclassified(&run, v);
        assert!(m <= 0.5, "{v}: {m:.3}% misclassified");
    }
    let no_front = support::misclassified(&run, "zfail_no_front_cap");
    assert!(
        no_front > 10.0,
        "without the front cap every lit caster face is counted: {no_front:.2}%"
    );
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
        c("zfail_selective", "casters_skipped") >= Some(1),
        "the knot behind the camera is skipped"
    );
    assert!(
        c("zfail_selective", "casters_zpass") >= Some(1),
        "some casters use z-pass"
    );
    assert!(
        c("zfail_selective", "casters_zfail") >= Some(1),
        "the roof needs z-fail"
    );
    // Fragment counts need PIPELINE_STATISTICS_QUERY (Vulkan); GL omits them.
    if let (Some(all), Some(sel)) = (
        c("zfail_quads", "volume_fragments"),
        c("zfail_selective", "volume_fragments"),
    ) {
        assert!(
            sel < all,
            "selective must rasterise fewer volume fragments: {sel} vs {all}"
        );
    }
}
