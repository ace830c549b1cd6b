//! lesson_08 (depth bounds and scissor): the same pixels for less volume
//! work. Snapshot of masks and errors; pixel-for-pixel identity of every
//! variant; the extreme cases (a range sphere crossing the near plane, the
//! camera inside a range sphere).

mod depth_formats;

use std::path::Path;

use common::measure::counters::{
    DRAWS, FRAGMENT_SHADER_INVOCATIONS, LIGHTS_AROUND_CAMERA, LIGHTS_CROSSING_NEAR_PLANE,
    SCISSOR_PIXELS, STENCIL_FRAGMENTS, STENCIL_UPDATES, VOLUME_FRAGMENTS, VOLUME_TRIANGLES,
};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_08");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];
const VARIANTS: [&str; 6] = [
    "unbounded",
    "scissor",
    "depth_bounds",
    "bounds_scissor",
    "cull",
    "cull_bounds_scissor",
];

fn scene(name: &str) -> String {
    format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn counter(report: &serde_json::Value, v: &str, key: &str) -> u64 {
    support::variant(report, v)["counters"][key]
        .as_u64()
        .unwrap_or_else(|| panic!("{v}: counter {key} missing"))
}

/// Pixels that differ between two PNGs (any channel).
fn differing_pixels(a: &Path, b: &Path) -> usize {
    let (a, b) = (
        image::open(a).unwrap().to_rgba8(),
        image::open(b).unwrap().to_rgba8(),
    );
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

/// Every variant's frame and visibility PNGs equal `unbounded`'s, pixel for
/// pixel; every variant within 0.5 % of the reference; and each limit lets
/// fewer volume fragments through to the stencil, and both together make
/// fewer stencil writes (exact counts on every backend: a tally).
fn check_identical_and_cheaper(run: &support::LessonRun) {
    let lights = support::variant(&run.report, "unbounded")["error_per_light"]
        .as_array()
        .unwrap()
        .len();
    for v in &VARIANTS[1..] {
        let mut files = vec![format!("{v}.png")];
        files.extend((0..lights).map(|k| format!("{v}_visibility_l{k}.png")));
        for f in files {
            let base = f.replacen(v, "unbounded", 1);
            let n = differing_pixels(&run.out.join(&base), &run.out.join(&f));
            assert_eq!(n, 0, "{f} differs from {base} in {n} pixels");
        }
    }
    for v in VARIANTS {
        let e = support::variant(&run.report, v)["error"]["misclassified_pct"]
            .as_f64()
            .unwrap();
        assert!(e <= 0.5, "{v}: {e}% misclassified");
    }
    let f = |v| counter(&run.report, v, STENCIL_FRAGMENTS.name);
    assert!(
        f("scissor") < f("unbounded"),
        "scissor saves nothing: {} vs {}",
        f("scissor"),
        f("unbounded")
    );
    assert!(
        f("depth_bounds") < f("unbounded"),
        "depth bounds save nothing: {} vs {}",
        f("depth_bounds"),
        f("unbounded")
    );
    assert!(
        f("bounds_scissor") <= f("scissor").min(f("depth_bounds")),
        "both together must save the most"
    );
    let u = |v| counter(&run.report, v, STENCIL_UPDATES.name);
    assert!(
        u("bounds_scissor") < u("unbounded"),
        "bounds + scissor must write the stencil less: {} vs {}",
        u("bounds_scissor"),
        u("unbounded")
    );
    // The cull leaves out whole casters: never more triangles, and the
    // pixel limits add none.
    let t = |v| counter(&run.report, v, VOLUME_TRIANGLES.name);
    assert!(t("cull") <= t("unbounded"), "the cull adds triangles");
    assert_eq!(t("cull_bounds_scissor"), t("cull"));
    assert!(f("cull_bounds_scissor") <= f("bounds_scissor"));
}

/// The default scene with every variant: the snapshot's run, which the
/// identical-pixels test reads too (one run, not two).
fn default_run() -> Option<&'static support::LessonRun> {
    support::shared_run(BIN, "lesson_08_snapshot", &SIZE)
}

#[test]
fn lesson_08_snapshot() {
    let Some(run) = default_run() else {
        return;
    };
    let mut text = String::from("bounds_scissor visibility, light 3 ('#' shadow, '.' lit, ' ' background;\nout of the light's range the lit pass draws nothing: '#'):\n");
    text += &support::ascii_of(&run.out.join("bounds_scissor_visibility_l3.png"), 64, 18);
    text += "\n\nerror against the reference (percent, 0.01 points):\n";
    for v in run.report["variants"].as_array().unwrap() {
        text += &support::error_line(v, 2);
        text += "\n";
    }
    text += &support::counter_lines(
        &run.report,
        &[
            DRAWS.name,
            VOLUME_TRIANGLES.name,
            SCISSOR_PIXELS.name,
            VOLUME_FRAGMENTS.name,
            STENCIL_FRAGMENTS.name,
            STENCIL_UPDATES.name,
        ],
    );
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(
            "lesson_08",
            support::tolerance::adapter_line(&run.report) + &text
        )
    });
}

