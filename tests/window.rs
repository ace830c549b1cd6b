//! The window as a workbench, run for real on a private Xvfb
//! (`common::run::display`): every lesson's window captures its own
//! picture with the overlay and the diff view, and the error figure it
//! shows is the headless report's; the figure follows a moving camera
//! without slowing the window.
//!
//! Each run writes `--window-log` (one JSON line per frame: its time, cost,
//! and the error figure shown with the view it was computed for).

mod support;

use std::path::Path;
use std::time::Duration;

use common::run::display::Display;
use serde_json::Value;

/// A window run's log, and its capture if it made one.
struct WindowRun {
    log: Vec<Value>,
    capture: Option<image::RgbaImage>,
}

/// Runs `bin` in a window on a private display with `args`, logging each frame.
fn run_window(bin: &str, name: &str, args: &[&str], capture: bool) -> Option<WindowRun> {
    let display = Display::open().expect("a display for the window");
    let out = support::out_dir(name);
    let log = out.join("window.jsonl");
    let shot = out.join("capture.png");
    let mut cmd = support::lesson_command(bin);
    display.apply(&mut cmd);
    cmd.args(args).arg("--window-log").arg(&log);
    cmd.arg("--out").arg(&out);
    if capture {
        cmd.arg("--capture").arg(&shot);
    }
    support::run_watched(&mut cmd, name, Duration::from_secs(300), |_| {})?;
    let text = std::fs::read_to_string(&log).expect("the window log");
    let log = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("a log line parses"))
        .collect();
    let capture = capture.then(|| image::open(&shot).expect("the capture").to_rgba8());
    Some(WindowRun { log, capture })
}

const W: u32 = 640;
const H: u32 = 360;
/// The overlay's panel, in pixels from the top left: it covers at least
/// this box at 1 pixel per point (Xvfb), whatever the lesson.
const PANEL: (u32, u32, u32, u32) = (12, 40, 300, 150);

/// The lesson's first variant in a window at `W × H` on the diff view,
/// captured once the full figure came; and the same variant headless.
fn check_lesson(bin: &str, lesson: &str) {
    let (w, h) = (W.to_string(), H.to_string());
    let size = ["--width", w.as_str(), "--height", h.as_str()];
    let mut args = size.to_vec();
    args.extend(["--view", "diff", "--capture-after", "3"]);
    let Some(win) = run_window(bin, &format!("{lesson}_window"), &args, true) else {
        return;
    };
    let last = win.log.last().expect("the window drew frames");
    let variant = last["variant"].as_str().expect("variant").to_string();
    assert_eq!(
        last["error_current"], true,
        "{lesson}: the capture came before the figure of its view: {last}"
    );
    assert_eq!(last["error"]["level"], "full", "{lesson}: {last}");

    // The same variant headless, at the same size: the same figure.
    let mut hargs = size.to_vec();
    hargs.extend(["--frames", "1", "--variant", variant.as_str()]);
    let Some(run) = support::run_lesson(bin, &format!("{lesson}_window_headless"), &hargs) else {
        return;
    };
    let report = &run.report["variants"][0]["error"];
    for key in ["misclassified_pct", "false_shadow_pct", "false_lit_pct"] {
        let (window, headless) = (
            last["error"][key].as_f64().expect("window figure"),
            report[key].as_f64().expect("report figure"),
        );
        assert!(
            (window - headless).abs() < 0.01,
            "{lesson} {variant}: the window shows {key} {window:.4} %, the headless report {headless:.4} %"
        );
    }

    // The capture: the diff view outside the overlay, the overlay over it.
    let shot = win.capture.expect("a capture");
    assert_eq!(shot.dimensions(), (W, H), "{lesson}: the capture's size");
    let diff = image::open(run.out.join(format!("{variant}_diff_l0.png")))
        .expect("the headless diff")
        .to_rgba8();
    let close = |a: &image::Rgba<u8>, b: &image::Rgba<u8>| {
        (0..3).all(|c| (a.0[c] as i32 - b.0[c] as i32).abs() <= 3)
    };
    let in_panel = |x: u32, y: u32| x < 420 && y < 300;
    let (mut outside, mut outside_same) = (0u64, 0u64);
    let (mut panel, mut panel_same, mut panel_dark) = (0u64, 0u64, 0u64);
    let (px, py, pw, ph) = PANEL;
    for (x, y, p) in shot.enumerate_pixels() {
        // The diff image's transparent pixels (nothing covered) show the background.
        let d = diff.get_pixel(x, y);
        let same = d.0[3] == 0 || close(p, d);
        if !in_panel(x, y) {
            outside += 1;
            outside_same += u64::from(same);
        } else if (px..px + pw).contains(&x) && (py..py + ph).contains(&y) {
            panel += 1;
            panel_same += u64::from(same && d.0[3] != 0);
            panel_dark += u64::from(p.0[..3].iter().all(|&c| c < 90));
        }
    }
    let outside_pct = 100.0 * outside_same as f64 / outside as f64;
    assert!(
        outside_pct > 99.0,
        "{lesson}: outside the overlay, only {outside_pct:.2} % of the capture is the headless diff image"
    );
    let dark_pct = 100.0 * panel_dark as f64 / panel as f64;
    let same_pct = 100.0 * panel_same as f64 / panel as f64;
    assert!(
        dark_pct > 50.0 && same_pct < 50.0,
        "{lesson}: no overlay panel at the top left ({dark_pct:.1} % dark, {same_pct:.1} % the diff image)"
    );
}

