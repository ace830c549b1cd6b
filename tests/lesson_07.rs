//! lesson_07 (depth clamp / infinite extrusion): a finite far plane clips
//! z-fail's back cap at infinity; clamping depth or an infinite far plane
//! keeps it. Snapshot of the masks and errors, the showcase, the extreme
//! depth range, and the depth-clip-control feature check.

mod depth_formats;

use common::measure::counters::{
    CASTERS_DRAWN, DRAWS, STENCIL_UPDATES, VOLUME_FRAGMENTS, VOLUME_TRIANGLES,
};
use depth_formats::DEPTH_FORMATS;

const BIN: &str = env!("CARGO_BIN_EXE_lesson_07");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

fn scene(name: &str) -> String {
    format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// The worst light's misclassified % away from edges (the report's
/// `interior_misclassified_pct`: receivers more than 2 px from a change of
/// surface or of lit/shadowed in the reference), for one variant.
fn worst_off_edge(run: &support::LessonRun, v: &str) -> f64 {
    support::variant(&run.report, v)["error_per_light"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["interior_misclassified_pct"].as_f64().unwrap())
        .fold(0.0, f64::max)
}

/// "vulkan" or "gl": the backend the run's adapter used.
fn backend(report: &serde_json::Value) -> String {
    report["adapter"]["backend"]
        .as_str()
        .unwrap_or("unknown")
        .to_lowercase()
}

#[test]
fn lesson_07_snapshot() {
    let args = [
        &SIZE[..],
        &["--variant", "neither", "--variant", "infinite"],
    ]
    .concat();
    let Some(run) = support::run_lesson(BIN, "lesson_07_snapshot", &args) else {
        return;
    };
    let mut text = String::from(
        "reference visibility, point light 1 ('#' shadow, '.' lit, ' ' background):\n",
    );
    text += &support::ascii_of(&run.out.join("reference_visibility_l1.png"), 64, 18);
    text += "\n\nneither (far plane clips the back cap), light 1:\n";
    text += &support::ascii_of(&run.out.join("neither_visibility_l1.png"), 64, 18);
    text += "\n\ninfinite (far plane at infinity, ε), light 1:\n";
    text += &support::ascii_of(&run.out.join("infinite_visibility_l1.png"), 64, 18);
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
            CASTERS_DRAWN.name,
            VOLUME_FRAGMENTS.name,
            STENCIL_UPDATES.name,
        ],
    );
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(
            "lesson_07",
            support::tolerance::adapter_line(&run.report) + &text
        )
    });
}

/// The showcase: volumes cross the finite far plane. Neither clamp nor an
/// infinite far plane → wrong; either one → right (≤ 0.5 %, and nothing
/// wrong more than 2 pixels away from a shadow edge). In the adapter's
/// default depth format and in Depth24PlusStencil8.
#[test]
fn lesson_07_volume_crossing_finite_far_plane() {
    for format in DEPTH_FORMATS {
        let args = [
            &SIZE[..],
            &["--variant", "neither", "--variant", "infinite"],
            &depth_formats::flag(format),
        ]
        .concat();
        let name = format!("lesson_07_far_plane_{format}");
        let Some(run) = support::run_lesson(BIN, &name, &args) else {
            return;
        };
        let (depth, storage) = depth_formats::used(&run.report, format);
        let neither = support::error(&run.report, "neither", "misclassified_pct");
        let inf = support::error(&run.report, "infinite", "misclassified_pct");
        let off = worst_off_edge(&run, "infinite");
        eprintln!(
            "{depth} ({storage}): neither {neither:.3}%, infinite {inf:.3}% (off-edge {off:.3}%)"
        );
        assert!(
            neither > 5.0,
            "{depth}: a clipped back cap must show: neither = {neither}%"
        );
        assert!(
            inf <= 0.5,
            "{depth}: infinite far plane: {inf}% misclassified"
        );
        assert!(
            off <= 0.01,
            "{depth}: infinite: {off}% wrong away from shadow edges"
        );
    }
}

