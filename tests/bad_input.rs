//! Bad input gets one clear line on stderr and a non-zero exit: never a
//! panic, never a hang. Each case names what is wrong (file, field, flag).

use std::path::PathBuf;

const BIN: &str = env!("CARGO_BIN_EXE_lesson_01");

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bad_input");
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs lesson_01 and returns its single stderr line, asserting failure.
fn fails(args: &[&str]) -> String {
    let out = support::tiny_headless(BIN, &dir().join("out"), args)
        .output()
        .expect("run lesson_01");
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(
        !out.status.success(),
        "expected failure for {args:?}, got success; stderr: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "panic for {args:?}: {stderr}");
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with("warning:"))
        .collect();
    assert_eq!(
        lines.len(),
        1,
        "expected one error line for {args:?}, got: {stderr}"
    );
    lines[0].to_string()
}

fn scene_file(name: &str, text: &str) -> String {
    let p = dir().join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

const GOOD_HEAD: &str = r#"
[camera]
eye = [4.0, 3.0, 6.0]
target = [0.0, 0.5, 0.0]
[[lights]]
type = "directional"
direction = [-0.4, -1.0, -0.3]
"#;

fn scene_with_object(name: &str, object: &str) -> String {
    scene_file(name, &format!("{GOOD_HEAD}\n[[objects]]\n{object}\n"))
}

#[test]
fn missing_scene_file() {
    let e = fails(&["--scene", "/nonexistent/scene.toml"]);
    assert!(
        e.contains("/nonexistent/scene.toml") && e.contains("cannot read"),
        "{e}"
    );
}

#[test]
fn malformed_scene_names_file_and_line() {
    let p = scene_file("malformed.toml", "[camera]\neye = [1.0, 2.0\n");
    let e = fails(&["--scene", &p]);
    assert!(
        e.contains("malformed.toml:2") || e.contains("malformed.toml:3"),
        "{e}"
    );
}

#[test]
fn unknown_field_is_named() {
    let p = scene_file(
        "unknown_field.toml",
        &format!("{GOOD_HEAD}\n[[objects]]\nmesh = \"cube\"\nscael = 2.0\n"),
    );
    let e = fails(&["--scene", &p]);
    assert!(e.contains("scael"), "{e}");
}

#[test]
fn unknown_mesh_name() {
    let p = scene_with_object("unknown_mesh.toml", "mesh = \"teapotz\"");
    let e = fails(&["--scene", &p]);
    assert!(
        e.contains("objects[0].mesh") && e.contains("teapotz"),
        "{e}"
    );
}

#[test]
fn nan_vector() {
    let p = scene_file(
        "nan.toml",
        "[camera]\neye = [4.0, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n[[lights]]\ntype = \"directional\"\ndirection = [nan, -1.0, 0.0]\n[[objects]]\nmesh = \"cube\"\n",
    );
    let e = fails(&["--scene", &p]);
    assert!(
        e.contains("lights[0].direction") && e.contains("finite"),
        "{e}"
    );
}

#[test]
fn zero_length_vector() {
    let p = scene_file(
        "zero.toml",
        "[camera]\neye = [4.0, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n[[lights]]\ntype = \"directional\"\ndirection = [0.0, 0.0, 0.0]\n[[objects]]\nmesh = \"cube\"\n",
    );
    let e = fails(&["--scene", &p]);
    assert!(
        e.contains("lights[0].direction") && e.contains("zero-length"),
        "{e}"
    );
}

#[test]
fn zero_scale() {
    let p = scene_with_object(
        "zero_scale.toml",
        "mesh = \"cube\"\nscale = [1.0, 0.0, 1.0]",
    );
    let e = fails(&["--scene", &p]);
    assert!(e.contains("objects[0].scale"), "{e}");
}

#[test]
fn missing_obj_file() {
    let p = scene_with_object("missing_obj.toml", "mesh = \"no_such_model.obj\"");
    let e = fails(&["--scene", &p]);
    assert!(e.contains("no_such_model.obj"), "{e}");
}

#[test]
fn empty_mesh() {
    std::fs::write(dir().join("empty.obj"), "# nothing here\nv 0 0 0\n").unwrap();
    let p = scene_with_object("empty_mesh.toml", "mesh = \"empty.obj\"");
    let e = fails(&["--scene", &p]);
    assert!(e.contains("empty.obj"), "{e}");
}

#[test]
fn degenerate_triangles_only() {
    std::fs::write(
        dir().join("degenerate.obj"),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n",
    )
    .unwrap();
    let p = scene_with_object("degenerate.toml", "mesh = \"degenerate.obj\"");
    let e = fails(&["--scene", &p]);
    assert!(
        e.contains("degenerate.obj") && e.contains("degenerate"),
        "{e}"
    );
}

#[test]
fn nan_in_obj() {
    std::fs::write(
        dir().join("nan.obj"),
        "v 0 0 0\nv 1 nan 0\nv 0 0 1\nf 1 2 3\n",
    )
    .unwrap();
    let p = scene_with_object("nan_obj.toml", "mesh = \"nan.obj\"");
    let e = fails(&["--scene", &p]);
    assert!(e.contains("nan.obj"), "{e}");
}

#[test]
fn nonsense_cli_values() {
    assert!(fails(&["--width", "abc"]).contains("--width"));
    assert!(
        fails(&["--width", "-5"]).contains("--width") || fails(&["--width", "-5"]).contains("-5")
    );
    assert!(fails(&["--frames", "0"]).contains("--frames"));
    assert!(fails(&["--backend", "glide"]).contains("--backend"));
    assert!(fails(&["--no-such-flag"]).contains("--no-such-flag"));
}

#[test]
fn unknown_variant() {
    let e = fails(&["--variant", "res_123"]);
    assert!(
        e.contains("--variant") && e.contains("res_123") && e.contains("res_1024"),
        "{e}"
    );
}

#[test]
fn point_light_is_refused_by_lesson_01() {
    let p = scene_file(
        "point.toml",
        "[camera]\neye = [4.0, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n[[lights]]\ntype = \"point\"\nposition = [0.0, 3.0, 0.0]\nrange = 10.0\n[[objects]]\nmesh = \"cube\"\n",
    );
    let e = fails(&["--scene", &p]);
    assert!(e.contains("lights[0]") && e.contains("lesson_04"), "{e}");
}

/// A light's size: each bad value is one line naming the field; a good one
/// is refused by the hard-shadow lessons in one line naming lesson 10.
#[test]
fn bad_light_sizes_name_the_field() {
    let light = |extra: &str, kind: &str| {
        let place = match kind {
            "directional" => "direction = [-0.4, -1.0, -0.3]",
            _ => "position = [0.0, 3.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\nrange = 10.0\nspot_angle_deg = 60.0",
        };
        format!("[camera]\neye = [4.0, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n[[lights]]\ntype = \"{kind}\"\n{place}\n{extra}\n[[objects]]\nmesh = \"cube\"\n")
    };
    let cases = [
        ("radius = -0.1", "spot", "lights[0].radius"),
        ("radius = 6.0", "spot", "lights[0].radius"),
        (
            "angular_radius_deg = 2.0",
            "spot",
            "lights[0].angular_radius_deg",
        ),
        ("radius = 0.1", "directional", "lights[0].radius"),
        (
            "angular_radius_deg = 90.0",
            "directional",
            "lights[0].angular_radius_deg",
        ),
        (
            "angular_radius_deg = nan",
            "directional",
            "lights[0].angular_radius_deg",
        ),
    ];
    for (i, (extra, kind, field)) in cases.into_iter().enumerate() {
        let p = scene_file(&format!("size_{i}.toml"), &light(extra, kind));
        let e = fails(&["--scene", &p]);
        assert!(e.contains(field), "{extra} on a {kind} light: {e}");
    }
    // A valid size: lesson 01 refuses it, naming lesson 10.
    let p = scene_file(
        "size_ok.toml",
        &light("angular_radius_deg = 0.27", "directional"),
    );
    let e = fails(&["--scene", &p]);
    assert!(
        e.contains("angular_radius_deg") && e.contains("lesson_10"),
        "{e}"
    );
}

#[test]
fn no_adapter_says_what_to_install() {
    // No Metal on Linux: the same path a machine without any driver takes.
    if cfg!(target_os = "macos") {
        return;
    }
    let e = fails(&["--backend", "metal"]);
    assert!(
        e.contains("no GPU adapter found")
            && e.contains("mesa-vulkan-drivers")
            && e.contains("macOS"),
        "{e}"
    );
}

/// The grader with no adapter (no Metal on Linux): one line that says what
/// to install and that Windows and macOS use their GPU, exit code 2, not
/// a failed check per exercise.
#[test]
fn grade_without_an_adapter_says_what_to_install() {
    if cfg!(target_os = "macos") {
        return;
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_grade"))
        .args(["lesson_02", "--backend", "metal", "--out"])
        .arg(dir().join("grade_no_adapter"))
        .env_remove("CARGO")
        .output()
        .expect("run grade");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "want one line, got {stderr}");
    assert!(
        lines[0].contains("no GPU adapter found")
            && lines[0].contains("mesa-vulkan-drivers")
            && lines[0].contains("macOS"),
        "{stderr}"
    );
}

/// The grader's own bad input: one line, exit code 2, before any run.
#[test]
fn grade_bad_input_is_one_line() {
    let grade = env!("CARGO_BIN_EXE_grade");
    let missing = dir().join("no_such_folder");
    for (args, want) in [
        (vec!["lesson_99"], "lesson_99: no such chapter"),
        (
            vec!["lesson_01", "--scenes", missing.to_str().unwrap()],
            "--scenes",
        ),
        (vec!["lesson_01", "--adapter", " "], "--adapter"),
    ] {
        let out = std::process::Command::new(grade)
            .args(&args)
            .env_remove("CARGO")
            .output()
            .expect("run grade");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
        assert_eq!(lines.len(), 1, "{args:?}: want one line, got {stderr}");
        assert!(
            lines[0].contains(want),
            "{args:?}: want {want:?} in {}",
            lines[0]
        );
    }
}

/// `--adapter` with a name no adapter has: one line naming the flag.
#[test]
fn unknown_adapter_is_one_line() {
    let e = fails(&["--adapter", "no-such-gpu-9000"]);
    assert!(
        e.contains("--adapter") && e.contains("no-such-gpu-9000"),
        "{e}"
    );
}

/// `--depth-format` with a format the workbook does not offer: one line
/// naming the flag and the value.
#[test]
fn unknown_depth_format_is_one_line() {
    let e = fails(&["--depth-format", "depth16unorm"]);
    assert!(
        e.contains("--depth-format") && e.contains("depth16unorm"),
        "{e}"
    );
}

/// A long bad value is quoted by its start and its length: one short line.
#[test]
fn long_bad_values_are_cut_in_the_error_line() {
    let long = "x".repeat(100_000);
    let cases = [
        (fails(&["--variant", &long]), "--variant"),
        (fails(&["--warm-up-ms", &"9".repeat(5_000)]), "--warm-up-ms"),
        (
            fails(&[
                "--scene",
                &scene_with_object("long_mesh.toml", &format!("mesh = \"{long}\"")),
            ]),
            "long_mesh.toml",
        ),
    ];
    for (e, names) in cases {
        let n = e.chars().count();
        assert!(n < 600, "{n} characters: {}", &e[..300]);
        assert!(e.contains(names), "{e}");
        assert!(e.contains(" characters)"), "{e}");
    }
}

/// A view that sees no receiver must not exit 0 with 0.000 %: a far plane
/// in front of the whole scene, and a camera looking away from it.
#[test]
fn a_view_with_no_receiver_is_refused() {
    let near_far = scene_file(
        "far_before_scene.toml",
        r#"
[camera]
eye = [0.0, 3.0, 8.0]
target = [0.0, 0.0, 0.0]
near = 0.1
far = 0.5
[[lights]]
type = "directional"
direction = [-0.4, -1.0, -0.3]
[[objects]]
mesh = "plane"
scale = [10.0, 1.0, 10.0]
[[objects]]
mesh = "cube"
translate = [0.0, 0.5, 0.0]
"#,
    );
    let e = fails(&["--scene", &near_far]);
    assert!(
        e.contains("far_before_scene.toml")
            && e.contains("sees no geometry")
            && e.contains("far plane (0.5)")
            && e.contains("[camera]"),
        "{e}"
    );
    // Geometry in view, but every surface faces away from the light.
    let away = scene_file(
        "lit_from_below.toml",
        r#"
[camera]
eye = [0.0, 3.0, 8.0]
target = [0.0, 0.0, 0.0]
[[lights]]
type = "directional"
direction = [0.0, 1.0, 0.0]
[[objects]]
mesh = "plane"
scale = [10.0, 1.0, 10.0]
"#,
    );
    let e = fails(&["--scene", &away]);
    assert!(
        e.contains("faces a light") && e.contains("lit_from_below.toml"),
        "{e}"
    );
}

/// `WORKBOOK_EXERCISES` (the exercise set a run uses) naming no set, or a
/// set the build does not hold: one line naming the variable, exit 2, from
/// a lesson and from the grader.
#[test]
fn bad_exercise_set_is_one_line() {
    let mut cases = vec![("bogus", "not an exercise set")];
    if !cfg!(feature = "chapter_copies") {
        cases.push(("chapter_copies", "--features chapter_copies"));
    }
    for (value, want) in cases {
        for (bin, args) in [
            (BIN, &["--frames", "1"][..]),
            (env!("CARGO_BIN_EXE_grade"), &["lesson_01"][..]),
        ] {
            let out = std::process::Command::new(bin)
                .args(args)
                .env("WORKBOOK_EXERCISES", value)
                .env_remove("CARGO")
                .output()
                .expect("run");
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{bin} {value}: {stderr}");
            let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
            assert_eq!(lines.len(), 1, "{bin} {value}: want one line, got {stderr}");
            assert!(
                lines[0].contains(&format!("WORKBOOK_EXERCISES={value}"))
                    && lines[0].contains(want),
                "{bin} {value}: {}",
                lines[0]
            );
        }
    }
}

/// `--times-only` measures times alone: asked for no timing (as
/// `WORKBOOK_NO_TIMING=1`, which the tests' runs set) or for the bounds of
/// figures it does not measure, it says which flag and stops; a
/// `--fragile-variant` that is not one of the run's variants is named.
#[test]
fn times_only_and_fragile_variant_name_what_they_cannot_do() {
    let e = fails(&["--times-only"]);
    assert!(
        e.contains("--times-only") && e.contains("WORKBOOK_NO_TIMING"),
        "{e}"
    );
    let out = support::tiny_headless(BIN, &dir().join("out"), &["--times-only", "--fragile"])
        .env("WORKBOOK_NO_TIMING", "0")
        .output()
        .expect("run lesson_01");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success(),
        "--times-only --fragile ran: {stderr}"
    );
    assert!(stderr.contains("--fragile"), "{stderr}");
    let e = fails(&["--variant", "res_256", "--fragile-variant", "res_2048"]);
    assert!(
        e.contains("--fragile-variant") && e.contains("res_2048") && e.contains("res_256"),
        "{e}"
    );
}
