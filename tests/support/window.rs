//! Running a lesson's window on a private display (`common::run::display`)
//! with `--window-log`, for the window's tests.

use std::time::Duration;

use common::run::display::Display;
use serde_json::Value;

use crate::paths::out_dir;
use crate::run::{lesson_command, run_watched};

/// A window run's log, and its capture if it made one.
pub struct WindowRun {
    pub log: Vec<Value>,
    pub capture: Option<image::RgbaImage>,
}

/// Runs `bin` in a window on a private display with `args`, logging each frame.
pub fn run_window(bin: &str, name: &str, args: &[&str], capture: bool) -> Option<WindowRun> {
    run_window_with(bin, name, args, capture, &[])
}

/// [`run_window`] with these environment variables set for the lesson.
pub fn run_window_with(
    bin: &str,
    name: &str,
    args: &[&str],
    capture: bool,
    env: &[(&str, &str)],
) -> Option<WindowRun> {
    let display = Display::open().expect("a display for the window");
    let out = out_dir(name);
    let log = out.join("window.jsonl");
    let shot = out.join("capture.png");
    let mut cmd = lesson_command(bin);
    display.apply(&mut cmd);
    cmd.envs(env.iter().copied());
    cmd.args(args).arg("--window-log").arg(&log);
    cmd.arg("--out").arg(&out);
    if capture {
        cmd.arg("--capture").arg(&shot);
    }
    run_watched(&mut cmd, name, Duration::from_secs(300), |_| {})?;
    let text = std::fs::read_to_string(&log).expect("the window log");
    let log = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("a log line parses"))
        .collect();
    let capture = capture.then(|| image::open(&shot).expect("the capture").to_rgba8());
    Some(WindowRun { log, capture })
}
