//! The window as a workbench, run for real on a private Xvfb
//! (`common::run::display`): every lesson's window captures its own
//! picture with the overlay and the diff view, and the error figure it
//! shows is the headless report's. (`window_live.rs` times the window
//! while the figure follows a moving camera, alone.)
//!
//! Each run writes `--window-log` (one JSON line per frame: its time, cost,
//! and the error figure shown with the view it was computed for).

use std::path::Path;
use std::time::Duration;

use common::run::display::Display;
use support::window::{run_window, run_window_with};

const W: u32 = 640;
const H: u32 = 360;

/// The lesson's first variant in a window at `W × H` on the diff view,
/// captured once the full figure came; and the same variant headless.
/// The window reads back as a web page does (`WORKBOOK_AS_PAGE=1`): its
/// counters a frame or more later, its GPU times frames later, never
/// waiting; they must be the headless run's counters, and GPU times where
/// the headless run had timestamps.
fn check_lesson(bin: &str, lesson: &str) {
    check_view(bin, lesson, "diff");
}

/// [`check_lesson`] on `view` (`diff`, or `dv` for an area light): the
/// capture outside the overlay is the headless `<variant>_<view>_l0.png`.
fn check_view(bin: &str, lesson: &str, view: &str) {
    let (w, h) = (W.to_string(), H.to_string());
    let size = ["--width", w.as_str(), "--height", h.as_str()];
    let mut args = size.to_vec();
    args.extend(["--view", view, "--capture-after", "3"]);
    let name = format!("{lesson}_window_{view}");
    let as_page = [("WORKBOOK_AS_PAGE", "1")];
    let Some(win) = run_window_with(bin, &name, &args, true, &as_page) else {
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
    let Some(run) = support::run_lesson(bin, &format!("{lesson}_window_{view}_headless"), &hargs)
    else {
        return;
    };
    let report = &run.report["variants"][0]["error"];
    // An area light's figures too, where the report has them (lesson 10).
    let soft = report.get("penumbra_mean_abs").is_some();
    let keys = ["misclassified_pct", "false_shadow_pct", "false_lit_pct"];
    let soft_keys = ["penumbra_mean_abs", "light_bleeding_pct"];
    for key in keys
        .into_iter()
        .chain(soft_keys.into_iter().filter(|_| soft))
    {
        let (window, headless) = (
            last["error"][key].as_f64().expect("window figure"),
            report[key].as_f64().expect("report figure"),
        );
        assert!(
            (window - headless).abs() < 0.01,
            "{lesson} {variant}: the window shows {key} {window:.4} %, the headless report {headless:.4} %"
        );
    }

    // The counters, read back as a page reads them: the report's.
    let counted = &run.report["variants"][0]["counters"];
    assert_eq!(
        &last["counters"], counted,
        "{lesson} {variant}: the window (as a page) counted otherwise than the headless run"
    );
    // GPU times read back frames later, where the adapter has timestamps.
    let timestamps = run.report["variants"][0]["timing_source"] == "gpu_timestamps";
    let late = &last["gpu_read_late"];
    if timestamps {
        let total = &last["gpu_ms"]["total"];
        assert!(
            total[1].as_f64().is_some_and(|t| t > 0.0) && late.as_u64().is_some(),
            "{lesson}: no GPU time read back later in the window: gpu_ms {}, read late {late}",
            last["gpu_ms"]
        );
    } else {
        assert!(
            late.is_null(),
            "{lesson}: GPU times without timestamps: {late}"
        );
    }

    // The capture: the diff view outside the overlay, the overlay over it.
    let shot = win.capture.expect("a capture");
    assert_eq!(shot.dimensions(), (W, H), "{lesson}: the capture's size");
    let diff = image::open(run.out.join(format!("{variant}_{view}_l0.png")))
        .expect("the headless image of the view")
        .to_rgba8();
    let close = |a: &image::Rgba<u8>, b: &image::Rgba<u8>| {
        (0..3).all(|c| (a.0[c] as i32 - b.0[c] as i32).abs() <= 3)
    };
    // The overlay's panel, as the window logged it (pixels).
    let r: Vec<f64> = last["overlay_px"]
        .as_array()
        .expect("the overlay's rectangle")
        .iter()
        .map(|v| v.as_f64().expect("a number"))
        .collect();
    assert!(
        r[2] - r[0] > 200.0 && r[3] - r[1] > 100.0,
        "{lesson}: overlay {r:?}"
    );
    // With its drop shadow (egui draws it up to about 25 pixels out).
    let m = 32.0;
    let in_panel = |x: u32, y: u32| {
        let (x, y) = (x as f64, y as f64);
        x >= r[0] - m && x <= r[2] + m && y >= r[1] - m && y <= r[3] + m
    };
    // Inside: away from its rounded corners and shadow.
    let (px, py, pw, ph) = (
        r[0] as u32 + 8,
        r[1] as u32 + 30,
        (r[2] - r[0]) as u32 - 16,
        (r[3] - r[1]) as u32 - 40,
    );
    let (mut outside, mut outside_same) = (0u64, 0u64);
    let (mut panel, mut panel_same, mut panel_text) = (0u64, 0u64, 0u64);

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
            panel_text += u64::from(p.0[..3].iter().all(|&c| c > 170));
        }
    }
    let outside_pct = 100.0 * outside_same as f64 / outside as f64;
    assert!(
        outside_pct > 99.0,
        "{lesson}: outside the overlay, only {outside_pct:.2} % of the capture is the headless {view} image"
    );
    // The panel darkens what is under it, and its text is light.
    let text_pct = 100.0 * panel_text as f64 / panel as f64;
    let same_pct = 100.0 * panel_same as f64 / panel as f64;
    assert!(
        text_pct > 0.5 && same_pct < 20.0,
        "{lesson}: no overlay panel at the top left ({text_pct:.1} % light text, {same_pct:.1} % the diff image)"
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

/// Lesson 10 on the diff view, then on the signed ΔV view of its area
/// light: a soft shadow's penumbra error, which the diff view cannot show,
/// is the headless `<variant>_dv_l0.png` in the window. One after the
/// other, in one test: two lesson 10 windows at once (each casting the
/// area light's reference on one low-priority thread while the rasteriser
/// takes both cores) starved both references past the capture's 60 s.
#[test]
fn lesson_10_window_capture() {
    let bin = env!("CARGO_BIN_EXE_lesson_10");
    check_view(bin, "lesson_10", "diff");
    check_view(bin, "lesson_10", "dv");
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

/// The window is documented in one place: the key table of the book's
/// "Using the workbook" and the README's are the overlay's own list (`overlay::KEYS`), row for
/// row, so that a key added to the window and not to the book fails here.
#[test]
fn the_book_and_the_readme_list_the_windows_keys() {
    use common::run::window::overlay::KEYS;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for file in ["book/src/using.md", "README.md"] {
        let text = std::fs::read_to_string(root.join(file)).expect("read");
        let start = text
            .find("| key | what it does |")
            .unwrap_or_else(|| panic!("{file}: no table of the window's keys"));
        let rows: Vec<(String, String)> = text[start..]
            .lines()
            .skip(2)
            .take_while(|l| l.starts_with('|'))
            .map(|l| {
                let cells: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
                (cells[0].to_string(), cells[1].to_string())
            })
            .collect();
        let keys: Vec<(String, String)> = KEYS
            .iter()
            .map(|(k, w)| (k.to_string(), w.to_string()))
            .collect();
        assert_eq!(
            rows, keys,
            "{file}: the key table is not the overlay's KEYS"
        );
    }
}

/// A knob set for the window (`--knob`, through the same `apply_knob` as
/// its widgets) is measured live like a variant: the window's figure for
/// `bias_1tx` at 4 texels is the headless report's at 4 texels, and not
/// the one at 1 texel.
#[test]
fn a_knob_is_measured_live_like_a_variant() {
    let bin = env!("CARGO_BIN_EXE_lesson_02");
    let (w, h) = (W.to_string(), H.to_string());
    let base = [
        "--width",
        w.as_str(),
        "--height",
        h.as_str(),
        "--variant",
        "bias_0.25tx",
    ];
    let mut args = base.to_vec();
    args.extend(["--knob", "bias_texels=4", "--capture-after", "3"]);
    let Some(win) = run_window(bin, "window_knob", &args, true) else {
        return;
    };
    let last = win.log.last().expect("frames");
    assert_eq!(last["error"]["level"], "full", "{last}");
    let shown = last["error"]["false_shadow_pct"].as_f64().expect("figure");
    let headless = |name: &str, extra: &[&'static str]| {
        let mut a = base.to_vec();
        a.extend(["--frames", "1"]);
        a.extend(extra);
        // `None` only where no GPU is found and none is required.
        let run = support::run_lesson(bin, name, &a)?;
        let pct = run.report["variants"][0]["error"]["false_shadow_pct"].as_f64();
        Some(pct.expect("the report's false shadow"))
    };
    let (Some(at_4), Some(named)) = (
        headless("window_knob_4", &["--knob", "bias_texels=4"]),
        headless("window_knob_named", &[]),
    ) else {
        return;
    };
    assert!(
        (shown - at_4).abs() < 0.01 && (shown - named).abs() > 1.0,
        "the window shows false shadow {shown:.3} %; headless at 4 texels {at_4:.3} %, as named (0.25 texels) {named:.3} %"
    );
}

/// The live reference's readback, which the window never waits for
/// (`PendingRead`, under `PendingFrame`), reads what the blocking one
/// reads: a texture of odd width (its rows padded to 256 bytes) comes back
/// row for row, and is not mapped until it is asked for and the device is
/// polled. (The window's captures above check the frame it reads this way:
/// their figures are the headless report's.)
#[test]
fn the_readback_without_waiting_reads_what_the_blocking_one_reads() {
    use common::gpu::readback::{read_texture, PendingRead};
    use common::gpu::targets::{render_texture, ID_FORMAT};

    let Some(gpu) = support::test_gpu() else {
        return;
    };
    // 37 × 5 ids, each texel its own.
    let (w, h) = (37u32, 5u32);
    let copy_dst = wgpu::TextureUsages::COPY_DST;
    let tex = render_texture(&gpu, "odd width", w, h, ID_FORMAT, copy_dst);
    let texels: Vec<u32> = (0..w * h).map(|i| i * 7 + 1).collect();
    gpu.queue.write_texture(
        tex.as_image_copy(),
        bytemuck::cast_slice(&texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * w),
            rows_per_image: Some(h),
        },
        tex.size(),
    );
    let pending = PendingRead::start(&gpu, &tex, 4);
    assert!(!pending.mapped(), "mapped before it was asked for");
    pending.map();
    let mut polls = 0;
    while !pending.mapped() {
        assert!(polls < 1000, "not mapped after 1000 polls");
        gpu.device.poll(wgpu::PollType::Poll).expect("poll");
        std::thread::sleep(Duration::from_millis(2));
        polls += 1;
    }
    let got = pending.take().expect("mapped").expect("read");
    assert_eq!(
        got,
        bytemuck::cast_slice::<u32, u8>(&texels),
        "the texels in order"
    );
    assert_eq!(got, read_texture(&gpu, &tex, 4).expect("blocking read"));
}
