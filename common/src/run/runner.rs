//! Runs a lesson binary headless and reads back its `report.json`.
//!
//! The book's generator, the grader and the tests drive the lessons
//! through their public command line (the book's appendix "Interfaces",
//! `book/src/appendix/interfaces.md`), exactly as a reader would, so what
//! the book shows is what `lesson_NN --headless` prints.
//!
//! A run may have a time limit ([`Runner::time_limit`]; the grader sets
//! one): a lesson still running then is killed, and the run ends in
//! a [`RunError`] that tells "did not finish" from "crashed" from the
//! lesson's own refusal, so that one student's endless loop or panic
//! stops one exercise, not the grader.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::gpu::watchdog;
use crate::measure::report::Report;
use anyhow::{bail, Context, Result};

/// One headless run of a lesson.
#[derive(Clone, Debug)]
pub struct RunArgs<'a> {
    pub lesson: &'a str,
    /// A scene file; the lesson's default scene when `None`.
    pub scene: Option<&'a Path>,
    pub width: u32,
    pub height: u32,
    pub frames: u32,
    /// Only these variants (all when empty).
    pub variants: &'a [&'a str],
    pub backend: Option<&'a str>,
    /// `--adapter` (`software` pins lavapipe/llvmpipe); the default when `None`.
    pub adapter: Option<&'a str>,
    /// `--warm-up-ms`: the lesson's default protocol when `None`; `Some(0.0)`
    /// for runs whose times nobody reads (errors and counters only).
    pub warm_up_ms: Option<f64>,
    /// `--fragile`: also measure how far each figure may move on another
    /// adapter (report.json's `fragile`).
    pub fragile: bool,
    /// With `fragile`, only these variants' bounds (`--fragile-variant`;
    /// all the run's when empty).
    pub fragile_variants: &'a [&'a str],
}

/// Why a run gave no report. The `anyhow::Error` of [`Runner::run`]
/// carries one (`e.downcast_ref::<RunError>()`); its text is one line.
#[derive(Debug)]
pub enum RunError {
    /// Still running at the time limit, so the runner killed it.
    TimedOut {
        lesson: String,
        scene: String,
        seconds: f64,
    },
    /// The lesson's own GPU watchdog ended it (`common::gpu::watchdog`):
    /// a frame the GPU did not finish. `line` is the lesson's.
    GpuHung {
        lesson: String,
        scene: String,
        line: String,
    },
    /// Killed by a signal, a Rust panic (exit code 101), or out of memory.
    /// `how` says which; `line` is the lesson's last word on it.
    Crashed {
        lesson: String,
        scene: String,
        how: String,
        line: String,
    },
    /// The lesson refused, with its own one line (any other non-zero exit).
    Failed {
        lesson: String,
        scene: String,
        line: String,
    },
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::TimedOut {
                lesson,
                scene,
                seconds,
            } => write!(
                f,
                "{lesson} on {scene} did not finish within {seconds} s, so it was stopped"
            ),
            RunError::GpuHung {
                lesson,
                scene,
                line,
            } => write!(f, "{lesson} on {scene} did not finish: {line}"),
            RunError::Crashed {
                lesson,
                scene,
                how,
                line,
            } => write!(f, "{lesson} on {scene} crashed ({how}): {line}"),
            RunError::Failed {
                lesson,
                scene,
                line,
            } => write!(f, "{lesson} on {scene} failed: {line}"),
        }
    }
}

impl std::error::Error for RunError {}

/// Finds the lesson binaries: beside this executable (`target/release/`).
pub struct Runner {
    bin_dir: PathBuf,
    /// A run still going after this is killed ([`RunError::TimedOut`]).
    /// None by default: the generator's runs take as long as they take;
    /// the grader sets one.
    pub time_limit: Option<Duration>,
}

impl Runner {
    /// Looks for the lesson binaries beside `exe` (the generator, or a
    /// test's `CARGO_BIN_EXE_*`), and names the build command if one is
    /// missing.
    pub fn beside(exe: &Path) -> Result<Runner> {
        let bin_dir = exe
            .parent()
            .context("the running binary's own path has no folder")?
            .to_path_buf();
        Runner::in_dir(bin_dir)
    }

    /// The lesson binaries in `bin_dir`.
    pub fn in_dir(bin_dir: PathBuf) -> Result<Runner> {
        let runner = Runner {
            bin_dir,
            time_limit: None,
        };
        for n in 1..=10 {
            let bin = runner.binary(&format!("lesson_{n:02}"));
            if !bin.exists() {
                bail!(
                    "{} is missing: build the lessons first (`cargo build --release --bins`)",
                    bin.display()
                );
            }
        }
        Ok(runner)
    }

    pub fn binary(&self, lesson: &str) -> PathBuf {
        self.bin_dir
            .join(format!("{lesson}{}", std::env::consts::EXE_SUFFIX))
    }

