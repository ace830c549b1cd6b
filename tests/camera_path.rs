//! A scene's `[camera_path]` (chapter 09; the book's appendix "Interfaces"):
//! the headless runner renders the path and counts shadow pixels that flip:
//! world-locked (shimmer: frame i's view with frame i + 1's fit, where the
//! reference cannot flip) and screen-space (consecutive frames, flips the
//! reference does not make). It refuses the path for a lesson that does not
//! re-read the camera each frame.
//!
//! The scenes are a lesson's default scene with a path appended, written
//! to a temporary folder.

use std::path::{Path, PathBuf};

const LESSON_01: &str = env!("CARGO_BIN_EXE_lesson_01");
const LESSON_05: &str = env!("CARGO_BIN_EXE_lesson_05");

/// `scene` with `path` appended as `[camera_path]`, in the test's folder.
fn scene_with_path(dir: &Path, scene: &str, path: &str) -> PathBuf {
    let file = dir.join("scene.toml");
    std::fs::write(&file, format!("{scene}\n[camera_path]\n{path}\n")).expect("write the scene");
    file
}

fn f(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing: {v}"))
}

/// Lesson 01 fits its map to the scene's bounds, not to the camera: moved
/// to the next frame's camera, its fit does not change, so nothing
/// shimmers (world-locked, exactly 0). On screen its unbiased acne is a
/// moiré of texels and pixels that moves whenever the camera does, and a
/// dolly moves the true shadow edges: the screen-space figures are not 0.
#[test]
fn lesson_01_does_not_shimmer_while_its_acne_crawls_on_screen() {
    let dir = support::out_dir("camera_path_lesson_01_scene");
    let scene = scene_with_path(
        &dir,
        include_str!("../scenes/lesson_01.toml"),
        "frames = 8\npan_deg = 2.0\ndolly = 1.0",
    );
    let args = [
        "--scene",
        scene.to_str().expect("utf-8 path"),
        "--width",
        "320",
        "--height",
        "180",
        "--frames",
        "1",
        "--variant",
        "res_256",
        "--variant",
        "res_4096",
    ];
    let Some(run) = support::run_lesson(LESSON_01, "camera_path_lesson_01", &args) else {
        return;
    };
    assert!(run.stdout.contains("| shimmer %"), "{}", run.stdout);
    for name in ["res_256", "res_4096"] {
        let v = support::variant(&run.report, name);
        let p = &v["camera_path"];
        assert_eq!(p["frames"].as_u64(), Some(8), "{name}: {p}");
        let per_frame = p["misclassified_pct_per_frame"]
            .as_array()
            .expect("per frame");
        assert_eq!(per_frame.len(), 8, "{name}: {p}");
        // Frame 0 is the scene's camera: the same figure as the variant's error.
        let first = per_frame[0].as_f64().unwrap_or(f64::NAN);
        let error = f(&v["error"], "misclassified_pct");
        assert!((first - error).abs() < 1e-9, "{name}: {first} vs {error}");
        let (shimmer, mismatch, reference, technique) = (
            f(p, "shimmer_pct"),
            f(p, "screen_mismatch_pct"),
            f(p, "reference_flip_pct"),
            f(p, "technique_flip_pct"),
        );
        // The fit does not follow the camera: no world-locked flip at all.
        assert_eq!(shimmer, 0.0, "{name}: {p}");
        // The dolly moves the true shadow edges; the acne crawls.
        assert!(reference > 0.0, "{name}: {p}");
        assert!(mismatch > 0.0, "{name}: {p}");
        // The mismatch is the technique's flips that the reference does
        // not make: no more than its flips, no fewer than its flips minus
        // the reference's.
        assert!(mismatch < technique, "{name}: {p}");
        assert!(technique <= mismatch + reference + 1e-9, "{name}: {p}");
        // The shimmer picture is black: nothing flipped world-locked.
        let img = image::open(run.out.join(format!("{name}_shimmer.png")))
            .expect("shimmer image")
            .to_luma8();
        assert_eq!(img.dimensions(), (320, 180));
        assert!(img.pixels().all(|p| p.0[0] == 0), "{name}: not black");
        // Over the frame: the scene in grey, no flip drawn (no orange).
        let over = image::open(run.out.join(format!("{name}_shimmer_over.png")))
            .expect("shimmer image over the frame")
            .to_rgba8();
        assert_eq!(over.dimensions(), (320, 180));
        assert!(
            over.pixels().all(|p| p.0[0] == p.0[1] && p.0[1] == p.0[2]),
            "{name}: a flip drawn"
        );
        assert!(
            over.pixels().any(|p| p.0[0] > 40),
            "{name}: no scene under the flips"
        );
        assert!(v.get("classes").is_none(), "lesson 01 has no pixel classes");
    }
}

/// Without `[camera_path]` the report and the table are as before.
#[test]
fn without_a_path_nothing_is_added() {
    let args = ["--width", "64", "--height", "36", "--frames", "1"];
    let args = [&args[..], &["--variant", "res_256"]].concat();
    let Some(run) = support::run_lesson(LESSON_01, "camera_path_none", &args) else {
        return;
    };
    assert!(!run.stdout.contains("shimmer"), "{}", run.stdout);
    let v = support::variant(&run.report, "res_256");
    assert!(v.get("camera_path").is_none(), "{v}");
    assert!(!run.out.join("res_256_shimmer.png").exists());
}

/// Runs `bin` on `scene` (tiny, one frame) and returns its stderr, which
/// must be one line, after a non-zero exit.
fn refused(bin: &str, name: &str, scene: &Path) -> String {
    let out = support::out_dir(name);
    let scene = scene.to_str().expect("utf-8 path");
    let o = support::tiny_headless(bin, &out, &["--scene", scene])
        .output()
        .expect("run the lesson");
    let stderr = String::from_utf8_lossy(&o.stderr).to_string();
    if stderr.contains("no GPU adapter found") {
        support::gpu_required();
    }
    assert!(!o.status.success(), "{name}: accepted; stderr: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: {stderr}");
    assert!(!out.join("report.json").exists(), "{name}: wrote a report");
    stderr
}

/// Lesson 05 does not re-read the camera for a path: a figure it gave
/// would be silently wrong, so it refuses the scene in one line.
#[test]
fn a_lesson_that_does_not_refit_refuses_a_path() {
    let dir = support::out_dir("camera_path_lesson_05_scene");
    let scene = scene_with_path(
        &dir,
        include_str!("../scenes/lesson_05.toml"),
        "dolly = 1.0",
    );
    let e = refused(LESSON_05, "camera_path_lesson_05", &scene);
    assert!(
        e.contains("[camera_path]: lesson_05 does not re-fit to a moving camera"),
        "{e}"
    );
}

/// A path that does not move, or has fewer than 2 frames, says which field.
#[test]
fn a_path_that_does_not_move_is_refused() {
    let text = include_str!("../scenes/lesson_01.toml");
    for (i, (path, want)) in [
        (
            "pan_deg = 0.0\ndolly = 0.0",
            "camera_path: pan_deg and dolly are both 0",
        ),
        (
            "frames = 1\ndolly = 1.0",
            "camera_path.frames: must be in [2, 1000], got 1",
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let dir = support::out_dir(&format!("camera_path_still_{i}_scene"));
        let scene = scene_with_path(&dir, text, path);
        let e = refused(LESSON_01, &format!("camera_path_still_{i}"), &scene);
        assert!(e.contains(want), "{path:?}: {e}");
    }
}
