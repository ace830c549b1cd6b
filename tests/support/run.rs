//! Running a lesson binary: headless with its report ([`run_lesson`],
//! [`shared_run`], [`run_small`]), for its times alone ([`run_times_only`]),
//! or watched while it runs ([`run_watched`]); the command line and
//! environment every run gets ([`lesson_command`]).

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::gpu::{gpu_required, measure_bounds, test_adapter};
use crate::paths::{out_dir, scene_path};

/// A lesson binary's command, on [`test_adapter`].
pub fn lesson_command(bin: &str) -> Command {
    let mut c = Command::new(bin);
    c.env("WORKBOOK_ADAPTER", test_adapter());
    // The tests read errors, counters and that times exist; the protocol's
    // warm-up is unit-tested (common::measure::protocol). A test that sets
    // WORKBOOK_WARM_UP_MS itself keeps its own.
    if std::env::var_os("WORKBOOK_WARM_UP_MS").is_none() {
        c.env("WORKBOOK_WARM_UP_MS", "0");
    }
    // Most tests read no times at all: they skip the timed blocks
    // (`--no-timing`). A test that reads times sets WORKBOOK_NO_TIMING=0
    // for its run ([`TIMED`]).
    if std::env::var_os("WORKBOOK_NO_TIMING").is_none() {
        c.env("WORKBOOK_NO_TIMING", "1");
    }
    c
}

/// The environment of a run whose times a test reads.
pub const TIMED: &[(&str, &str)] = &[("WORKBOOK_NO_TIMING", "0")];

pub struct LessonRun {
    pub out: PathBuf,
    pub report: serde_json::Value,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `bin --headless --out <dir> args...`. `None` only when no adapter
/// exists and the GPU is not required (the skip is printed).
pub fn run_lesson(bin: &str, name: &str, args: &[&str]) -> Option<LessonRun> {
    run_lesson_env(bin, name, args, &[])
}

/// `run_lesson` with extra environment variables for the lesson process.
pub fn run_lesson_env(
    bin: &str,
    name: &str,
    args: &[&str],
    env: &[(&str, &str)],
) -> Option<LessonRun> {
    let out = out_dir(name);
    // A snapshot's run (its name ends in `_snapshot`) also measures how far
    // each figure may move on another adapter (`--fragile`): the snapshot
    // prints those bounds as `±B`, and `tolerance::compare` allows them.
    // Only on the adapter the snapshots were recorded on ([`measure_bounds`]).
    let fragile = if name.ends_with("_snapshot") && measure_bounds() {
        "1"
    } else {
        "0"
    };
    let mut c = lesson_command(bin);
    c.env("WORKBOOK_FRAGILE", fragile).envs(env.iter().copied());
    c.arg("--headless").arg("--out").arg(&out).args(args);
    finish(name, c, out, "report.json")
}

/// Runs `bin --times-only --out <dir> args...` (timed, whatever the
/// environment says): its `times.json`, as [`LessonRun::report`]: the times
/// of a report.json and nothing else. For a test that reads times alone.
pub fn run_times_only(bin: &str, name: &str, args: &[&str]) -> Option<LessonRun> {
    let out = out_dir(name);
    let mut c = lesson_command(bin);
    c.env("WORKBOOK_FRAGILE", "0")
        .env("WORKBOOK_NO_TIMING", "0");
    c.arg("--times-only").arg("--out").arg(&out).args(args);
    finish(name, c, out, "times.json")
}

/// Runs the lesson command `c`, which writes `file` into `out`.
fn finish(name: &str, mut c: Command, out: PathBuf, file: &str) -> Option<LessonRun> {
    let o = c.output().expect("run the lesson binary");
    let stderr = String::from_utf8_lossy(&o.stderr).to_string();
    let stdout = String::from_utf8_lossy(&o.stdout).to_string();
    if !o.status.success() {
        if stderr.contains("no GPU adapter found") && !gpu_required() {
            eprintln!("SKIPPED {name}: no GPU adapter (WORKBOOK_ALLOW_NO_GPU=1)");
            return None;
        }
        panic!("{name}: lesson failed ({}):\n{stderr}\n{stdout}", o.status);
    }
    let text = std::fs::read_to_string(out.join(file))
        .unwrap_or_else(|e| panic!("{name}: {file} not written: {e}"));
    let report: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{name}: {file}: {e}"));
    Some(LessonRun {
        out,
        report,
        stdout,
        stderr,
    })
}

/// One run for every test of a test binary that asks for it with the same
/// binary, name and arguments: the lesson runs at the first test that
/// asks, and a test that asks while it runs waits for it (the tests of a
/// binary run in parallel threads). A run that panics is not kept: the
/// next test to ask runs it again (and fails the same way). The name is
/// the output folder's (`out_dir`), so a run made here must not share its
/// name with one made by [`run_lesson`]. A snapshot's run (`*_snapshot`,
/// with `--fragile`) gives the same figures as one without: `--fragile`
/// only adds the bounds' moved draws after the measured frame (compared on
/// the default scenes of lessons 02, 03, 06, 08 and 09, every figure of
/// every variant, 2026-12-03). So the tests of lessons 02, 03, 06, 08 and
/// 09 that read their lesson's default run read the snapshot's: one run,
/// where there were two to four.
pub fn shared_run(bin: &str, name: &str, args: &[&str]) -> Option<&'static LessonRun> {
    use std::sync::{Mutex, OnceLock};
    type Key = (String, String, Vec<String>);
    type Cell = &'static OnceLock<Option<LessonRun>>;
    static RUNS: Mutex<Vec<(Key, Cell)>> = Mutex::new(Vec::new());
    let key: Key = (
        bin.to_string(),
        name.to_string(),
        args.iter().map(|a| a.to_string()).collect(),
    );
    let cell = {
        let mut runs = RUNS.lock().unwrap_or_else(|e| e.into_inner());
        match runs.iter().find(|(k, _)| *k == key) {
            Some((_, cell)) => *cell,
            None => {
                let cell: Cell = Box::leak(Box::new(OnceLock::new()));
                runs.push((key, cell));
                cell
            }
        }
    };
    cell.get_or_init(|| run_lesson(bin, name, args)).as_ref()
}

