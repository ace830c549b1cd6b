//! Hostile input (issue 8): one test per class. Nothing panics, hangs or
//! exits 0 with a meaningless result; a refusal is one line that names the
//! field and the allowed range (the limits are in `common::scene::limits`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::scene::{LightKind, Scene};

const L01: &str = env!("CARGO_BIN_EXE_lesson_01");
const L05: &str = env!("CARGO_BIN_EXE_lesson_05");
const L06: &str = env!("CARGO_BIN_EXE_lesson_06");

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("hostile_input");
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(name: &str, text: &str) -> String {
    let p = dir().join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

const CAMERA: &str = "[camera]\neye = [4.0, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n";
const SUN: &str = "[[lights]]\ntype = \"directional\"\ndirection = [-0.4, -1.0, -0.3]\n";
const FLOOR: &str = "[[objects]]\nmesh = \"plane\"\nscale = 10.0\n";
const CUBE: &str = "[[objects]]\nmesh = \"cube\"\ntranslate = [0.0, 0.5, 0.0]\n";

fn headless(bin: &str, args: &[&str]) -> Command {
    support::tiny_headless(bin, &dir().join("out"), args)
}

/// The one error line of a run that must fail (no panic).
fn error_line(out: &Output, what: &str) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "{what}: exit 0; stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{what}: panic: {stderr}");
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with("warning:"))
        .collect();
    assert_eq!(lines.len(), 1, "{what}: want one error line, got: {stderr}");
    lines[0].to_string()
}

/// Runs lesson_01 on a scene and returns its single error line.
fn refused(name: &str, scene: &str) -> String {
    let p = write(&format!("{name}.toml"), scene);
    error_line(&headless(L01, &["--scene", &p]).output().unwrap(), name)
}

fn parse(text: &str) -> common::Result<Scene> {
    Scene::parse(text, "s.toml", &dir())
}

#[test]
fn absurd_magnitudes_name_the_field_and_the_range() {
    let obj = |n: &str, v: &str| write(n, &format!("v 0 0 0\nv {v} 0 0\nv 0 0 1\nf 1 2 3\n"));
    obj("v1e30.obj", "1e30");
    obj("v1e38.obj", "1e38");
    let cases: Vec<(&str, String, &[&str])> = vec![
        ("scale_1e20", format!("{CAMERA}{SUN}{FLOOR}[[objects]]\nmesh = \"cube\"\nscale = 1e20\n"), &["objects[1].scale", "[1e-6, 1e6]", "1e20"]),
        ("scale_1e300", format!("{CAMERA}{SUN}{FLOOR}[[objects]]\nmesh = \"cube\"\nscale = [1.0, 1e300, 1.0]\n"), &["objects[1].scale", "1e300"]),
        ("translate_1e300", format!("{CAMERA}{SUN}{FLOOR}[[objects]]\nmesh = \"cube\"\ntranslate = [-1e300, 0.0, 0.0]\n"), &["objects[1].translate", "±1e6", "-1e300"]),
        ("floor_1e9", format!("{CAMERA}{SUN}[[objects]]\nmesh = \"plane\"\nscale = 1e9\n{CUBE}"), &["objects[0].scale", "1e9"]),
        ("floor_1e12", format!("{CAMERA}{SUN}[[objects]]\nmesh = \"plane\"\nscale = 1e12\n{CUBE}"), &["objects[0].scale", "1e12"]),
        ("object_at_1e8", format!("{CAMERA}{SUN}{FLOOR}{CUBE}[[objects]]\nmesh = \"cube\"\ntranslate = [1e8, 0.0, 0.0]\n"), &["objects[2].translate", "±1e6", "1e8"]),
        // Inside the world bound but too far from the rest: the extent.
        ("object_at_5e5", format!("{CAMERA}{SUN}{FLOOR}{CUBE}[[objects]]\nmesh = \"cube\"\ntranslate = [5e5, 0.0, 0.0]\n"), &["objects[2]", "1e5 units"]),
        ("point_light_1e20", format!("{CAMERA}[[lights]]\ntype = \"spot\"\nposition = [0.0, 1e20, 0.0]\ndirection = [0.0, -1.0, 0.0]\nrange = 10.0\nspot_angle_deg = 40.0\n{FLOOR}"), &["lights[0].position", "±1e6", "1e20"]),
        ("eye_1e300", format!("[camera]\neye = [1e300, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n{SUN}{FLOOR}"), &["camera.eye", "±1e6", "1e300"]),
        ("fov_1e-9", format!("{CAMERA}fov_y_deg = 1e-9\n{SUN}{FLOOR}"), &["camera.fov_y_deg", "[0.1, 179)", "1e-9"]),
        ("near_1e-7", format!("{CAMERA}near = 1e-7\n{SUN}{FLOOR}"), &["camera.near", "[1e-6, 1e6]", "1e-7"]),
        ("near_1e-30_far_1e30", format!("{CAMERA}near = 1e-30\nfar = 1e30\n{SUN}{FLOOR}"), &["camera.near", "1e-30"]),
        ("near_1e-6_far_100", format!("{CAMERA}near = 1e-6\nfar = 100.0\n{SUN}{FLOOR}"), &["camera.near", "at most 1e6", "raise near"]),
        ("near_1e308", format!("{CAMERA}near = 1e308\n{SUN}{FLOOR}"), &["camera.near", "1e308"]),
        ("obj_vertex_1e30", format!("{CAMERA}{SUN}{FLOOR}[[objects]]\nmesh = \"v1e30.obj\"\n"), &["objects[1].mesh", "v1e30.obj:2", "±1e6"]),
        ("obj_vertex_1e38", format!("{CAMERA}{SUN}{FLOOR}[[objects]]\nmesh = \"v1e38.obj\"\n"), &["objects[1].mesh", "v1e38.obj:2", "±1e6"]),
    ];
    for (name, scene, want) in cases {
        let e = refused(name, &scene);
        for w in want {
            assert!(e.contains(w), "{name}: {w:?} missing from: {e}");
        }
        // Short numbers: no run of 10 digits (1e308 is not 309 of them).
        let longest = e.split(|c: char| !c.is_ascii_digit()).map(str::len).max();
        assert!(longest.unwrap_or(0) < 10, "{name}: long number in: {e}");
    }
}

