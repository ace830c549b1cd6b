//! Runs a lesson binary headless and reads back its `report.json`.
//!
//! The generator drives the lessons through their public command line
//! (INTERFACES.md), exactly as a reader would, so what the book shows is
//! what `lesson_NN --headless` prints.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};
use common::measure::report::Report;

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
}

/// Finds the lesson binaries: beside this executable (`target/release/`).
pub struct Runner {
    bin_dir: PathBuf,
}

impl Runner {
    /// Looks for the lesson binaries beside `exe` (the generator, or a
    /// test's `CARGO_BIN_EXE_*`), and names the build command if one is
    /// missing.
    pub fn beside(exe: &Path) -> Result<Runner> {
        let bin_dir = exe
            .parent()
            .context("the generator's own path has no folder")?
            .to_path_buf();
        let runner = Runner { bin_dir };
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
    /// report. A non-zero exit is an error carrying the lesson's own line.
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
        if a.fragile {
            cmd.arg("--fragile");
        }
        let output = cmd
            .output()
            .with_context(|| format!("cannot start {}", self.binary(a.lesson).display()))?;
        if !output.status.success() {
            let err = String::from_utf8_lossy(&output.stderr);
            let line = err.lines().last().unwrap_or("(no message)");
            let scene = a
                .scene
                .map_or("its default scene".into(), |s| s.display().to_string());
            bail!("{} on {scene} failed: {line}", a.lesson);
        }
        let path = out.join("report.json");
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        serde_json::from_str(&text).with_context(|| format!("{}: not a report", path.display()))
    }
}