/// One untimed frame of `bin` at 640×360, on `scene` (a file in
/// `scenes/`) or the lesson's own, with `extra` arguments.
pub fn run_small(bin: &str, name: &str, scene: Option<&str>, extra: &[&str]) -> Option<LessonRun> {
    let scene = scene.map(|s| scene_path(s).display().to_string());
    let mut args: Vec<&str> = [&SMALL[..], extra].concat();
    if let Some(s) = &scene {
        args.extend(["--scene", s.as_str()]);
    }
    run_lesson(bin, name, &args)
}

/// The size and frames of [`run_small`].
pub const SMALL: [&str; 6] = ["--width", "640", "--height", "360", "--frames", "1"];

/// Runs a prepared lesson command (stdout discarded, stderr kept), calling
/// `poll(pid)` every 2 ms while it runs and killing it past `limit`.
/// `None` when no adapter exists and none is required (the skip is
/// printed); a failed run or one past `limit` panics with its stderr.
pub fn run_watched(
    cmd: &mut Command,
    name: &str,
    limit: std::time::Duration,
    mut poll: impl FnMut(u32),
) -> Option<std::time::Duration> {
    use std::io::Read;
    let start = std::time::Instant::now();
    let mut child = cmd
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("start the lesson");
    let status = loop {
        poll(child.id());
        if let Some(status) = child.try_wait().expect("wait for the lesson") {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{name}: ran past {limit:?}");
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    };
    let mut stderr = String::new();
    if let Some(mut e) = child.stderr.take() {
        let _ = e.read_to_string(&mut stderr);
    }
    if !status.success() {
        if stderr.contains("no GPU adapter found") && !gpu_required() {
            eprintln!("SKIPPED {name}: no GPU adapter (WORKBOOK_ALLOW_NO_GPU=1)");
            return None;
        }
        panic!("{name}: lesson failed ({status}):\n{stderr}");
    }
    Some(start.elapsed())
}

/// `bin --headless` at 64×36, one frame, writing to `out`, then `args`:
/// the cheapest run, for tests that look at the exit and stderr.
pub fn tiny_headless(bin: &str, out: &Path, args: &[&str]) -> Command {
    let mut c = lesson_command(bin);
    c.args([
        "--headless",
        "--width",
        "64",
        "--height",
        "36",
        "--frames",
        "1",
    ])
    .args(args)
    .arg("--out")
    .arg(out);
    c
}