/// The default scene (four point lights of range 3.5): identical pixels,
/// and depth bounds + scissor pass at most half the unbounded stencil work.
#[test]
fn lesson_08_bounds_and_scissor_keep_pixels_identical() {
    let Some(run) = default_run() else {
        return;
    };
    check_identical_and_cheaper(run);
    let (all, both) = (
        counter(&run.report, "unbounded", STENCIL_FRAGMENTS.name),
        counter(&run.report, "bounds_scissor", STENCIL_FRAGMENTS.name),
    );
    assert!(
        both * 2 < all,
        "bounds + scissor: {both} of {all} stencil fragments"
    );
    // Each light reaches one or two of the six casters here.
    let t = |v| counter(&run.report, v, VOLUME_TRIANGLES.name);
    assert!(
        t("cull") * 2 < t("unbounded"),
        "cull: {} of {} volume triangles",
        t("cull"),
        t("unbounded")
    );
    // `volume_fragments` is the true rasterised count: with no depth bounds
    // every rasterised fragment reaches the stencil, and the bounds (after
    // rasterisation) do not lower it.
    let raster = |v| counter(&run.report, v, VOLUME_FRAGMENTS.name);
    assert_eq!(
        raster("unbounded"),
        all,
        "rasterised = reaching the stencil"
    );
    assert_eq!(raster("depth_bounds"), all, "bounds act after rasterising");
    assert_eq!(
        raster("scissor"),
        counter(&run.report, "scissor", STENCIL_FRAGMENTS.name)
    );
    // llvmpipe's pipeline statistics count 16 per 4×4 block shaded.
    let adapter = run.report["adapter"]["name"].as_str().unwrap_or("");
    let inv =
        &support::variant(&run.report, "unbounded")["counters"][FRAGMENT_SHADER_INVOCATIONS.name];
    if let (true, Some(inv)) = (adapter.contains("llvmpipe"), inv.as_u64()) {
        assert!(
            inv % 16 == 0 && inv > all,
            "{inv} invocations, {all} fragments"
        );
    }
}

/// A range sphere crossing the near plane (camera outside it): zmin = 0,
/// and the scissor from the near-plane cut still covers every lit pixel.
#[test]
fn lesson_08_light_sphere_crosses_near_plane() {
    let file = scene("lesson_08_near_crossing.toml");
    let Some(run) = support::run_lesson(
        BIN,
        "lesson_08_near_crossing",
        &[&SIZE[..], &["--scene", &file]].concat(),
    ) else {
        return;
    };
    assert_eq!(
        counter(
            &run.report,
            "bounds_scissor",
            LIGHTS_CROSSING_NEAR_PLANE.name
        ),
        1
    );
    assert_eq!(
        counter(&run.report, "bounds_scissor", LIGHTS_AROUND_CAMERA.name),
        0
    );
    let receivers = support::variant(&run.report, "bounds_scissor")["error_per_light"][0]
        ["receiver_pixels"]
        .as_u64()
        .unwrap();
    assert!(
        receivers > 500,
        "the crossing light must light something: {receivers} receivers"
    );
    check_identical_and_cheaper(&run);
}

