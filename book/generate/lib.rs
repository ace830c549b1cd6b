//! The book's generator, a library: every measured table, figure and plot
//! of the book and the README's results table, made from real runs of the
//! lessons. The `workbook` binary (`main.rs`) is its command line:
//!
//! ```text
//! cargo run --release --bin workbook -- book
//! ```
//!
//! It runs every lesson headless on its default scene (timed, repeated) and
//! on every extreme-case scene a chapter cites ([`manifest::RUNS`]), then
//! writes `book/src/generated/` (tables, and the records the drift test
//! checks), `book/src/figures/` (figures, plots, diagrams) and the README's
//! table between its marker comments.
//!
//! The chapters' measured figures are markers it fills ([`prose`]); the
//! sentences comparing them carry claims it checks on the same records
//! ([`claims`]): it fails, naming the chapter's line, when one is false.
//!
//! The `book` command's runs are in [`runs`], what it makes from the
//! records in [`derive`]. The tests (`tests/generated.rs`, the book's
//! tests) use these modules as the generator does.

pub mod adapters;
pub mod bounds;
pub mod choosing;
pub mod claims;
pub mod derive;
pub mod diagrams;
pub mod error_plots;
pub mod figures;
pub mod gpu_costs;
pub mod gpus;
pub mod grade_times;
pub mod legend;
pub mod lesson09;
pub mod lesson10;
pub mod manifest;
pub mod origins;
pub mod over_floor;
pub mod pass_model;
pub mod plots;
pub mod ports;
pub mod prose;
pub mod record;
pub mod runs;
pub mod scaling;
pub mod sets;
pub mod soft_diagrams;
pub mod stability;
pub mod summary;
pub mod table;
pub mod tap_floor;
pub mod taps;
pub mod views;
pub mod volume_diagrams;
pub mod volumes_gpu;
pub mod web;
pub mod web_sources;
pub mod why;
pub mod window_shots;

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};

/// Runs the lesson binaries headless and reads back their reports
/// (`common::run::runner`): the generator's, the grader's and the tests'.
pub use common::run::runner;
use runner::Runner;

/// The repository's root (this crate is `book/generate/`).
pub fn repo_root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors()
        .nth(2)
        .expect("book/generate/ is two folders below the root")
        .to_path_buf()
}

/// The runner, building the lesson binaries first when one is missing.
pub fn runner_or_build() -> Result<Runner> {
    let exe = std::env::current_exe().context("cannot find the generator's own path")?;
    if Runner::beside(&exe).is_err() {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        eprintln!("building the lessons: {cargo} build --release --bins");
        let ok = std::process::Command::new(&cargo)
            .args(["build", "--release", "--bins"])
            .current_dir(repo_root())
            .status()
            .with_context(|| format!("cannot run {cargo}"))?
            .success();
        if !ok {
            bail!("`cargo build --release --bins` failed");
        }
    }
    Runner::beside(&exe)
}

pub fn write(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}