macro_rules! window_test {
    ($test:ident, $bin:literal) => {
        #[test]
        fn $test() {
            check_lesson(env!(concat!("CARGO_BIN_EXE_", $bin)), $bin);
        }
    };
}

window_test!(lesson_01_window_capture, "lesson_01");
window_test!(lesson_02_window_capture, "lesson_02");
window_test!(lesson_03_window_capture, "lesson_03");
window_test!(lesson_04_window_capture, "lesson_04");
window_test!(lesson_05_window_capture, "lesson_05");
window_test!(lesson_06_window_capture, "lesson_06");
window_test!(lesson_07_window_capture, "lesson_07");
window_test!(lesson_08_window_capture, "lesson_08");
window_test!(lesson_09_window_capture, "lesson_09");

/// Seconds of camera motion, and of the run, in the camera test.
const MOVING_S: f64 = 4.0;
const RUN_S: f64 = 14.0;
/// The longest a figure may take, from its view to the overlay, while the
/// camera moves (measured on lavapipe at 1280×720 on 2 cores: 1.3 s at most).
const MAX_MOVING_LATENCY_S: f64 = 3.0;
/// The longest from the camera's stop to the full figure of its last view
/// (measured: about 1 s).
const MAX_SETTLE_S: f64 = 8.0;

/// Frames per second over `[from, to)` seconds of a log.
fn fps(log: &[Value], from: f64, to: f64) -> f64 {
    let t: Vec<f64> = log
        .iter()
        .map(|l| l["t_s"].as_f64().expect("t_s"))
        .filter(|t| (from..to).contains(t))
        .collect();
    (t.len() as f64 - 1.0) / (t.last().expect("frames") - t[0])
}

/// Moving the camera (a steady `--orbit`, as a drag) at 1280×720: the error
/// figure follows it within a bounded time, the full figure comes soon
/// after it stops, and the window draws as fast as without the live
/// reference (within 20 %).
#[test]
fn the_error_figure_follows_the_camera() {
    let bin = env!("CARGO_BIN_EXE_lesson_02");
    let (moving, run) = (MOVING_S.to_string(), RUN_S.to_string());
    let args = [
        "--width",
        "1280",
        "--height",
        "720",
        "--variant",
        "slope_hw",
        "--orbit",
        "20",
        "--orbit-seconds",
        &moving,
        "--window-seconds",
        &run,
    ];
    let Some(live) = run_window(bin, "window_follows_live", &args, false) else {
        return;
    };
    let mut without = args.to_vec();
    without.push("--no-live-reference");
    let Some(off) = run_window(bin, "window_follows_off", &without, false) else {
        return;
    };

    // When each view was first drawn, and when each figure first showed.
    let mut first_seen = std::collections::BTreeMap::new();
    let mut latencies = Vec::new();
    let mut shown = std::collections::BTreeSet::new();
    let mut settled_at = None;
    let last_gen = live.log.last().expect("frames")["scene_gen"].clone();
    for l in &live.log {
        let t = l["t_s"].as_f64().expect("t_s");
        first_seen
            .entry(l["scene_gen"].as_u64().expect("gen"))
            .or_insert(t);
        let e = &l["error"];
        if e.is_null() {
            continue;
        }
        let gen = e["scene_gen"].as_u64().expect("answer gen");
        if shown.insert((gen, e["level"].to_string())) {
            latencies.push((t, t - first_seen[&gen]));
        }
        if settled_at.is_none() && e["scene_gen"] == last_gen && e["level"] == "full" {
            settled_at = Some(t);
        }
    }
    let moving: Vec<f64> = latencies
        .iter()
        .filter(|(t, _)| *t < MOVING_S)
        .map(|l| l.1)
        .collect();
    let worst = moving.iter().cloned().fold(0.0, f64::max);
    eprintln!(
        "figures while moving: {}, latency (s): {moving:.2?}",
        moving.len()
    );
    assert!(
        moving.len() >= 2 && worst <= MAX_MOVING_LATENCY_S,
        "while the camera moved, {} figures came, the slowest {worst:.2} s after its view",
        moving.len()
    );
    let settled = settled_at.expect("the full figure of the last view came") - MOVING_S;
    eprintln!("full figure {settled:.2} s after the camera stopped");
    assert!(
        settled <= MAX_SETTLE_S,
        "the full figure came {settled:.2} s after the stop"
    );

    let (a, b) = (fps(&live.log, 1.0, MOVING_S), fps(&off.log, 1.0, MOVING_S));
    eprintln!("fps while moving: {a:.2} with the live reference, {b:.2} without");
    assert!(
        a >= 0.8 * b,
        "the live reference slowed the window from {b:.2} to {a:.2} fps"
    );
}

/// Bad window flags: one line naming the flag, non-zero, before any window.
#[test]
fn window_flags_without_a_window_are_refused() {
    let bin = env!("CARGO_BIN_EXE_lesson_01");
    let out = support::out_dir("window_flags_headless");
    let o = support::tiny_headless(bin, &out, &["--capture", "x.png"])
        .output()
        .expect("run");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--capture") && err.lines().count() == 1,
        "{err}"
    );
    let display = Display::open().expect("a display");
    let mut cmd = support::lesson_command(bin);
    display.apply(&mut cmd);
    let bad = out.join("no_such_folder").join("x.png");
    let o = cmd.arg("--capture").arg(&bad).output().expect("run");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("does not exist") && err.lines().count() == 1,
        "{err}"
    );
    assert!(!Path::new(&bad).exists());
}
