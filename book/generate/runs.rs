//! The `book` command's runs of the lessons: one manifest entry run once
//! ([`Measure`]), its repeats pooled into the record the book keeps
//! ([`to_record`]), and the figures and texts the runs wrote copied into
//! the book ([`copy_outputs`]).

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{bail, Context, Result};
use common::measure::report::Report;
use indicatif::ProgressBar;

use crate::manifest::{Run, FIGURES, TEXTS};
use crate::record::{pool, Record, VariantRecord};
use crate::runner::{RunArgs, Runner};
use crate::{figures, manifest, record, repo_root as root};

/// What one run of a lesson needs.
pub struct Measure<'a> {
    pub runner: &'a Runner,
    pub backend: &'a str,
    pub adapter: &'a str,
    pub work: &'a Path,
    pub bar: &'a ProgressBar,
}

impl Measure<'_> {
    /// Runs repeat `i` of one manifest entry and returns its report.
    pub fn once(&self, run: &Run, i: u32) -> Result<Report> {
        let repeats = if run.timed { manifest::REPEATS } else { 1 };
        let scene = run.scene.map(|s| root().join(s));
        let args = RunArgs {
            lesson: run.lesson,
            scene: scene.as_deref(),
            width: run.size.0,
            height: run.size.1,
            frames: if run.timed { run.frames } else { 1 },
            variants: run.variants,
            backend: Some(self.backend),
            adapter: Some(self.adapter),
            // Untimed runs keep errors and counters only: no warm-up needed.
            warm_up_ms: (!run.timed).then_some(0.0),
            // The bounds once (they are deterministic), after the timed
            // frames of the same process.
            fragile: i == 0,
            fragile_variants: &[],
        };
        let bar = self.bar;
        bar.set_message(format!("{} ({}/{repeats})", run.id(), i + 1));
        let out = self
            .work
            .join(run.lesson)
            .join(run.name)
            .join(format!("r{i}"));
        let t = std::time::Instant::now();
        let report = self.runner.run(&args, &out)?;
        bar.inc(1);
        if bar.is_hidden() {
            // Not a terminal (a log): one line a run instead of the bar.
            eprintln!(
                "[{}/{}] {} run {}: {:.1} s",
                bar.position(),
                bar.length().unwrap_or(0),
                run.id(),
                i + 1,
                t.elapsed().as_secs_f64()
            );
        }
        Ok(report)
    }
}

/// What the book keeps of a run. Errors and counters must agree between
/// the repeats (they are deterministic); times are pooled.
pub fn to_record(run: &Run, reports: &[Report]) -> Result<Record> {
    let first = &reports[0];
    let variants = first
        .variants
        .iter()
        .map(|v| {
            let same: Vec<&common::measure::report::VariantReport> = reports
                .iter()
                .filter_map(|r| r.variants.iter().find(|w| w.name == v.name))
                .collect();
            if same.iter().any(|w| {
                w.error != v.error
                    || w.counters != v.counters
                    || w.camera_path != v.camera_path
                    || w.classes != v.classes
            }) {
                bail!(
                    "{}: variant {} gave different errors, counters or shimmer in repeated runs",
                    run.id(),
                    v.name
                );
            }
            let runs: Vec<RunTimes> = same
                .iter()
                .zip(1..)
                .map(|(w, i)| {
                    let base = w.timing_check.as_ref().and_then(|c| c.base_ms);
                    let why = format!(
                        "base pass {} ms in run {i}",
                        base.map_or("—".into(), |b| format!("{b:.3}"))
                    );
                    (&w.timing_samples_ms, w.timing_stable(), why)
                })
                .collect();
            let timing = pool_stable(&runs);
            Ok(VariantRecord {
                name: v.name.clone(),
                receiver_pixels: v.error.receiver_pixels,
                misclassified_pct: v.error.misclassified_pct,
                false_shadow_pct: v.error.false_shadow_pct,
                false_lit_pct: v.error.false_lit_pct,
                mean_abs: v.error.mean_abs,
                coverage_mismatch_pct: v.error.coverage_mismatch_pct,
                counters: v.counters.clone(),
                timing: if run.timed { timing } else { None },
                camera_path: v.camera_path.clone(),
                classes: record::ClassRecord::of(v),
                soft: v.error.soft.clone(),
                fragile: v.fragile.clone(),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let baselines: Vec<RunTimes> = reports
        .iter()
        .zip(1..)
        .filter_map(|(r, i)| {
            let b = r.baseline.as_ref()?;
            Some((
                &b.timing_samples_ms,
                b.stable(),
                format!("every baseline block of run {i}"),
            ))
        })
        .collect();
    let baseline = pool_stable(&baselines);
    Ok(Record {
        lesson: run.lesson.to_string(),
        run: run.name.to_string(),
        scene: run.scene.unwrap_or("default").to_string(),
        title: run.title.to_string(),
        adapter: first.adapter.name.clone(),
        backend: first.adapter.backend.clone(),
        width: first.width,
        height: first.height,
        repeats: reports.len() as u32,
        frames: if run.timed { first.frames } else { 0 },
        timing_source: record::timing_source(first),
        variants,
        warm_up_ms: first
            .timing_protocol
            .as_ref()
            .filter(|_| run.timed)
            .map(|p| p.warm_up_min_ms),
        baseline: if run.timed { baseline } else { None },
    })
}

/// One run's samples of a timed cell, whether its block was stable, and
/// why not.
type RunTimes<'a> = (&'a BTreeMap<String, Vec<f64>>, bool, String);

/// Pools the runs whose times were stable; a run that was not is left out
/// and named (`left_out`). When no run was stable, every run is pooled and
/// the timing is `unstable`, with the reasons.
fn pool_stable(runs: &[RunTimes]) -> Option<record::Timing> {
    let stable: Vec<&BTreeMap<String, Vec<f64>>> =
        runs.iter().filter(|r| r.1).map(|r| r.0).collect();
    let why: Vec<&str> = runs.iter().filter(|r| !r.1).map(|r| r.2.as_str()).collect();
    let why = (!why.is_empty()).then(|| why.join(", "));
    if stable.is_empty() {
        let all: Vec<&BTreeMap<String, Vec<f64>>> = runs.iter().map(|r| r.0).collect();
        return pool(&all).map(|t| record::Timing { unstable: why, ..t });
    }
    pool(&stable).map(|t| record::Timing { left_out: why, ..t })
}

/// Copies the figures and lesson-written tables of the manifest; a PNG
/// figure is made ready for the page on the way ([`figures::prepare`]),
/// and its count goes to `generated/figures.json`.
pub fn copy_outputs(
    work: &Path,
    figures: &Path,
    generated: &Path,
    only: Option<&str>,
) -> Result<()> {
    let mut counts = figures::load_counts(generated)?;
    for (list, dest_root, is_figure) in [(FIGURES, figures, true), (TEXTS, generated, false)] {
        for f in list
            .iter()
            .filter(|f| only.is_none_or(|l| f.run.starts_with(l)))
        {
            let src = work.join(f.run).join("r0").join(f.file);
            let dest = dest_root.join(f.dest);
            std::fs::create_dir_all(dest.parent().context("figure path")?)?;
            if is_figure && f.dest.ends_with(".png") {
                figures::prepare_file(&src, f.dest, &dest, &mut counts)
                    .with_context(|| format!("figure {}", f.dest))?;
                continue;
            }
            std::fs::copy(&src, &dest)
                .with_context(|| format!("figure {}: cannot copy {}", f.dest, src.display()))?;
        }
    }
    figures::write_counts(generated, &counts)
}
