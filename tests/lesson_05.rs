//! lesson_05 (z-pass shadow volumes): snapshot of the masks and error
//! figures on the default scene, and the z-pass failure measured.
//!
//! Run `cargo insta review` after a change to see what moved.

mod support;

use std::path::Path;

const BIN: &str = env!("CARGO_BIN_EXE_lesson_05");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

#[test]
fn lesson_05_snapshot() {
    let Some(run) = support::run_lesson(BIN, "lesson_05_snapshot", &SIZE) else {
        return;
    };
    let mut text = String::new();
    for k in 0..2 {
        text +=
            &format!("reference visibility, light {k} ('#' shadow, '.' lit, ' ' background):\n");
        text += &support::ascii_of(
            &run.out.join(format!("reference_visibility_l{k}.png")),
            64,
            18,
        );
        text += &format!("\n\nzpass_quads visibility, light {k}:\n");
        text += &support::ascii_of(
            &run.out.join(format!("zpass_quads_visibility_l{k}.png")),
            64,
            18,
        );
        text += "\n\n";
    }
    text += "error against the reference (1 decimal):\n";
    for v in run.report["variants"].as_array().unwrap() {
        text += &support::error_line(v, 1);
        text += "\n";
    }
    text += &support::counter_lines(
        &run.report,
        &["draws", "volume_triangles", "volume_fragments"],
    );
    insta::assert_snapshot!("lesson_05", text);
}

/// With the camera outside every volume, z-pass is exact (both builds).
#[test]
fn lesson_05_exact_when_the_eye_is_outside() {
    let Some(run) = support::run_lesson(BIN, "lesson_05_exact", &SIZE) else {
        return;
    };
    for v in ["zpass_cpu", "zpass_quads"] {
        let m = support::misclassified(&run, v);
        assert!(m <= 0.5, "{v}: {m:.3}% misclassified");
        let t = &support::variant(&run.report, v)["timing_ms"];
        assert!(
            t["volume"].as_f64().is_some() && t["lighting"].as_f64().is_some(),
            "{v}: volume and lighting timed"
        );
    }
    let cpu = &support::variant(&run.report, "zpass_cpu")["timing_ms"];
    assert!(
        cpu["cpu_silhouette"].as_f64().is_some(),
        "the CPU path reports cpu_silhouette"
    );
}

/// The eye in the umbra, and the near plane in a volume: z-pass misses the
/// "enter" count and the error is large.
#[test]
fn lesson_05_zpass_fails_inside_a_volume() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for (name, min) in [
        ("volume_eye_in_umbra.toml", 10.0),
        ("volume_near_slice.toml", 5.0),
    ] {
        let s = scenes.join(name);
        let args = [
            &SIZE[..],
            &["--scene", s.to_str().unwrap(), "--variant", "zpass_quads"],
        ]
        .concat();
        let Some(run) = support::run_lesson(BIN, &format!("lesson_05_{name}"), &args) else {
            return;
        };
        let m = support::misclassified(&run, "zpass_quads");
        assert!(
            m > min,
            "{name}: z-pass should fail here, misclassified {m:.2}%"
        );
    }
}
