//! lesson_08 (depth bounds and scissor): the same pixels for less volume
//! work. Snapshot of masks and errors; pixel-for-pixel identity of every
//! variant; the extreme cases (a range sphere crossing the near plane, the
//! camera inside a range sphere).

mod support;

use std::path::Path;

const BIN: &str = env!("CARGO_BIN_EXE_lesson_08");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];
const VARIANTS: [&str; 4] = ["unbounded", "scissor", "depth_bounds", "bounds_scissor"];

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
/// fewer volume fragments through to the stencil.
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
    // GL has no fragment counter (its occlusion queries only say "any").
    if support::variant(&run.report, "unbounded")["counters"]["stencil_fragments"].is_null() {
        assert_eq!(
            run.report["adapter"]["backend"], "Gl",
            "only GL may lack the fragment counter"
        );
        return;
    }
    let f = |v| counter(&run.report, v, "stencil_fragments");
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
}

#[test]
fn lesson_08_snapshot() {
    let Some(run) = support::run_lesson(BIN, "lesson_08_snapshot", &SIZE) else {
        return;
    };
    let mut text = String::from("bounds_scissor visibility, light 3 ('#' shadow, '.' lit, ' ' background;\nout of the light's range the lit pass draws nothing: '#'):\n");
    text += &support::ascii_of(&run.out.join("bounds_scissor_visibility_l3.png"), 64, 18);
    text += "\n\nerror against the reference (rounded to whole percent):\n";
    for v in run.report["variants"].as_array().unwrap() {
        text += &support::error_line(v, 0);
        text += "\n";
    }
    insta::assert_snapshot!("lesson_08", text);
}

/// The default scene (four point lights of range 3.5): identical pixels,
/// and depth bounds + scissor pass at most half the unbounded stencil work.
#[test]
fn lesson_08_bounds_and_scissor_keep_pixels_identical() {
    let Some(run) = support::run_lesson(BIN, "lesson_08_identical", &SIZE) else {
        return;
    };
    check_identical_and_cheaper(&run);
    if run.report["adapter"]["backend"] == "Gl" {
        return;
    }
    let (all, both) = (
        counter(&run.report, "unbounded", "stencil_fragments"),
        counter(&run.report, "bounds_scissor", "stencil_fragments"),
    );
    assert!(
        both * 2 < all,
        "bounds + scissor: {both} of {all} stencil fragments"
    );
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
        counter(&run.report, "bounds_scissor", "lights_crossing_near_plane"),
        1
    );
    assert_eq!(
        counter(&run.report, "bounds_scissor", "lights_around_camera"),
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
        counter(&run.report, "bounds_scissor", "lights_around_camera"),
        1
    );
    let full = 320 * 180;
    assert!(
        counter(&run.report, "scissor", "scissor_pixels") >= full,
        "the light around the camera gets the full screen"
    );
    check_identical_and_cheaper(&run);
}
