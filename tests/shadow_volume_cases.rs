//! Extreme cases for stencil shadow volumes (lessons 05-06; the scenes in
//! `scenes/volume_*.toml` are shared with lessons 07 and 08). Each test
//! runs lesson_06 on one scene and asserts a number from report.json.
//!
//! Pass criterion for "correct": misclassified ≤ 0.5 % of receiver pixels,
//! and almost no error away from shadow edges (an error pixel whose 3 × 3
//! neighbourhood is all lit or all shadowed in the reference).
//!
//! Not here: a volume crossing a finite far plane. That is lesson 07's
//! subject (its tests own it); lessons 05-06 use `far = "infinite"`.

mod depth_formats;

use std::path::{Path, PathBuf};

use common::measure::counters::{CASTERS_ZFAIL, MAX_VOLUME_OVERLAP, NONMANIFOLD_EDGES, OPEN_EDGES};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_06");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

fn run(test: &str, scene_path: &Path, variants: &[&str]) -> Option<support::LessonRun> {
    let s = scene_path.to_str().expect("utf-8 path");
    let mut args: Vec<&str> = SIZE.to_vec();
    args.extend(["--scene", s]);
    for v in variants {
        args.extend(["--variant", v]);
    }
    support::run_lesson(BIN, test, &args)
}

/// [`run`] with the scene's depth in `format` (`--depth-format`); the
/// report's format and storage are checked and returned.
fn run_in(
    format: &str,
    test: &str,
    scene_path: &Path,
    variants: &[&str],
) -> Option<(support::LessonRun, String)> {
    let s = scene_path.to_str().expect("utf-8 path");
    let mut args: Vec<&str> = SIZE.to_vec();
    args.extend(["--scene", s]);
    for v in variants {
        args.extend(["--variant", v]);
    }
    args.extend(depth_formats::flag(format));
    let run = support::run_lesson(BIN, &format!("{test}_{format}"), &args)?;
    let (depth, storage) = depth_formats::used(&run.report, format);
    Some((run, format!("{depth} ({storage})")))
}

fn counter(run: &support::LessonRun, variant: &str, key: &str) -> Option<u64> {
    support::variant(&run.report, variant)["counters"][key].as_u64()
}

/// Error pixels (red or green in the diff) whose 3 × 3 neighbourhood in the
/// reference is uniform: errors that are not at a shadow edge, in % of
/// receiver pixels, summed over lights.
fn interior_error_pct(run: &support::LessonRun, variant: &str) -> f64 {
    let lights = support::variant(&run.report, variant)["error_per_light"]
        .as_array()
        .map_or(1, |a| a.len());
    let receivers = support::variant(&run.report, variant)["error"]["receiver_pixels"]
        .as_u64()
        .unwrap_or(1)
        .max(1);
    let mut bad = 0u64;
    for k in 0..lights {
        let diff = image::open(run.out.join(format!("{variant}_diff_l{k}.png")))
            .expect("diff png")
            .to_rgba8();
        let (_, reference, w, h) =
            support::read_visibility(&run.out.join(format!("reference_visibility_l{k}.png")));
        let at = |x: u32, y: u32| reference[(y * w + x) as usize] >= 0.5;
        for y in 1..h - 1 {
            for x in 1..w - 1 {
                let p = diff.get_pixel(x, y).0;
                let error = p == [255, 0, 0, 255] || p == [0, 255, 0, 255];
                let uniform = (0..9).all(|i| at(x + i % 3 - 1, y + i / 3 - 1) == at(x, y));
                bad += (error && uniform) as u64;
            }
        }
    }
    100.0 * bad as f64 / receivers as f64
}

/// The pass criterion of a correct variant.
fn assert_exact(run: &support::LessonRun, variant: &str) {
    let m = support::misclassified(run, variant);
    assert!(m <= 0.5, "{variant}: misclassified {m:.3}% > 0.5%");
    let interior = interior_error_pct(run, variant);
    assert!(
        interior <= 0.02,
        "{variant}: {interior:.3}% of receivers wrong away from shadow edges"
    );
}

/// Z-pass fails with the eye in shadow, z-fail is exact: in the adapter's
/// default depth format and in Depth24PlusStencil8.
#[test]
fn eye_inside_the_umbra() {
    for format in depth_formats::DEPTH_FORMATS {
        let Some((r, depth)) = run_in(
            format,
            "case_eye_in_umbra",
            &scene("volume_eye_in_umbra.toml"),
            &["zpass_quads", "zfail_quads", "zfail_cpu"],
        ) else {
            return;
        };
        let zpass = support::misclassified(&r, "zpass_quads");
        eprintln!("eye in umbra, {depth}: zpass_quads {zpass:.3}%");
        assert!(
            zpass > 10.0,
            "{depth}: z-pass must fail with the eye in shadow, got {zpass:.2}%"
        );
        assert_exact(&r, "zfail_quads");
        assert_exact(&r, "zfail_cpu");
    }
}