#[test]
fn supported_extremes_are_accepted_and_directions_normalised() {
    // Lesson 07's deep range, and a scene 10 km out.
    parse(&format!("{CAMERA}near = 1e-3\nfar = 1e5\n{SUN}{FLOOR}")).expect("near 1e-3, far 1e5");
    let far_out = "[camera]\neye = [10004.0, 3.0, 6.0]\ntarget = [10000.0, 0.5, 0.0]\n";
    parse(&format!("{far_out}{SUN}[[objects]]\nmesh = \"plane\"\ntranslate = [10000.0, 0.0, 0.0]\nscale = 10.0\n"))
        .expect("10 km offset");
    // A direction of length 1e200 (its square overflows) and 1e-200 (underflows).
    for len in ["1e200", "1e-200"] {
        let s = parse(&format!(
            "{CAMERA}[[lights]]\ntype = \"directional\"\ndirection = [0.0, -{len}, 0.0]\n{FLOOR}"
        ))
        .unwrap_or_else(|e| panic!("direction of length {len}: {e}"));
        match s.lights[0].kind {
            LightKind::Directional { direction } => assert_eq!(direction.y, -1.0, "{len}"),
            k => panic!("{k:?}"),
        }
    }
}

#[test]
fn serde_messages_name_the_field() {
    let cases: Vec<(&str, String, &str)> = vec![
        ("scale_word", format!("{CAMERA}{SUN}[[objects]]\nmesh = \"cube\"\nscale = \"big\"\n"), "scale: expected a number or [x, y, z], got \"big\""),
        ("scale_two", format!("{CAMERA}{SUN}[[objects]]\nmesh = \"cube\"\nscale = [1.0, 2.0]\n"), "scale: expected a number or [x, y, z]"),
        ("far_true", format!("{CAMERA}far = true\n{SUN}{FLOOR}"), "far: expected a number or \"infinite\", got true"),
        ("far_array", format!("{CAMERA}far = [1.0, 2.0, 3.0]\n{SUN}{FLOOR}"), "far: expected a number or \"infinite\""),
        ("duplicate_translate", format!("{CAMERA}{SUN}[[objects]]\nmesh = \"cube\"\ntranslate = [0.0, 0.0, 0.0]\ntranslate = [1.0, 0.0, 0.0]\n"), "duplicate key `translate`"),
        ("duplicate_camera", format!("{CAMERA}{CAMERA}{SUN}{FLOOR}"), "duplicate table `[camera]`"),
    ];
    for (name, scene, want) in cases {
        let e = refused(name, &scene);
        assert!(e.contains(want), "{name}: want {want:?}, got: {e}");
        assert!(!e.contains("untagged"), "{name}: {e}");
    }
}

#[test]
fn frames_have_an_upper_bound() {
    let e = error_line(
        &support::lesson_command(L01)
            .args(["--headless", "--frames", "10000"])
            .output()
            .unwrap(),
        "--frames 10000",
    );
    assert!(e.contains("--frames") && e.contains("1..=1000"), "{e}");
}

