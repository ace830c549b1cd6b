//! `--times-only`: a headless run that times the variants and the no-shadow
//! baseline exactly as [`super::headless`] does, writes `times.json` (the
//! times of report.json and nothing else) and stops. It traces no
//! reference, writes no image, and measures no error figure and no counter:
//! for what reads times alone (`tests/cpu_share.rs`). Lesson 08's three
//! variants on a 262 k-triangle torus at 160×90, 5 frames: 40.8 s so,
//! 54.8 s as a full timed run (lavapipe, 2026-12-04).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};

use crate::measure::report::{AdapterReport, BaselineReport, TimingCheck, TimingProtocolReport};
use crate::measure::timing::{median_times, samples, spread_times, TimingSource, CPU_TOTAL, TOTAL};
use crate::run::cli::Args;
use crate::run::headless::{baseline_report, setup, time_variants};
use crate::run::instruments::Instruments;
use crate::run::lesson::variant_name;
use crate::scene::Scene;

/// `times.json`: a report's times, and what they were measured on.
#[derive(Serialize, Deserialize, Clone, Debug)]
pub struct TimesReport {
    pub lesson: String,
    pub adapter: AdapterReport,
    pub width: u32,
    pub height: u32,
    pub scene: String,
    pub frames: u32,
    pub variants: Vec<VariantTimes>,
    pub baseline: BaselineReport,
    pub timing_protocol: TimingProtocolReport,
}

/// One variant's times, as report.json's variant has them.
#[derive(Serialize, Deserialize, Clone, Debug)]
pub struct VariantTimes {
    pub name: String,
    pub timing_ms: BTreeMap<String, f64>,
    pub timing_spread_ms: BTreeMap<String, [f64; 2]>,
    pub timing_samples_ms: BTreeMap<String, Vec<f64>>,
    pub timing_source: TimingSource,
    pub timing_check: TimingCheck,
}

/// Times every variant and the baseline, writes `times.json` in the output
/// folder; returns what it wrote and where.
pub fn run_times_only<L: Instruments>(
    args: &Args,
    scene: Scene,
    variants: &[L::Variant],
) -> Result<(TimesReport, PathBuf)> {
    let mut s = setup::<L>(args, scene, variants)?;
    let timed = time_variants(&mut s, args)?;
    let source = s.timer.source();
    let rows = (s.runnable.iter().zip(&timed.variants))
        .map(|(&v, (times, check))| VariantTimes {
            name: variant_name(v),
            timing_ms: median_times(times),
            timing_spread_ms: spread_times(times),
            timing_samples_ms: samples(times),
            timing_source: source,
            timing_check: check.clone(),
        })
        .collect();
    let baseline = baseline_report(&timed);
    let report = TimesReport {
        lesson: L::NAME.to_string(),
        adapter: s.adapter,
        width: args.width,
        height: args.height,
        scene: s.scene_name,
        frames: args.frames,
        variants: rows,
        baseline,
        timing_protocol: timed.protocol,
    };
    report.write(&s.out_dir.join("times.json"))?;
    Ok((report, s.out_dir))
}

impl TimesReport {
    /// Writes `times.json`, naming the file on failure (not generic: its
    /// JSON writer is compiled once, here, not in each lesson binary).
    fn write(&self, path: &Path) -> Result<()> {
        let json = serde_json::to_string_pretty(self)?;
        std::fs::write(path, json).with_context(|| format!("cannot write {}", path.display()))
    }

    /// Each variant's median frame time and CPU time, with their spread.
    pub fn table(&self) -> String {
        let mut s = format!(
            "{} on {} ({}), {}x{}, scene {}: times only (--times-only: no reference, figures or counters), median [quartiles] of {} frames\n",
            self.lesson,
            self.adapter.name,
            self.adapter.backend,
            self.width,
            self.height,
            self.scene,
            self.frames
        );
        let w = (self.variants.iter().map(|v| v.name.len()).max())
            .unwrap_or(0)
            .max(8);
        let row = |name: &str, ms: &BTreeMap<String, f64>, spread: &BTreeMap<String, [f64; 2]>| {
            let cell = |key: &str| match (ms.get(key), spread.get(key)) {
                (Some(m), Some([a, b])) => format!("{key} {m:.3} ms [{a:.3}, {b:.3}]"),
                (Some(m), None) => format!("{key} {m:.3} ms"),
                _ => format!("{key} -"),
            };
            format!("{name:<w$}  {}  {}\n", cell(TOTAL), cell(CPU_TOTAL))
        };
        let b = &self.baseline;
        s += &row("baseline", &b.timing_ms, &b.timing_spread_ms);
        for v in &self.variants {
            s += &row(&v.name, &v.timing_ms, &v.timing_spread_ms);
        }
        s
    }
}
