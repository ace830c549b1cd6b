//! `workbook bounds`: each committed record's bounds, measured again and
//! written into the record, its times and tables untouched.
//!
//! A figure measured on two adapters differs by the pixels either
//! rasteriser could flip (`common::reference::fragile`). The drift test
//! (`tests/generated.rs`) on another adapter than the records' allows each
//! figure to move by the bound the records' run measured plus the bound
//! its own run measures: each adapter flips only its own fragile pixels,
//! so the two images differ by at most both sets. The records carry their
//! run's bound (`VariantRecord::fragile`): `book` measures it with every
//! run, and this command again for records made before it did, with an
//! untimed run of the same entry (`--fragile`) on the records' adapter.

use std::path::Path;

use anyhow::{bail, Context, Result};

use crate::manifest::{self, RUNS};
use crate::record::Record;
use crate::runner::RunArgs;

/// Measures the bounds of every record (of lesson `only`, if given) and
/// writes them into the committed records under `root`.
pub fn write(root: &Path, only: Option<&str>) -> Result<()> {
    let runner = crate::runner_or_build()?;
    let generated = root.join("book/src/generated");
    let work = root.join("target/book-runs/bounds");
    let runs: Vec<_> = RUNS
        .iter()
        .filter(|r| only.is_none_or(|l| l == r.lesson))
        .collect();
    if runs.is_empty() {
        bail!("--only: no lesson {only:?} in the manifest");
    }
    let start = std::time::Instant::now();
    for (i, run) in runs.iter().enumerate() {
        let path = generated
            .join(run.lesson)
            .join(format!("{}.json", run.name));
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("{} is missing: run `workbook book`", path.display()))?;
        let mut record: Record = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a record", path.display()))?;
        let scene = run.scene.map(|s| root.join(s));
        let args = RunArgs {
            lesson: run.lesson,
            scene: scene.as_deref(),
            width: record.width,
            height: record.height,
            frames: 1,
            variants: run.variants,
            backend: Some(manifest::BACKEND),
            adapter: Some(manifest::ADAPTER),
            warm_up_ms: Some(0.0),
            fragile: true,
            fragile_variants: &[],
        };
        let t = std::time::Instant::now();
        let out = work.join(run.lesson).join(run.name);
        let report = runner.run(&args, &out)?;
        if report.adapter.name != record.adapter || report.adapter.backend != record.backend {
            bail!(
                "{}: the records were made on {} ({}), this run is on {} ({}): bounds are the records' adapter's",
                run.id(),
                record.adapter,
                record.backend,
                report.adapter.name,
                report.adapter.backend
            );
        }
        for v in &mut record.variants {
            let now = report
                .variants
                .iter()
                .find(|w| w.name == v.name)
                .with_context(|| format!("{}: variant {} no longer runs", run.id(), v.name))?;
            if now.error.misclassified_pct != v.misclassified_pct || now.counters != v.counters {
                bail!(
                    "{}: variant {} no longer gives its record's figures: run `workbook book --only {}`",
                    run.id(),
                    v.name,
                    run.lesson
                );
            }
            v.fragile = now.fragile.clone();
        }
        std::fs::write(&path, serde_json::to_string_pretty(&record)?)
            .with_context(|| format!("cannot write {}", path.display()))?;
        eprintln!(
            "[{}/{}] {}: bounds in {:.1} s",
            i + 1,
            runs.len(),
            run.id(),
            t.elapsed().as_secs_f64()
        );
    }
    println!(
        "bounds written into {} records in {:.0} s",
        runs.len(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