/// The camera inside a light's range sphere: that light's scissor is the
/// full screen, and the pixels stay the same.
#[test]
fn lesson_08_camera_inside_light_sphere() {
    let file = scene("lesson_08_camera_inside.toml");
    let Some(run) = support::run_lesson(
        BIN,
        "lesson_08_camera_inside",
        &[&SIZE[..], &["--scene", &file]].concat(),
    ) else {
        return;
    };
    assert_eq!(
        counter(&run.report, "bounds_scissor", LIGHTS_AROUND_CAMERA.name),
        1
    );
    let full = 320 * 180;
    assert!(
        counter(&run.report, "scissor", SCISSOR_PIXELS.name) >= full,
        "the light around the camera gets the full screen"
    );
    check_identical_and_cheaper(&run);
}

/// One lesson run on `scene`, or `None` when its adapter lacks
/// DEPTH_CLIP_CONTROL (then it must fail with one line naming it) or no
/// adapter exists and none is required.
fn run_finite(bin: &str, name: &str, file: &str, variants: &[&str]) -> Option<support::LessonRun> {
    let out = support::out_dir(name);
    let mut cmd = support::lesson_command(bin);
    cmd.args(["--headless", "--out"]).arg(&out).args(SIZE);
    cmd.args(["--scene", file]);
    for v in variants {
        cmd.args(["--variant", v]);
    }
    let o = cmd.output().expect("run the lesson binary");
    let stderr = String::from_utf8_lossy(&o.stderr);
    if stderr.contains("no GPU adapter found") && !support::gpu_required() {
        eprintln!("SKIPPED {name}: no GPU adapter");
        return None;
    }
    if !o.status.success() {
        let lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
        assert!(
            lines.len() == 1 && lines[0].contains("DEPTH_CLIP_CONTROL"),
            "{name}: only a missing DEPTH_CLIP_CONTROL may stop a finite far plane:\n{stderr}"
        );
        return None;
    }
    let text = std::fs::read_to_string(out.join("report.json")).expect("report.json");
    Some(support::LessonRun {
        out,
        report: serde_json::from_str(&text).expect("report.json parses"),
        stdout: String::from_utf8_lossy(&o.stdout).to_string(),
        stderr: stderr.to_string(),
    })
}

/// A finite far plane: lesson 08 clamps depth as lesson 07's `clamp` does,
/// and gets lesson 07's error on the same scenes: lesson 07's own scene
/// (far 16, a directional and a point light), the courtyard with far 200,
/// and the courtyard with the far plane through two range spheres. With
/// clipping instead of clamping, lesson 08 misclassifies 12–20 % here.
#[test]
fn lesson_08_finite_far_matches_lesson_07_clamp() {
    let l07 = env!("CARGO_BIN_EXE_lesson_07");
    for name in [
        "lesson_07.toml",
        "lesson_08_far_200.toml",
        "lesson_08_far_crossing.toml",
    ] {
        let file = scene(name);
        let tag = name.trim_end_matches(".toml");
        let r7 = run_finite(l07, &format!("l08_finite_l07_{tag}"), &file, &["clamp"]);
        let r8 = run_finite(BIN, &format!("l08_finite_{tag}"), &file, &VARIANTS);
        let (r7, r8) = match (r7, r8) {
            (Some(r7), Some(r8)) => (r7, r8),
            // No adapter, or no DEPTH_CLIP_CONTROL: then neither may run.
            (None, None) => return,
            (r7, _) => panic!(
                "{name}: lesson 07 clamp ran: {}, lesson 08 ran: {}",
                r7.is_some(),
                r7.is_none()
            ),
        };
        let e7 = support::error(&r7.report, "clamp", "misclassified_pct");
        assert!(e7 <= 0.05, "{name}: lesson 07 clamp {e7}%");
        for v in VARIANTS {
            let e8 = support::error(&r8.report, v, "misclassified_pct");
            assert!(
                e8 <= 0.05 && (e8 - e7).abs() <= 0.01,
                "{name}: lesson 08 {v} {e8}% misclassified, lesson 07 clamp {e7}%"
            );
        }
        if name == "lesson_08_far_crossing.toml" {
            check_identical_and_cheaper(&r8);
        }
    }
}