/// Z-pass fails where the near plane cuts a volume; z-fail (everywhere or
/// selectively) is exact: in both depth formats.
#[test]
fn near_plane_slices_a_volume() {
    for format in depth_formats::DEPTH_FORMATS {
        let Some((r, depth)) = run_in(
            format,
            "case_near_slice",
            &scene("volume_near_slice.toml"),
            &["zpass_quads", "zfail_quads", "zfail_selective"],
        ) else {
            return;
        };
        let zpass = support::misclassified(&r, "zpass_quads");
        eprintln!("near plane in a volume, {depth}: zpass_quads {zpass:.3}%");
        assert!(
            zpass > 5.0,
            "{depth}: z-pass must fail where the near plane is in shadow, got {zpass:.2}%"
        );
        assert_exact(&r, "zfail_quads");
        assert_exact(&r, "zfail_selective");
        assert!(
            counter(&r, "zfail_selective", CASTERS_ZFAIL.name) >= Some(1),
            "the slab needs z-fail"
        );
    }
}

#[test]
fn open_caster_single_quad() {
    let Some(r) = run(
        "case_open_quad",
        &scene("volume_open_quad.toml"),
        &["zpass_quads", "zfail_quads", "zfail_cpu"],
    ) else {
        return;
    };
    assert_eq!(
        counter(&r, "zfail_quads", OPEN_EDGES.name),
        Some(8),
        "floor and quad: 4 open edges each"
    );
    for v in ["zpass_quads", "zfail_quads", "zfail_cpu"] {
        assert_exact(&r, v);
    }
}

#[test]
fn nonmanifold_edge_shared_by_four_faces() {
    let Some(r) = run(
        "case_nonmanifold",
        &scene("volume_nonmanifold.toml"),
        &["zfail_quads", "zfail_cpu"],
    ) else {
        return;
    };
    assert_eq!(
        counter(&r, "zfail_quads", NONMANIFOLD_EDGES.name),
        Some(1),
        "the spine"
    );
    assert_exact(&r, "zfail_quads");
    assert_exact(&r, "zfail_cpu");
}

#[test]
fn degenerate_and_edge_on_triangles() {
    let Some(r) = run(
        "case_degenerate",
        &scene("volume_degenerate.toml"),
        &["zfail_quads", "zfail_cpu"],
    ) else {
        return;
    };
    assert_exact(&r, "zfail_quads");
    assert_exact(&r, "zfail_cpu");
}

#[test]
fn mirrored_models() {
    let Some(r) = run(
        "case_mirrored",
        &scene("volume_mirrored.toml"),
        &["zfail_quads", "zfail_cpu", "zpass_quads"],
    ) else {
        return;
    };
    for v in ["zfail_quads", "zfail_cpu", "zpass_quads"] {
        assert_exact(&r, v);
    }
}

// ---- a mesh with UV seams, generated here ------------------------------

/// A UV sphere as a UV-mapped mesh is stored: `segments + 1` columns (the
/// u = 0 and u = 1 columns share positions) and one pole vertex per column.
fn seam_sphere_obj(segments: u32, stacks: u32) -> String {
    use std::f64::consts::{PI, TAU};
    let mut s = String::from(
        "# generated by tests/shadow_volume_cases.rs (seam_sphere_obj); do not edit\n",
    );
    s += "# a radius-0.5 UV sphere with duplicated seam and pole vertices\no seam_sphere\n";
    let cols = segments + 1;
    for k in 0..=stacks {
        for j in 0..cols {
            let (theta, phi) = (
                PI * k as f64 / stacks as f64,
                TAU * (j % segments) as f64 / segments as f64,
            );
            let mut n = [
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ];
            if k == 0 || k == stacks {
                // The poles exactly: sin(π) is not 0 in floating point.
                n = [0.0, if k == 0 { 1.0 } else { -1.0 }, 0.0];
            }
            let f = |x: f64| x as f32;
            s += &format!("v {} {} {}\n", f(0.5 * n[0]), f(0.5 * n[1]), f(0.5 * n[2]));
            s += &format!(
                "vt {} {}\n",
                f(j as f64 / segments as f64),
                f(k as f64 / stacks as f64)
            );
            s += &format!("vn {} {} {}\n", f(n[0]), f(n[1]), f(n[2]));
        }
    }
    let id = |k: u32, j: u32| k * cols + j + 1;
    let mut face =
        |a: u32, b: u32, c: u32| s += &format!("f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}\n");
    for k in 0..stacks {
        for j in 0..segments {
            let (a, b, c, d) = (id(k, j), id(k, j + 1), id(k + 1, j + 1), id(k + 1, j));
            if k > 0 {
                face(a, b, c);
            }
            if k + 1 < stacks {
                face(a, c, d);
            }
        }
    }
    s
}

