//! A user's city of boxes: 20,000 objects in one scene file.
//!
//! Before issue 8 such a scene aborted lavapipe ("LLVM ERROR: Unable to
//! allocate section memory", a shader recompiled per draw) and cost minutes
//! of CPU time in per-object passes over the whole scene. It must render,
//! right, in bounded time.

use common::measure::counters::CASTERS_DRAWN;
use std::time::Duration;

/// Objects in the generated scene: a floor and a grid of boxes.
const BOXES: usize = 19_999;
/// Far beyond the ~25 s the two runs take on 2 CPU cores with lavapipe; a
/// run past it is a hang or a quadratic pass, and fails.
const LIMIT: Duration = Duration::from_secs(240);

/// A floor and a 142 × 141 grid of boxes of varied height, 2 units apart,
/// lit by the sun, seen from above.
fn city_scene() -> String {
    let mut s = String::from(
        "[camera]\neye = [60.0, 80.0, 100.0]\ntarget = [0.0, 0.0, 0.0]\n\
         fov_y_deg = 45.0\nnear = 0.1\nfar = 400.0\n\n\
         [[lights]]\ntype = \"directional\"\ndirection = [-0.5, -1.0, -0.35]\n\n\
         [[objects]]\nmesh = \"plane\"\nscale = [300.0, 1.0, 300.0]\n",
    );
    for k in 0..BOXES {
        let (i, j) = ((k / 141) as f64 - 71.0, (k % 141) as f64 - 70.0);
        // A deterministic spread of heights between 0.2 and 3.
        let h = 0.2 + 2.8 * (((k * 7919) % 1000) as f64 / 1000.0);
        s.push_str(&format!(
            "\n[[objects]]\nmesh = \"cube\"\ntranslate = [{}, {}, {}]\nscale = [1.0, {h}, 1.0]\n",
            i * 2.0,
            h / 2.0,
            j * 2.0
        ));
    }
    s
}

/// Runs `bin` headless on the city with `variant`; the report, or `None`
/// when no adapter exists and none is required.
fn run_city(bin: &str, name: &str, variant: &str) -> Option<serde_json::Value> {
    let out = support::out_dir(&format!("many_objects-{name}"));
    let scene = out.join("city.toml");
    std::fs::write(&scene, city_scene()).expect("write the city scene");
    let mut cmd = support::lesson_command(bin);
    cmd.args(["--headless", "--width", "320", "--height", "180"])
        .args(["--variant", variant, "--frames", "1", "--scene"])
        .arg(&scene)
        .arg("--out")
        .arg(&out);
    let took = support::run_watched(&mut cmd, name, LIMIT, |_| {})?;
    eprintln!("{name}: 20,000 objects in {:.1} s", took.as_secs_f64());
    let text = std::fs::read_to_string(out.join("report.json")).expect("report.json");
    Some(serde_json::from_str(&text).expect("report.json parses"))
}

#[test]
fn lesson_05_renders_twenty_thousand_objects_right() {
    let Some(report) = run_city(env!("CARGO_BIN_EXE_lesson_05"), "lesson_05", "zpass_cpu") else {
        return;
    };
    let v = support::variant(&report, "zpass_cpu");
    let pct = v["error"]["misclassified_pct"]
        .as_f64()
        .expect("misclassified");
    let receivers = v["error"]["receiver_pixels"].as_u64().expect("receivers");
    assert!(receivers > 10_000, "only {receivers} receiver pixels");
    // Stencil volumes are exact up to edge pixels: 0.175 % measured.
    assert!(pct <= 0.5, "lesson_05 zpass_cpu: {pct} % misclassified");
    let casters = support::counter(&report, "zpass_cpu", CASTERS_DRAWN.name);
    assert!(casters > 1000, "only {casters} casters drawn");
}

#[test]
fn lesson_02_renders_twenty_thousand_objects() {
    let Some(report) = run_city(env!("CARGO_BIN_EXE_lesson_02"), "lesson_02", "slope_hw") else {
        return;
    };
    let v = support::variant(&report, "slope_hw");
    let receivers = v["error"]["receiver_pixels"].as_u64().expect("receivers");
    assert!(receivers > 10_000, "only {receivers} receiver pixels");
    let pct = v["error"]["misclassified_pct"]
        .as_f64()
        .expect("misclassified");
    // One 2048² map over a 300-unit city: coarse texels, but biased.
    assert!(pct < 10.0, "lesson_02 slope_hw: {pct} % misclassified");
}