/// A shifted lens (`[camera] shift`, an off-centre frustum): `infinite`
/// applies the shift to its own projection, so it sees what the exact
/// reference sees (the same surfaces, and the volumes counted right).
#[test]
fn lesson_07_infinite_exact_on_a_shifted_camera() {
    let file = scene("lesson_07_shifted.toml");
    let args = [&SIZE[..], &["--scene", &file, "--variant", "infinite"]].concat();
    let Some(run) = support::run_lesson(BIN, "lesson_07_shifted", &args) else {
        return;
    };
    let inf = support::error(&run.report, "infinite", "misclassified_pct");
    let cover = support::error(&run.report, "infinite", "coverage_mismatch_pct");
    let off = worst_off_edge(&run, "infinite");
    eprintln!("shifted: infinite {inf:.3}%, coverage mismatch {cover:.3}%, off-edge {off:.3}%");
    assert!(
        inf <= 0.5,
        "infinite on a shifted camera: {inf}% misclassified"
    );
    assert!(
        cover <= 0.5,
        "infinite sees other surfaces than the reference on {cover}%"
    );
    assert!(off <= 0.01, "infinite: {off}% wrong away from shadow edges");
}

/// A lesson that fits to a centred frustum (lesson 08's scissor reads the
/// projection's diagonal) refuses a shifted scene: one line naming
/// `camera.shift` and lesson 07, exit non-zero, before any GPU work.
#[test]
fn a_shifted_camera_is_refused_where_the_frustum_is_fitted_centred() {
    let o = support::lesson_command(env!("CARGO_BIN_EXE_lesson_08"))
        .args(["--headless", "--out"])
        .arg(support::out_dir("lesson_08_shifted_refused"))
        .args(["--scene", &scene("lesson_07_shifted.toml")])
        .output()
        .expect("run lesson_08");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success(),
        "lesson_08 drew a shifted camera: {stderr}"
    );
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "one line: {stderr}");
    assert!(
        lines[0].contains("camera.shift") && lines[0].contains("lesson_07"),
        "the line names the field and the lesson that draws it: {stderr}"
    );
}

/// `clamp` needs DEPTH_CLIP_CONTROL: it either renders right, or fails with
/// one line naming the feature (never something else).
#[test]
fn lesson_07_clamp_renders_right_or_names_the_missing_feature() {
    let out = support::out_dir("lesson_07_clamp");
    let o = support::lesson_command(BIN)
        .args(["--headless", "--out"])
        .arg(&out)
        .args(SIZE)
        .args(["--variant", "clamp"])
        .output()
        .expect("run lesson_07");
    let stderr = String::from_utf8_lossy(&o.stderr);
    if stderr.contains("no GPU adapter found") && !support::gpu_required() {
        eprintln!("SKIPPED lesson_07_clamp: no GPU adapter");
        return;
    }
    if o.status.success() {
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap())
                .unwrap();
        let e = support::error(&report, "clamp", "misclassified_pct");
        assert!(e <= 0.5, "clamp: {e}% misclassified");
    } else {
        let lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
        assert_eq!(lines.len(), 1, "one error line: {stderr}");
        assert!(
            lines[0].contains("DEPTH_CLIP_CONTROL"),
            "the line names the feature: {stderr}"
        );
    }
}

/// near = 1e-3, far = 1e5 (far/near = 1e8): the volumes still count right,
/// and the depth-precision study shows why reversed float depth is the cure
/// for the depth buffer itself (GPU-measured, `depth_precision.csv`). In the
/// adapter's default depth format and in Depth24PlusStencil8.
#[test]
fn lesson_07_extreme_near_1e_3_far_1e5() {
    for format in DEPTH_FORMATS {
        extreme_range(format);
    }
}