    /// Runs one lesson headless into `out` (created afresh) and returns its
    /// report. A run without a report is an error carrying a [`RunError`]:
    /// the lesson's own line, a crash, or the time limit.
    pub fn run(&self, a: &RunArgs, out: &Path) -> Result<Report> {
        if out.exists() {
            std::fs::remove_dir_all(out)
                .with_context(|| format!("cannot clear {}", out.display()))?;
        }
        let mut cmd = Command::new(self.binary(a.lesson));
        cmd.arg("--headless")
            .args(["--width", &a.width.to_string()])
            .args(["--height", &a.height.to_string()])
            .args(["--frames", &a.frames.to_string()])
            .arg("--out")
            .arg(out);
        if let Some(scene) = a.scene {
            cmd.arg("--scene").arg(scene);
        }
        for v in a.variants {
            cmd.args(["--variant", v]);
        }
        if let Some(b) = a.backend {
            cmd.args(["--backend", b]);
        }
        if let Some(ad) = a.adapter {
            cmd.args(["--adapter", ad]);
        }
        if let Some(ms) = a.warm_up_ms {
            cmd.args(["--warm-up-ms", &ms.to_string()]);
        }
        // Times nobody reads are not measured at all.
        if a.warm_up_ms == Some(0.0) {
            cmd.arg("--no-timing");
        }
        if a.fragile && a.fragile_variants.is_empty() {
            cmd.arg("--fragile");
        }
        if a.fragile {
            for v in a.fragile_variants {
                cmd.args(["--fragile-variant", v]);
            }
        }
        let ran = run_limited(&mut cmd, self.time_limit)
            .with_context(|| format!("cannot run {}", self.binary(a.lesson).display()))?;
        let lesson = a.lesson.to_string();
        let scene = a
            .scene
            .map_or("its default scene".into(), |s| s.display().to_string());
        let Some((status, stderr)) = ran else {
            let seconds = self.time_limit.map_or(0.0, |l| l.as_secs_f64());
            bail!(RunError::TimedOut {
                lesson,
                scene,
                seconds
            });
        };
        if !status.success() {
            bail!(ended(status, &stderr, lesson, scene));
        }
        let path = out.join("report.json");
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        serde_json::from_str(&text).with_context(|| format!("{}: not a report", path.display()))
    }
}

/// Runs `cmd` to its end, or kills it at `limit`: `None` then. Its output
/// is read in threads, so a lesson that writes much cannot block on a
/// full pipe; its stderr comes back.
fn run_limited(
    cmd: &mut Command,
    limit: Option<Duration>,
) -> std::io::Result<Option<(ExitStatus, String)>> {
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()?;
    let stdout = drain(child.stdout.take());
    let stderr = drain(child.stderr.take());
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait()? {
            break Some(s);
        }
        if limit.is_some_and(|l| start.elapsed() >= l) {
            // The process, and with it its device and the GPU work it
            // holds, ends here.
            child.kill()?;
            child.wait()?;
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    // A grandchild that kept the pipes open must not hold the runner.
    let grace = Duration::from_secs(5);
    let _ = stdout.recv_timeout(grace);
    let err = stderr.recv_timeout(grace).unwrap_or_default();
    Ok(status.map(|s| (s, String::from_utf8_lossy(&err).into_owned())))
}

/// Reads a pipe to its end in a thread; the bytes arrive on the channel.
fn drain<R: Read + Send + 'static>(pipe: Option<R>) -> mpsc::Receiver<Vec<u8>> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut buf = Vec::new();
        if let Some(mut p) = pipe {
            let _ = p.read_to_end(&mut buf);
        }
        let _ = tx.send(buf);
    });
    rx
}

/// The error of a run that exited unsuccessfully: crashed (a signal, a
/// panic, out of memory), the GPU watchdog, or the lesson's own line.
fn ended(status: ExitStatus, stderr: &str, lesson: String, scene: String) -> RunError {
    let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    let last = lines
        .last()
        .map_or("(no message)", |l| l.trim())
        .to_string();
    // Rust's own words for running out of memory, before it aborts.
    let oom = lines
        .iter()
        .find(|l| l.contains("memory allocation of") && l.contains("failed"));
    // A panic's location and message: `thread 'main' panicked at FILE:L:C:`
    // then the message (a backtrace, when asked for, comes after).
    let panic = lines
        .iter()
        .position(|l| l.contains("panicked at"))
        .map(|i| {
            let at = lines[i].trim();
            let at = at.find("panicked at").map_or(at, |k| &at[k..]);
            match lines.get(i + 1) {
                Some(msg) if !msg.starts_with("note:") && !msg.starts_with("stack backtrace") => {
                    format!("{at} {}", msg.trim())
                }
                _ => at.to_string(),
            }
        });
    let crashed = |how: &str, line: String| RunError::Crashed {
        lesson: lesson.clone(),
        scene: scene.clone(),
        how: how.to_string(),
        line,
    };
    if let Some(l) = oom {
        return crashed("out of memory", l.trim().to_string());
    }
    if let Some(sig) = signal(status) {
        let how = match sig {
            9 => "killed by signal 9, SIGKILL: out of memory?".to_string(),
            6 => "aborted, signal 6, SIGABRT".to_string(),
            11 => "segmentation fault, signal 11, SIGSEGV".to_string(),
            n => format!("killed by signal {n}"),
        };
        return crashed(&how, panic.unwrap_or(last));
    }
    match status.code() {
        Some(101) => crashed("panic", panic.unwrap_or(last)),
        Some(c) if c == watchdog::EXIT_CODE => RunError::GpuHung {
            lesson,
            scene,
            line: last,
        },
        _ => RunError::Failed {
            lesson,
            scene,
            line: last,
        },
    }
}

#[cfg(unix)]
fn signal(status: ExitStatus) -> Option<i32> {
    use std::os::unix::process::ExitStatusExt;
    status.signal()
}

#[cfg(not(unix))]
fn signal(_: ExitStatus) -> Option<i32> {
    None
}
