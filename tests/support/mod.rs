//! Shared by the lesson tests: run a lesson binary headless, read its outputs.
//!
//! The tests drive the real command line (`--headless --out DIR ...`), so
//! what they check is what a learner runs.

use std::path::{Path, PathBuf};
use std::process::Command;

pub mod portable;
pub mod tolerance;
pub mod window;

/// The repository's root: this library is its `tests/support/` (its
/// path checked, so that moving the library is an error, not another
/// folder read). A test can use this or its own
/// `env!("CARGO_MANIFEST_DIR")`, which is the root too (the tests are the
/// root package's); this library's code can only use this.
pub fn root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = here.parent().and_then(Path::parent);
    match root {
        Some(r) if r.join("tests/support/Cargo.toml") == here.join("Cargo.toml") => r.to_path_buf(),
        _ => panic!(
            "{}: the test support library is not the root's tests/support/",
            here.display()
        ),
    }
}

/// The folder cargo gives integration tests for their files
/// (`CARGO_TARGET_TMPDIR`, `<target>/tmp`). Cargo sets it only when it
/// compiles an integration test, not this library, so it is found from
/// the running test binary, which cargo puts in `<profile>/deps/`
/// (`target/release/deps/lesson_01-…`): the folder `tmp` beside the
/// profile's folder (`target/tmp`; with `--target T`, `target/T/tmp`). A
/// test binary anywhere else is an error that says so. A test can read its
/// own `env!("CARGO_TARGET_TMPDIR")`, the same folder.
pub fn target_tmp() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let above_profile = exe
        .parent()
        .filter(|deps| deps.file_name().is_some_and(|n| n == "deps"))
        .and_then(Path::parent)
        .and_then(Path::parent);
    match above_profile {
        Some(above) => above.join("tmp"),
        None => panic!(
            "{}: not a test binary in cargo's <target>/<profile>/deps/ folder",
            exe.display()
        ),
    }
}

/// Called when a lesson found no adapter. A GPU test without a GPU proves
/// nothing, so by default the test FAILS here, with the line that says
/// what to install. Only with `WORKBOOK_ALLOW_NO_GPU=1` does it return
/// `false`, and the caller skips with a loud `SKIPPED` line.
pub fn gpu_required() -> bool {
    if std::env::var("WORKBOOK_ALLOW_NO_GPU").is_ok_and(|v| v == "1") {
        return false;
    }
    panic!(
        "no GPU adapter found: on Linux without a GPU driver, install Mesa's software \
         rasterisers (`apt-get install -y mesa-vulkan-drivers libgl1-mesa-dri libegl1`); \
         Windows (DX12, Vulkan) and macOS (Metal) use their GPU; \
         WORKBOOK_ALLOW_NO_GPU=1 skips the GPU tests instead, and then they prove nothing"
    );
}

/// The adapter the tests run the lessons on: `any` (your GPU, else a
/// software rasteriser), unless `WORKBOOK_ADAPTER` says otherwise. CI pins
/// `software` (lavapipe/llvmpipe) for determinism; the snapshots hold on
/// either, within the tolerances of [`tolerance`].
pub fn test_adapter() -> String {
    std::env::var("WORKBOOK_ADAPTER")
        .ok()
        .filter(|v| !v.trim().is_empty())
        .unwrap_or_else(|| "any".into())
}