fn extreme_range(format: &str) {
    let file = scene("lesson_07_near_1e-3_far_1e5.toml");
    let args = [
        &SIZE[..],
        &["--scene", &file, "--variant", "infinite"],
        &depth_formats::flag(format),
    ]
    .concat();
    let name = format!("lesson_07_extreme_range_{format}");
    let Some(run) = support::run_lesson(BIN, &name, &args) else {
        return;
    };
    let (depth, storage) = depth_formats::used(&run.report, format);
    let inf = support::error(&run.report, "infinite", "misclassified_pct");
    let off = worst_off_edge(&run, "infinite");
    eprintln!("far/near 1e8, {depth} ({storage}): infinite {inf:.3}% (off-edge {off:.3}%)");
    assert!(
        inf <= 0.5,
        "{depth}: infinite at far/near 1e8: {inf}% misclassified"
    );
    assert!(
        off <= 0.05,
        "{depth}: infinite at far/near 1e8: {off}% wrong away from shadow edges"
    );
    // At d = far/2 = 5e4: standard depth resolves no gap below Δd = d; reversed
    // Depth32Float resolves Δd/d ≤ 1e-6 (where the adapter has the format).
    let csv = std::fs::read_to_string(run.out.join("depth_precision.csv")).unwrap();
    // Columns: 5 = GPU-measured, 6 = CPU model, 7 = analytic, 8 = the storage
    // the model assumes. "none": no gap up to Δd = d.
    let at_half_far = |format: &str, mapping: &str, col: usize| {
        let line = csv
            .lines()
            .rfind(|l| l.starts_with(&format!("{format},{mapping},1e-3,1e5,")))
            .unwrap();
        let cell = line.split(',').nth(col).unwrap();
        (cell != "n/a").then(|| cell.parse::<f64>().unwrap_or(f64::INFINITY))
    };
    assert_eq!(
        at_half_far("Depth24PlusStencil8", "standard", 5),
        Some(f64::INFINITY)
    );
    let model = at_half_far("Depth32FloatStencil8", "reversed", 6).unwrap();
    assert!(
        model <= 1e-6,
        "CPU model: reversed Depth32Float at far/2 resolves Δd/d = {model}"
    );
    // The study models each format as what the adapter stores: with the
    // scene in Depth24PlusStencil8, the report's probe is that format's.
    let d24_storage: Vec<&str> = csv
        .lines()
        .filter(|l| l.starts_with("Depth24PlusStencil8,"))
        .map(|l| l.split(',').nth(8).unwrap())
        .collect();
    assert!(!d24_storage.is_empty());
    if depth == "Depth24PlusStencil8" && storage != "unknown" {
        assert!(
            d24_storage.iter().all(|s| *s == storage),
            "the study's Depth24PlusStencil8 rows model {d24_storage:?}, the probe found {storage}"
        );
    }
    // Every GPU cell (95 % of 32 jittered samples) lies within [½, 10]× the
    // analytic curve, one storage step: no cell resolved by rounding luck.
    let gl = run.report["adapter"]["backend"] == "Gl";
    let mut checked = 0;
    for line in csv.lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let a: f64 = c[7].parse().unwrap();
        // On GL, reversed float depth loses its precision (see below).
        let reversed_f32 = c[0] == "Depth32FloatStencil8" && c[1].contains("reversed");
        if a > 0.1 || c[5] == "n/a" || (gl && reversed_f32) {
            continue;
        }
        let g = c[5].parse::<f64>().unwrap_or(f64::INFINITY);
        assert!(
            g >= a / 2.0 && g <= a * 10.0,
            "GPU {g} vs analytic {a}: {line}"
        );
        checked += 1;
    }
    assert!(checked > 300, "only {checked} rows checked");
    // wgpu's GL backend rewrites clip z to 2z − w (GL's [−1, 1]), which
    // throws away the small depths reversed-Z lives on: measured on Vulkan only.
    if run.report["adapter"]["backend"] != "Gl" {
        if let Some(g) = at_half_far("Depth32FloatStencil8", "reversed", 5) {
            assert!(
                g <= 1e-6,
                "GPU: reversed Depth32Float at far/2 resolves Δd/d = {g}"
            );
        }
    }
}

