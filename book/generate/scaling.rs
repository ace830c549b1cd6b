//! Scaling sweeps (issue 9): time and deterministic counters of one
//! shadow-map lesson and one shadow-volume lesson against the size of the
//! problem: caster triangles, shadow-map (or screen) resolution, and the
//! number of lights. This file runs them and writes what they make.
//!
//! Every point is one process of the lesson (`--frames 5`) on a scene this
//! module writes into a scratch folder (a torus at rising tessellation, or
//! the default casters under N lights), or on the lesson's default scene.
//! The records go to `book/src/generated/scaling/<sweep>.json`, the tables
//! to `<sweep>.md`, and two log-log plots a sweep (times, and counters on
//! their own axes) to `book/src/figures/scaling/<sweep>_{time,counters}.svg`.
//!
//! The parts, one file each under `scaling/`:
//! - [`plan`]: the six sweeps, what each shows and expects, and their runs.
//! - [`scenes`]: the meshes and scenes the runs are made on.
//! - [`measure`]: one sweep's runs made into its record.
//! - [`sweep`]: the record, and reading the committed ones back.
//! - [`table`] and [`legend`]: a sweep's markdown and its columns' meanings.
//! - [`plot`]: a sweep's two log-log plots.

mod legend;
mod measure;
mod plan;
mod plot;
mod scenes;
mod sweep;
mod table;

use std::path::Path;

use anyhow::{bail, Context, Result};
use indicatif::ProgressBar;

use crate::runner::Runner;
use measure::measure;
use plan::plans;
use plot::plot;
use sweep::generated_dir;
pub use sweep::load_sweeps;
pub use table::{table, table_file};

/// Rewrites every sweep's table from its committed record.
pub fn write_tables(root: &Path) -> Result<()> {
    let generated = generated_dir(root);
    for sweep in load_sweeps(root)? {
        write(&generated.join(table_file(&sweep)), &table(&sweep))?;
    }
    Ok(())
}

/// Runs the scaling sweeps (all, or the one named `only`) and writes
/// book/src/generated/scaling/*.json and *.md and
/// book/src/figures/scaling/*.svg. `work` is a scratch folder (meshes,
/// scenes, run outputs).
pub fn run(
    runner: &Runner,
    root: &Path,
    work: &Path,
    backend: &str,
    bar: &ProgressBar,
    only: Option<&str>,
) -> Result<()> {
    let work = work.join("scaling");
    std::fs::create_dir_all(&work)?;
    let generated = generated_dir(root);
    let figures = root.join("book/src/figures/scaling");
    std::fs::create_dir_all(&generated)?;
    std::fs::create_dir_all(&figures)?;

    let mut sweeps = plans(&work)?;
    if let Some(name) = only {
        let names: Vec<&str> = sweeps.iter().map(|(p, _)| p.name).collect();
        if !names.contains(&name) {
            bail!("sweep: no sweep {name:?} (one of {})", names.join(", "));
        }
        sweeps.retain(|(p, _)| p.name == name);
    }
    let total: usize = sweeps.iter().map(|(_, steps)| steps.len()).sum();
    bar.inc_length(total as u64);
    for (plan, steps) in &sweeps {
        let sweep = measure(runner, plan, steps, &work, backend, bar)?;
        write(
            &generated.join(format!("{}.json", sweep.name)),
            &(serde_json::to_string_pretty(&sweep)? + "\n"),
        )?;
        write(&generated.join(table_file(&sweep)), &table(&sweep))?;
        plot(&sweep, plan.x_label, &figures)?;
    }
    // The records read back to the same tables (what the drift test checks).
    for sweep in load_sweeps(root)? {
        let path = generated.join(table_file(&sweep));
        let md = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        if md != table(&sweep) {
            bail!(
                "{}: the record does not read back to its table",
                path.display()
            );
        }
    }
    Ok(())
}

pub fn write(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}