/// A device on [`test_adapter`], for the tests that drive the GPU
/// themselves; `None` (the test returns, having said `SKIPPED`) only where
/// [`gpu_required`] allows it.
pub fn test_gpu() -> Option<common::gpu::Gpu> {
    match common::gpu::Gpu::new(None, Some(&test_adapter()), None) {
        Ok(gpu) => Some(gpu),
        Err(e) if !gpu_required() => {
            eprintln!("SKIPPED: {e}");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

/// Whether a snapshot's run measures its figures' bounds (`--fragile`):
/// only on an adapter the committed snapshots were recorded on (their
/// first line, `adapter: NAME (BACKEND)`: CI's lavapipe on Vulkan). There
/// the new text must equal the committed one, bounds and all, so the run
/// measures them again. On any other adapter (llvmpipe on GL, a
/// student's GPU) a figure may move by the committed run's bound and the
/// new run's own bound is never read (`tolerance::compare`: a broken
/// technique cannot widen its own tolerance), so the run leaves out the
/// moved draws, most of a snapshot's time: lesson 08's default scene at
/// 320×180 took 11.6 s without them, 52.7 s with them (lavapipe,
/// 2026-12-04). The adapter is recognised by that line alone (its name as
/// the driver gives it, and the backend). `WORKBOOK_FRAGILE=1` in the
/// tests' environment measures them on any adapter (printed there, never
/// compared); any other value leaves the rule as it is.
pub fn measure_bounds() -> bool {
    use std::sync::OnceLock;
    static HERE: OnceLock<bool> = OnceLock::new();
    *HERE.get_or_init(|| {
        let forced = std::env::var("WORKBOOK_FRAGILE").map(|v| v.trim().to_ascii_lowercase());
        if forced.is_ok_and(|v| v == "1" || v == "true") {
            return true;
        }
        // No adapter: measure, and let the run fail the way it must.
        let Ok(gpu) = common::gpu::Gpu::new(None, Some(&test_adapter()), None) else {
            return true;
        };
        let here = format!(
            "{}{} ({})",
            tolerance::ADAPTER_PREFIX,
            gpu.adapter_name(),
            gpu.backend_name()
        );
        tolerance::recorded_adapters().contains(&here)
    })
}

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

/// A fresh output folder under the target directory.
pub fn out_dir(name: &str) -> PathBuf {
    let backend = std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "auto".into());
    let dir = target_tmp().join(format!("{name}-{backend}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create test output folder");
    dir
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

/// Reads a visibility PNG (gray + alpha) as (object covered 0/1, visibility 0..1).
pub fn read_visibility(path: &Path) -> (Vec<u32>, Vec<f32>, u32, u32) {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_luma_alpha8();
    let (w, h) = img.dimensions();
    let ids = img.pixels().map(|p| u32::from(p.0[1] > 0)).collect();
    let vis = img.pixels().map(|p| p.0[0] as f32 / 255.0).collect();
    (ids, vis, w, h)
}

/// The coarse text mask a learner reads in `cargo insta review`.
pub fn ascii_of(path: &Path, cols: u32, rows: u32) -> String {
    let (ids, vis, w, h) = read_visibility(path);
    common::reference::metrics::ascii_mask(&ids, &vis, w, h, cols, rows)
}

/// A three-level text mask, stable across drivers where a surface is noisy:
/// per cell, '#' when under 15 % of its covered pixels are lit, '.' when over
/// 85 % are, ':' for mixed cells (acne, penumbrae, shadow edges), ' ' when
/// under half the cell is covered.
pub fn ascii_levels(path: &Path, cols: u32, rows: u32) -> String {
    let (ids, vis, w, h) = read_visibility(path);
    let mut out = String::new();
    for r in 0..rows {
        for c in 0..cols {
            let (x0, x1) = (c * w / cols, (c + 1) * w / cols);
            let (y0, y1) = (r * h / rows, (r + 1) * h / rows);
            let (mut covered, mut lit, mut n) = (0u32, 0f32, 0u32);
            for y in y0..y1 {
                for x in x0..x1 {
                    let i = (y * w + x) as usize;
                    n += 1;
                    if ids[i] != 0 {
                        covered += 1;
                        lit += vis[i];
                    }
                }
            }
            let ch = if covered * 2 < n {
                ' '
            } else {
                match lit / covered as f32 {
                    f if f < 0.15 => '#',
                    f if f > 0.85 => '.',
                    _ => ':',
                }
            };
            out.push(ch);
        }
        out.push('\n');
    }
    out
}

/// One variant's error figures, rounded for a stable snapshot, each with
/// its bound when the run measured one ([`bound`]).
pub fn error_line(v: &serde_json::Value, decimals: usize) -> String {
    let e = &v["error"];
    let f = |k: &str| e[k].as_f64().unwrap_or(f64::NAN);
    let b = |k: &str| bound(v, k, 1.0, decimals);
    format!(
        "{:<14} misclassified {:>6.d$}%{}  false shadow {:>6.d$}%{}  false lit {:>6.d$}%{}",
        v["name"].as_str().unwrap_or("?"),
        f("misclassified_pct"),
        b("misclassified_pct"),
        f("false_shadow_pct"),
        b("false_shadow_pct"),
        f("false_lit_pct"),
        b("false_lit_pct"),
        d = decimals
    )
}

/// ` ±B`: how far error figure `field` (an `ErrorStats` or `SoftError`
/// field) of variant `v` may move on another adapter, as the run measured
/// it (`--fragile`, report.json's `fragile.bounds`; see
/// `common::reference::fragile`), times `scale` (100 for a fraction
/// printed in percent), rounded up to `decimals`. Empty when the run
/// measured none. `tolerance::compare` allows the committed text's bound.
/// A figure whose bound is too wide for it to be compared (as printed, to
/// `decimals`: [`portable::portable`]) gets
/// ` (not portable: ±B, above 10%)` instead, and is compared by its side.
pub fn bound(v: &serde_json::Value, field: &str, scale: f64, decimals: usize) -> String {
    let Some(b) = v["fragile"]["bounds"][field].as_f64() else {
        return String::new();
    };
    let step = 10f64.powi(-(decimals as i32));
    let up = (b * scale / step - 1e-9).ceil().max(0.0) * step;
    let text = format!("{up:.decimals$}");
    // The figure as the snapshot prints it.
    let figure = v["error"][field].as_f64().map(|f| {
        let printed = format!("{:.decimals$}", f * scale);
        printed.parse::<f64>().unwrap_or(f64::NAN)
    });
    match figure {
        Some(f) if !portable::portable(f, up) => {
            portable::not_portable(&text, portable::portable_side(f))
        }
        _ => format!(" ±{text}"),
    }
}

/// ` ±N`: how far counter `key` of variant `v` moved when the run drew it
/// again with the camera moved (`fragile.counters`), or empty.
pub fn counter_bound(v: &serde_json::Value, key: &str) -> String {
    match v["fragile"]["counters"][key].as_u64() {
        Some(n) => format!(" ±{n}"),
        None => String::new(),
    }
}

/// One error figure of one variant (`"misclassified_pct"`, `"false_lit_pct"`, ...).
pub fn error(report: &serde_json::Value, variant_name: &str, key: &str) -> f64 {
    variant(report, variant_name)["error"][key]
        .as_f64()
        .unwrap_or_else(|| panic!("{variant_name}: error.{key} missing"))
}

/// One counter of one variant (`"taps"`, `"volume_fragments"`, ...).
pub fn counter(report: &serde_json::Value, variant_name: &str, key: &str) -> u64 {
    variant(report, variant_name)["counters"][key]
        .as_u64()
        .unwrap_or_else(|| panic!("{variant_name}: counters.{key} missing"))
}

/// A committed scene file, by name (`"lesson_02_grazing_85.toml"`).
pub fn scene_path(name: &str) -> PathBuf {
    root().join("scenes").join(name)
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

/// A variant's misclassified %, the figure most pass criteria use.
pub fn misclassified(run: &LessonRun, variant_name: &str) -> f64 {
    error(&run.report, variant_name, "misclassified_pct")
}

pub fn variant<'a>(report: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    report["variants"]
        .as_array()
        .and_then(|vs| vs.iter().find(|v| v["name"] == name))
        .unwrap_or_else(|| panic!("variant {name} missing from report.json"))
}

/// Compares a rendered frame with a committed reference PNG.
///
/// Both are box-filtered into `block`×`block` cells (so single-pixel raster
/// differences between drivers do not count); the test fails when more than
/// `max_bad_pct` % of the cells differ by more than `tol` (0–255) in any
/// channel. On failure, the actual image and a difference image are written
/// next to the reference as `*.actual.png` and `*.diff.png`. A missing
/// reference is a failure (with `WORKBOOK_BLESS=1` it is written instead).
pub fn compare_with_reference(
    actual: &Path,
    reference: &Path,
    block: u32,
    tol: u8,
    max_bad_pct: f64,
) {
    let a = image::open(actual)
        .unwrap_or_else(|e| panic!("{}: {e}", actual.display()))
        .to_rgba8();
    if std::env::var("WORKBOOK_BLESS").is_ok_and(|v| v == "1") {
        a.save(reference).expect("write reference image");
        eprintln!("blessed {}", reference.display());
        return;
    }
    let r = match image::open(reference) {
        Ok(r) => r.to_rgba8(),
        Err(e) => panic!(
            "reference image {} is missing or unreadable ({e}); render it with WORKBOOK_BLESS=1 and look at it before committing",
            reference.display()
        ),
    };
    assert_eq!(
        a.dimensions(),
        r.dimensions(),
        "image size differs from {}",
        reference.display()
    );
    let (w, h) = a.dimensions();
    let (cw, ch) = (w.div_ceil(block), h.div_ceil(block));
    let mut bad = 0u32;
    let mut diff = image::RgbaImage::new(w, h);
    for cy in 0..ch {
        for cx in 0..cw {
            let mut sa = [0f64; 4];
            let mut sr = [0f64; 4];
            let mut n = 0f64;
            for y in cy * block..((cy + 1) * block).min(h) {
                for x in cx * block..((cx + 1) * block).min(w) {
                    for c in 0..4 {
                        sa[c] += a.get_pixel(x, y).0[c] as f64;
                        sr[c] += r.get_pixel(x, y).0[c] as f64;
                    }
                    n += 1.0;
                }
            }
            let d = (0..4)
                .map(|c| ((sa[c] - sr[c]) / n).abs())
                .fold(0.0, f64::max);
            let is_bad = d > tol as f64;
            bad += is_bad as u32;
            for y in cy * block..((cy + 1) * block).min(h) {
                for x in cx * block..((cx + 1) * block).min(w) {
                    let g = (d * 4.0).min(255.0) as u8;
                    diff.put_pixel(
                        x,
                        y,
                        if is_bad {
                            image::Rgba([255, 0, 0, 255])
                        } else {
                            image::Rgba([g, g, g, 255])
                        },
                    );
                }
            }
        }
    }
    let pct = 100.0 * bad as f64 / (cw * ch) as f64;
    if pct > max_bad_pct {
        let stem = reference.with_extension("");
        let act = PathBuf::from(format!("{}.actual.png", stem.display()));
        let dif = PathBuf::from(format!("{}.diff.png", stem.display()));
        a.save(&act).expect("write actual image");
        diff.save(&dif).expect("write diff image");
        panic!(
            "{} differs from {}: {pct:.2}% of {block}x{block} cells off by more than {tol} (allowed {max_bad_pct}%); wrote {} and {}",
            actual.display(),
            reference.display(),
            act.display(),
            dif.display()
        );
    }
}

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

/// The snapshot's cost counters: for every variant, `keys` that it has
/// (keys a variant lacks, such as a skipped variant's, are left out),
/// compared as [`tolerance`] says (most exactly).
pub fn counter_lines(report: &serde_json::Value, keys: &[&str]) -> String {
    let mut out = String::from("\ncounters:\n");
    for v in report["variants"].as_array().into_iter().flatten() {
        let c = &v["counters"];
        let parts: Vec<String> = keys
            .iter()
            .filter_map(|k| {
                c[*k]
                    .as_u64()
                    .map(|n| format!("{k} {n}{}", counter_bound(v, k)))
            })
            .collect();
        out += &format!(
            "{:<18} {}\n",
            v["name"].as_str().unwrap_or("?"),
            parts.join("  ")
        );
    }
    out
}