/// Runs `variant` alone; on GL expects reversed-Z's one-line refusal.
/// Returns the run where it rendered.
fn run_or_refused(name: &str, args: &[&str]) -> Option<support::LessonRun> {
    let out = support::out_dir(name);
    let o = support::lesson_command(BIN)
        .args(["--headless", "--out"])
        .arg(&out)
        .args(args)
        .output()
        .expect("run lesson_07");
    let stderr = String::from_utf8_lossy(&o.stderr);
    if stderr.contains("no GPU adapter found") && !support::gpu_required() {
        eprintln!("SKIPPED {name}: no GPU adapter");
        return None;
    }
    if !o.status.success() {
        let lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
        assert_eq!(lines.len(), 1, "one error line: {stderr}");
        assert!(
            lines[0].contains("reversed_z") && lines[0].contains("--backend vulkan"),
            "the line names the variant and the backend that handles it: {stderr}"
        );
        return None;
    }
    let report =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    Some(support::LessonRun {
        report,
        out,
        stdout,
        stderr: stderr.to_string(),
    })
}

/// The deep-range scene, read from its file: the near plane, the nearest
/// caster vertex's distance from the eye, and the smallest height of a
/// caster above the floor (the receivers that cast no shadow).
fn near_casters_distance_and_gap(file: &str) -> (f64, f64, f64) {
    let s = common::scene::Scene::load(std::path::Path::new(file)).unwrap();
    let vertices = |casts: bool| {
        let objects = s.objects.iter().filter(move |o| o.casts_shadow == casts);
        objects.flat_map(|o| {
            let p = o.mesh.positions.iter();
            p.map(|&p| o.model.transform_point3(p.as_dvec3()))
        })
    };
    let eye = s.camera.eye;
    let nearest = vertices(true)
        .map(|p| p.distance(eye))
        .fold(f64::MAX, f64::min);
    let floor = vertices(false).map(|p| p.y).fold(f64::MIN, f64::max);
    let lowest = vertices(true).map(|p| p.y).fold(f64::MAX, f64::min);
    (s.camera.near, nearest, lowest - floor)
}

/// Standard depth's coverage mismatch on the deep range must exceed this
/// (%). Measured at 320×180: lavapipe clamp 2.18, infinite 2.75; llvmpipe
/// (GL) 4.28, 3.50, the same in Depth32FloatStencil8 and (true 24-bit)
/// Depth24PlusStencil8; NVIDIA H100 (Vulkan) 0.354 (clamp). Reversed-Z
/// stays ≤ 0.05 (0.000 on lavapipe), so 0.1 parts the two; the test also
/// asks for 3× reversed-Z's own figure.
const DEEP_ZFIGHT_COVERAGE_PCT: f64 = 0.1;