#[test]
fn a_failed_write_to_stdout_is_an_error() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        eprintln!("SKIPPED: no /dev/full on this system");
        return;
    };
    let list = support::lesson_command(L01)
        .arg("--list-variants")
        .stdout(full.try_clone().unwrap())
        .output()
        .unwrap();
    let e = error_line(&list, "--list-variants > /dev/full");
    assert!(e.contains("cannot write to stdout"), "{e}");
    let run = headless(L01, &[]).stdout(full).output().unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    if stderr.contains("no GPU adapter found") && !support::gpu_required() {
        eprintln!("SKIPPED headless > /dev/full: no GPU adapter");
        return;
    }
    let e = error_line(&run, "--headless > /dev/full");
    assert!(e.contains("cannot write to stdout"), "{e}");
}

/// An OBJ of 200k copies of one triangle (each with its own `v` lines).
fn duplicate_triangles_obj(path: &Path) {
    let mut s = String::with_capacity(12_000_000);
    for _ in 0..200_000 {
        s += "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0 1 0.5\n";
    }
    for k in 0..200_000 {
        let a = 3 * k + 1;
        s += &format!("f {a} {} {}\n", a + 1, a + 2);
    }
    std::fs::write(path, s).unwrap();
}

#[test]
fn duplicate_triangles_cost_linear_time() {
    duplicate_triangles_obj(&dir().join("dup200k.obj"));
    let scene = write(
        "dup200k.toml",
        &format!("{CAMERA}far = \"infinite\"\n{SUN}{FLOOR}[[objects]]\nmesh = \"dup200k.obj\"\n"),
    );
    for bin in [L01, L05, L06] {
        let start = Instant::now();
        let variant = match bin {
            L01 => "res_1024",
            L05 => "zpass_cpu",
            _ => "zfail_cpu",
        };
        let mut child = headless(bin, &["--scene", &scene, "--variant", variant])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Before the fix: past 60 s on each of these lessons.
        let limit = Duration::from_secs(30);
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > limit {
                let _ = child.kill();
                panic!("{bin}: 200k duplicate triangles still running after {limit:?}");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        if stderr.contains("no GPU adapter found") && !support::gpu_required() {
            eprintln!("SKIPPED {bin}: no GPU adapter");
            continue;
        }
        assert!(out.status.success(), "{bin}: {stderr}");
        assert!(
            stderr.contains("dropped 199999 duplicate triangle(s)"),
            "{bin}: {stderr}"
        );
    }
}

/// Two floors a micrometre apart, the lower one listed (and drawn) first:
/// the reference sees the upper floor, the GPU's depth cannot tell them
/// apart and keeps the first. Before `coverage_mismatch_pct`, every figure
/// read "0 % misclassified" over the few pixels where the two agreed.
#[test]
fn coverage_mismatch_is_reported_and_warned() {
    let scene = write(
        "coverage_mismatch.toml",
        &format!("{CAMERA}{SUN}[[objects]]\nmesh = \"plane\"\ntranslate = [0.0, -1e-6, 0.0]\nscale = 10.0\n{FLOOR}{CUBE}"),
    );
    let Some(run) = support::run_lesson_env(
        L05,
        "hostile_coverage",
        &[
            "--scene", &scene, "--width", "160", "--height", "90", "--frames", "1",
        ],
        &[],
    ) else {
        return;
    };
    for v in run.report["variants"].as_array().unwrap() {
        let pct = v["error"]["coverage_mismatch_pct"]
            .as_f64()
            .expect("error.coverage_mismatch_pct");
        assert!(
            pct > 20.0 && pct <= 100.0,
            "{}: coverage mismatch {pct}",
            v["name"]
        );
    }
    // The plain scene: the key is there, near 0, and no warning.
    let plain = write(
        "coverage_plain.toml",
        &format!("{CAMERA}{SUN}{FLOOR}{CUBE}"),
    );
    let out = headless(L05, &["--scene", &plain]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        assert!(!stderr.contains("different surfaces"), "{stderr}");
        let text = std::fs::read_to_string(dir().join("out/report.json")).unwrap();
        let r: serde_json::Value = serde_json::from_str(&text).unwrap();
        for v in r["variants"].as_array().unwrap() {
            let pct = v["error"]["coverage_mismatch_pct"].as_f64().expect("key");
            assert!(pct < 1.0, "{}: {pct}", v["name"]);
        }
    }
    // The warning: one line, from the run that mismatched.
    let out = headless(L05, &["--scene", &scene]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        let warnings: Vec<&str> = stderr
            .lines()
            .filter(|l| l.contains("different surfaces"))
            .collect();
        assert_eq!(warnings.len(), 1, "{stderr}");
        assert!(warnings[0].starts_with("warning: lesson_05:"), "{stderr}");
    }
}