/// `n` stacked squares under one directional light, far = 50: every pixel
/// of the shadow is inside `n` volumes.
fn nested_scene(n: usize) -> String {
    let mut s = format!(
        "# generated by tests/lesson_08.rs (nested_scene({n})); do not edit\n\
         # {n} nested shadow volumes (stacked squares): lesson 08's count\n\
         # (stencil bits 0-6) wraps at 128, lesson 07's (8 bits) at 256.\n\
         [camera]\neye = [2.0, 3.0, 3.0]\ntarget = [0.0, 0.3, 0.0]\n\
         fov_y_deg = 50.0\nnear = 0.1\nfar = 50.0\n\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0.2, -1.0, 0.1]\n\n\
         [[objects]]\nmesh = \"plane\"\nscale = [6.0, 1.0, 6.0]\ncasts_shadow = false\n"
    );
    for i in 0..n {
        s += &format!(
            "\n[[objects]]\nmesh = \"plane\"\ntranslate = [0.0, {:.3}, 0.0]\nscale = 1.2\ncolor = [0.8, 0.4, 0.3]\n",
            1.0 + 0.004 * i as f64
        );
    }
    s
}

/// The count wraps modulo 128, and the warning says so at 128, not 256:
/// 127 nested volumes render right without a warning; 128 read as 0 (the
/// whole shadow false lit) with the warning, while lesson 07 (8 bits) is
/// right on the same scene. In the adapter's default depth format and in
/// Depth24PlusStencil8.
#[test]
fn lesson_08_count_wraps_at_128_and_warns_there() {
    let committed = std::fs::read_to_string(scene("lesson_08_nested_128.toml")).unwrap();
    assert_eq!(
        committed,
        nested_scene(128),
        "regenerate scenes/lesson_08_nested_128.toml"
    );
    for format in depth_formats::DEPTH_FORMATS {
        if !count_wraps_at_128(format) {
            return;
        }
    }
}

/// The test above in one `--depth-format`; `false` when it was skipped
/// (no adapter, or no depth clamp).
fn count_wraps_at_128(format: &str) -> bool {
    let dir = support::out_dir(&format!("lesson_08_nested_scenes_{format}"));
    let run = |n: usize, bin: &str, variant: &str| {
        let file = dir.join(format!("nested_{n}.toml"));
        std::fs::write(&file, nested_scene(n)).unwrap();
        let out = support::out_dir(&format!("lesson_08_nested_{n}_{variant}_{format}"));
        let o = support::lesson_command(bin)
            .args(["--headless", "--out"])
            .arg(&out)
            .args(SIZE)
            .args(depth_formats::flag(format))
            .args(["--variant", variant, "--scene"])
            .arg(&file)
            .output()
            .expect("run the lesson binary");
        let stderr = String::from_utf8_lossy(&o.stderr).to_string();
        if !o.status.success() {
            // Far = 50 needs depth clamp; without an adapter or the feature, skip.
            let no_gpu = stderr.contains("no GPU adapter found") && !support::gpu_required();
            assert!(
                no_gpu || stderr.contains("DEPTH_CLIP_CONTROL"),
                "nested_{n}: {stderr}"
            );
            return None;
        }
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap())
                .unwrap();
        depth_formats::used(&report, format);
        Some((
            support::error(&report, variant, "misclassified_pct"),
            stderr,
        ))
    };
    let l07 = env!("CARGO_BIN_EXE_lesson_07");
    let Some((e127, w127)) = run(127, BIN, "bounds_scissor") else {
        return false;
    };
    let (e128, w128) = run(128, BIN, "bounds_scissor").expect("nested_128 runs");
    let e7 = run(128, l07, "clamp").map(|(e, _)| e);
    eprintln!("--depth-format {format}: 127 volumes {e127:.3}%, 128 volumes {e128:.3}%, lesson 07 at 128 {e7:?}%");
    assert!(e127 <= 0.5, "{format}: 127 volumes: {e127}% misclassified");
    assert!(!w127.contains("warning"), "no warning below 128: {w127}");
    // The square's shadow is about 4 % of the receivers (320×180).
    assert!(
        e128 >= 2.0,
        "{format}: 128 volumes must wrap to 0 (lit): only {e128}%"
    );
    assert!(
        w128.lines()
            .any(|l| l.starts_with("warning") && l.contains("wrap at 128")),
        "the warning names 128: {w128}"
    );
    if let Some(e7) = e7 {
        assert!(e7 <= 0.5, "{format}: lesson 07 counts to 255: {e7}%");
    }
    true
}