/// Issue 8, item 5: near = 1e-3, far = 1e5, the casters ~400 units away and
/// 1 cm above the floor. Reversed-Z in Depth32Float (far plane at infinity)
/// is exact away from shadow edges (≤ 0.05 %); `clamp` and `infinite`
/// (standard depth, whose steps near 1 are 2⁻²⁴ in either format) are not,
/// in the adapter's default depth format and in Depth24PlusStencil8
/// (`--depth-format` sets the scene's depth; reversed-Z keeps its own
/// Depth32FloatStencil8). On GL, which refuses reversed-Z, standard
/// depth's failure is checked alone.
#[test]
fn lesson_07_reversed_z_exact_on_deep_range() {
    let file = scene("lesson_07_deep_range.toml");
    let (near, nearest, gap) = near_casters_distance_and_gap(&file);
    for format in DEPTH_FORMATS {
        let flag = depth_formats::flag(format);
        let rz = [
            &SIZE[..],
            &["--scene", &file, "--variant", "reversed_z"],
            &flag,
        ]
        .concat();
        let rz_run = run_or_refused(&format!("lesson_07_deep_reversed_{format}"), &rz);
        let std_args = [
            &SIZE[..],
            &[
                "--scene",
                &file,
                "--variant",
                "clamp",
                "--variant",
                "infinite",
            ],
            &flag,
        ]
        .concat();
        let name = format!("lesson_07_deep_standard_{format}");
        let Some(std_run) = support::run_lesson(BIN, &name, &std_args) else {
            return;
        };
        let (depth, storage) = depth_formats::used(&std_run.report, format);
        // The precondition, from what the buffer stores: standard depth puts
        // the casters at z = 1 − n/d, where one step spans Δd = step·d²/n.
        let resolvable = depth_formats::step_near_one(&storage) * nearest * nearest / near;
        eprintln!(
            "{} {depth} ({storage}): casters from {nearest:.1} units, {:.3} above the floor; standard depth resolves Δd ≥ {resolvable:.2} there",
            backend(&std_run.report),
            gap
        );
        assert!(
            gap > 0.0 && resolvable > 100.0 * gap,
            "{depth} ({storage}): standard depth should not resolve the {gap}-unit gap (Δd = {resolvable})"
        );
        let cov = |r: &serde_json::Value, v| support::error(r, v, "coverage_mismatch_pct");
        // Reversed-Z sees what the reference sees (where it runs).
        let (rz_cov, rz_off) = match &rz_run {
            Some(run) => {
                let rz_all = support::error(&run.report, "reversed_z", "misclassified_pct");
                let (c, off) = (
                    cov(&run.report, "reversed_z"),
                    worst_off_edge(run, "reversed_z"),
                );
                eprintln!("  reversed_z: coverage mismatch {c:.3}%, off-edge {off:.3}% (all {rz_all:.3}%)");
                assert!(rz_all <= 0.5, "reversed_z: {rz_all}% misclassified");
                assert!(c <= 0.05, "reversed_z: {c}% of pixels see another surface");
                assert!(off <= 0.05, "reversed_z: {off}% wrong away from edges");
                (c, off)
            }
            None => (0.0, 0.0),
        };
        // Standard depth cannot keep the casters in front of the floor (the
        // base pass z-fights) nor count their volumes right near it.
        for v in ["clamp", "infinite"] {
            let (c, off) = (cov(&std_run.report, v), worst_off_edge(&std_run, v));
            eprintln!("  {v}: coverage mismatch {c:.3}%, off-edge {off:.3}%");
            assert!(
                c > DEEP_ZFIGHT_COVERAGE_PCT && c > 3.0 * rz_cov,
                "{v} in {depth}: standard depth should z-fight here, {c}% coverage mismatch (reversed_z {rz_cov}%)"
            );
            assert!(
                off > 0.05 && off > 5.0 * rz_off,
                "{v} in {depth} should fail on the deep range (standard depth): {off}% off-edge vs reversed_z {rz_off}%"
            );
        }
    }
}

/// A default run (no `--variant`) renders what the adapter can: on GL it
/// skips `reversed_z` with one note line naming the backend that handles
/// it and exits 0; elsewhere the report has every variant.
#[test]
fn lesson_07_default_run_skips_only_what_the_adapter_cannot_render() {
    let out = support::out_dir("lesson_07_default_run");
    let o = support::lesson_command(BIN)
        .args(["--headless", "--width", "160", "--height", "90", "--out"])
        .arg(&out)
        .output()
        .expect("run lesson_07");
    let stderr = String::from_utf8_lossy(&o.stderr);
    if stderr.contains("no GPU adapter found") && !support::gpu_required() {
        eprintln!("SKIPPED: no GPU adapter");
        return;
    }
    assert!(o.status.success(), "default run failed:\n{stderr}");
    let text = std::fs::read_to_string(out.join("report.json")).unwrap();
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    let names: Vec<&str> = report["variants"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["name"].as_str().unwrap())
        .collect();
    let notes: Vec<&str> = stderr.lines().filter(|l| l.starts_with("note:")).collect();
    if report["adapter"]["backend"].as_str() == Some("Gl") {
        assert_eq!(names, ["neither", "clamp", "infinite"]);
        assert_eq!(notes.len(), 1, "one note line: {stderr}");
        assert!(notes[0].contains("reversed_z") && notes[0].contains("--backend vulkan"));
    } else {
        assert_eq!(names, ["neither", "clamp", "infinite", "reversed_z"]);
        assert!(notes.is_empty(), "no variant skipped: {stderr}");
    }
}