/// `count` thin squares stacked over a floor under a light straight down:
/// the floor's centre is inside `count` volumes.
fn nested_scene(count: u32) -> String {
    let mut s = format!(
        "# generated by tests/shadow_volume_cases.rs (nested_scene); do not edit\n\
         # Extreme case: {count} nested shadow volumes (stacked squares).\n\
         [camera]\neye = [2.0, 3.0, 3.0]\ntarget = [0.0, 0.3, 0.0]\nfov_y_deg = 50.0\nnear = 0.1\nfar = \"infinite\"\n\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0.2, -1.0, 0.1]\n\n\
         [[objects]]\nmesh = \"plane\"\nscale = [6.0, 1.0, 6.0]\ncasts_shadow = false\n"
    );
    for i in 0..count {
        s += &format!("\n[[objects]]\nmesh = \"plane\"\ntranslate = [0.0, {:.3}, 0.0]\nscale = 1.2\ncolor = [0.8, 0.4, 0.3]\n", 1.0 + 0.004 * i as f64);
    }
    s
}

/// A generated file must match its generator (WORKBOOK_BLESS=1 rewrites it).
fn check_generated(path: &Path, text: &str) {
    if std::env::var("WORKBOOK_BLESS").is_ok_and(|v| v == "1") {
        std::fs::write(path, text).expect("write generated file");
    }
    let on_disk = std::fs::read_to_string(path).unwrap_or_default();
    assert!(
        on_disk == text,
        "{} is out of date: regenerate with WORKBOOK_BLESS=1",
        path.display()
    );
}

#[test]
fn uv_seams_weld_closed() {
    let obj = scene("seam_sphere.obj");
    check_generated(&obj, &seam_sphere_obj(32, 16));
    let mesh = common::scene::obj::load_obj(&obj).expect("seam sphere loads");
    let report = workbook::lesson_05::adjacency::validate(&mesh);
    assert!(
        report.closed && report.boundary_edges == 0,
        "welded by position the sphere is closed: {report:?}"
    );
    assert!(
        mesh.positions.len() > 32 * 15 + 2,
        "the OBJ really has duplicated seam vertices: {}",
        mesh.positions.len()
    );
    let Some(r) = run(
        "case_uv_seam",
        &scene("volume_uv_seam.toml"),
        &["zfail_quads", "zfail_cpu"],
    ) else {
        return;
    };
    assert_eq!(counter(&r, "zfail_quads", OPEN_EDGES.name), Some(0));
    assert_exact(&r, "zfail_quads");
    assert_exact(&r, "zfail_cpu");
}

/// 256 nested volumes wrap the 8-bit count to 0, 255 do not: in the
/// adapter's default depth format and in Depth24PlusStencil8.
#[test]
fn nested_256_volumes_wrap_the_stencil() {
    let path = scene("volume_nested_256.toml");
    check_generated(&path, &nested_scene(256));
    let dir = support::out_dir("case_nested_255_scene");
    let p255 = dir.join("volume_nested_255.toml");
    std::fs::write(&p255, nested_scene(255)).expect("write scene");
    for format in depth_formats::DEPTH_FORMATS {
        let Some((r, depth)) = run_in(format, "case_nested_256", &path, &["zfail_quads"]) else {
            return;
        };
        assert_eq!(
            counter(&r, "zfail_quads", MAX_VOLUME_OVERLAP.name),
            Some(256),
            "the CPU count finds 256 layers"
        );
        let m = support::misclassified(&r, "zfail_quads");
        eprintln!("256 nested volumes, {depth}: zfail_quads {m:.3}%");
        assert!(
            m > 1.0,
            "{depth}: 256 ≡ 0 (mod 256): the floor under the stack reads as lit, measured {m:.2}%"
        );
        // One fewer does not wrap.
        let Some((r, _)) = run_in(format, "case_nested_255", &p255, &["zfail_quads"]) else {
            return;
        };
        assert_eq!(
            counter(&r, "zfail_quads", MAX_VOLUME_OVERLAP.name),
            Some(255)
        );
        assert_exact(&r, "zfail_quads");
    }
}
