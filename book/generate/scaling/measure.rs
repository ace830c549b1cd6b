//! Measuring a sweep: its runs, one process a point, made into its record
//! (points, the left-out variants, and each curve's fitted log-log slopes).

use anyhow::{bail, Context, Result};
use common::measure::report::Report;
use common::measure::timing::{CPU_TOTAL, FRAME};
use indicatif::ProgressBar;
use std::path::Path;

use super::plan::{Plan, Step, FRAMES, HEIGHT, WIDTH};
use super::sweep::{value, Sweep, SweepCurve, SweepPoint, SweepStop, SIZES_TOP};
use crate::manifest;
use crate::plots;
use crate::record::Stat;
use crate::runner::{RunArgs, Runner};

/// Runs a sweep's steps and makes its record.
pub(super) fn measure(
    runner: &Runner,
    plan: &Plan,
    steps: &[Step],
    work: &Path,
    backend: &str,
    bar: &ProgressBar,
) -> Result<Sweep> {
    let mut points: Vec<SweepPoint> = Vec::new();
    let mut stops: Vec<SweepStop> = Vec::new();
    let mut first: Option<Report> = None;
    for (i, step) in steps.iter().enumerate() {
        bar.set_message(format!("scaling {} ({}/{})", plan.name, i + 1, steps.len()));
        let args = RunArgs {
            lesson: plan.lesson,
            scene: step.scene.as_deref(),
            width: step.width,
            height: step.height,
            frames: FRAMES,
            variants: &step.variants,
            backend: Some(backend),
            adapter: Some(manifest::ADAPTER),
            warm_up_ms: None,
            fragile: false,
            fragile_variants: &[],
        };
        let out = work.join("runs").join(plan.name).join(format!("p{i}"));
        let report = match runner.run(&args, &out) {
            Ok(r) => r,
            // A variant whose buffers pass the adapter's limits: the lesson
            // refuses it by name in one line; where it stops is a result.
            Err(e) if step.variants.len() == 1 && limit_line(&e.to_string()).is_some() => {
                let (variant, x, label) = &step.xs[0];
                let why = limit_line(&e.to_string()).unwrap_or_default();
                let own = format!("{}: ", plan.lesson);
                stops.push(SweepStop {
                    x: *x,
                    label: label.clone(),
                    variant: variant.to_string(),
                    why: why.strip_prefix(&own).unwrap_or(&why).to_string(),
                });
                bar.inc(1);
                continue;
            }
            Err(e) => {
                return Err(e)
                    .with_context(|| format!("scaling sweep {}, point {}", plan.name, i + 1))
            }
        };
        for (variant, x, label) in &step.xs {
            let v = report
                .variants
                .iter()
                .find(|v| v.name == *variant)
                .with_context(|| format!("{}: no variant {variant} in the report", plan.lesson))?;
            let total = v
                .timing_samples_ms
                .get("total")
                .with_context(|| format!("{}: {variant} has no total time", plan.lesson))?;
            points.push(SweepPoint {
                x: *x,
                label: label.clone(),
                variant: variant.to_string(),
                total: Stat::of(total),
                // The sweep's passes, and the frame cost and CPU time.
                passes: plan
                    .passes
                    .iter()
                    .chain(&[FRAME, CPU_TOTAL])
                    .filter_map(|&k| v.timing_samples_ms.get(k).map(|s| (k.into(), Stat::of(s))))
                    .collect(),
                counters: plan
                    .counters
                    .iter()
                    .filter_map(|&k| v.counters.get(k).map(|&n| (k.into(), n)))
                    .collect(),
                misclassified_pct: v.error.misclassified_pct,
            });
        }
        first.get_or_insert(report);
        bar.inc(1);
    }
    let Some(first) = first else {
        bail!("scaling sweep {} has no points", plan.name);
    };
    // The plan's passes and counters that some point reports.
    let reported = |keys: &[&str], has: fn(&SweepPoint, &str) -> bool| -> Vec<String> {
        (keys.iter())
            .filter(|k| points.iter().any(|p| has(p, k)))
            .map(|k| k.to_string())
            .collect()
    };
    let passes = reported(plan.passes, |p, k| p.passes.contains_key(k));
    let counters = reported(plan.counters, |p, k| p.counters.contains_key(k));
    let variants: Vec<String> = plan.variants.iter().map(|v| v.to_string()).collect();
    let mut curves = Vec::new();
    for &(variant, key, unit, expected, expected_slope) in &plan.curves {
        let mine: Vec<&str> = if variant == "*" {
            variants.iter().map(|v| v.as_str()).collect()
        } else {
            vec![variant]
        };
        let pts: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| mine.contains(&p.variant.as_str()))
            .filter_map(|p| value(p, key, unit).map(|y| (p.x, y)))
            .collect();
        if pts.is_empty() {
            continue; // the lesson does not report this key
        }
        let slope = |pts: &[(f64, f64)]| {
            let xs: Vec<f64> = pts.iter().map(|p| p.0).collect();
            let ys: Vec<f64> = pts.iter().map(|p| p.1).collect();
            Some(plots::loglog_slope(&xs, &ys)).filter(|s| s.is_finite())
        };
        let top = &pts[pts.len().saturating_sub(SIZES_TOP)..];
        curves.push(SweepCurve {
            variant: if variant == "*" {
                variants.join(", ")
            } else {
                variant.into()
            },
            key: key.into(),
            unit,
            expected: expected.into(),
            expected_slope,
            slope_all: slope(&pts),
            slope_top: slope(top),
        });
    }
    let single_size = steps.iter().all(|s| (s.width, s.height) == (WIDTH, HEIGHT));
    Ok(Sweep {
        name: plan.name.into(),
        lesson: plan.lesson.into(),
        title: plan.title.into(),
        axis: plan.axis.into(),
        scene: plan.scene.clone(),
        adapter: first.adapter.name.clone(),
        backend: first.adapter.backend.clone(),
        width: if single_size { WIDTH } else { 0 },
        height: if single_size { HEIGHT } else { 0 },
        frames: first.frames,
        timing_source: crate::record::timing_source(&first),
        passes,
        counters,
        points,
        curves,
        stops,
    })
}

/// The lesson's line about a buffer that passes one of the adapter's
/// limits (lesson 05's `fit`), from a failed run's message, or `None`.
fn limit_line(message: &str) -> Option<String> {
    let line = message.lines().last()?;
    let limits = ["(max_buffer_size = ", "(max_storage_buffer_binding_size = "];
    if !limits.iter().any(|l| line.contains(l)) {
        return None;
    }
    let why = line.rsplit_once("failed: ").map_or(line, |(_, w)| w);
    Some(why.trim_start_matches("error: ").to_string())
}
