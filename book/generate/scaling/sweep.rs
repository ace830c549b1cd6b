//! A sweep's record (`book/src/generated/scaling/<sweep>.json`): its points,
//! curves and stops, read back from the committed files.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};

use crate::record::Stat;

/// One point of a sweep: one variant at one size.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct SweepPoint {
    /// The size (triangles, texels on a side, pixels, lights).
    pub x: f64,
    /// The size as the table prints it (`1 048 576`, `1280×720`).
    pub label: String,
    pub variant: String,
    /// GPU time of the frame: median [interquartile range] of the point's
    /// frames (the frame cost, `frame`, is among the passes where recorded).
    pub total: Stat,
    /// The passes the sweep shows, by their report key.
    pub passes: BTreeMap<String, Stat>,
    /// The counters the sweep shows.
    pub counters: BTreeMap<String, u64>,
    pub misclassified_pct: f64,
}

/// Milliseconds or a count.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Unit {
    Ms,
    Count,
}

/// One curve of a sweep: a variant's time or counter against the size, its
/// expected order and the measured log-log slope.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct SweepCurve {
    pub variant: String,
    /// `total`, a pass key (`shadow`, `volume`, `cpu_silhouette`) or a
    /// counter name.
    pub key: String,
    pub unit: Unit,
    /// The expected order, e.g. `O(√n)`.
    pub expected: String,
    /// The log-log slope that order means once constant costs are small.
    pub expected_slope: f64,
    /// Least-squares log-log slope over every point (`None`: not defined,
    /// e.g. a counter that is zero).
    pub slope_all: Option<f64>,
    /// The same over the largest three sizes, where fixed costs weigh least.
    pub slope_top: Option<f64>,
}

/// One sweep: one lesson, one or more variants, one size axis.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Sweep {
    /// File stem: `triangles_lesson_05`.
    pub name: String,
    pub lesson: String,
    pub title: String,
    /// The x column's header (`triangles`).
    pub axis: String,
    /// What the points ran on.
    pub scene: String,
    pub adapter: String,
    pub backend: String,
    /// The frame size; 0 when the sweep varies it.
    pub width: u32,
    pub height: u32,
    pub frames: u32,
    pub timing_source: String,
    pub passes: Vec<String>,
    pub counters: Vec<String>,
    pub points: Vec<SweepPoint>,
    pub curves: Vec<SweepCurve>,
    /// Variants the lesson left out at some size: their buffers would pass
    /// one of the adapter's limits (the lesson's own note says which).
    #[serde(default)]
    pub stops: Vec<SweepStop>,
}

/// A variant left out at one size of a sweep, and why.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct SweepStop {
    pub x: f64,
    pub label: String,
    pub variant: String,
    /// The lesson's line: the buffer, its size and the limit.
    pub why: String,
}

/// The folder of the records and tables, under the repository root.
pub(super) fn generated_dir(root: &Path) -> PathBuf {
    root.join("book/src/generated/scaling")
}

/// Every committed sweep record, by file name.
pub fn load_sweeps(root: &Path) -> Result<Vec<Sweep>> {
    let dir = generated_dir(root);
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .with_context(|| format!("{} is missing: run `workbook book`", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p)
                .with_context(|| format!("cannot read {}", p.display()))?;
            serde_json::from_str(&text).with_context(|| format!("{}: not a sweep", p.display()))
        })
        .collect()
}

pub(super) fn distinct_variants(sweep: &Sweep) -> Vec<String> {
    let mut v: Vec<String> = Vec::new();
    for p in &sweep.points {
        if !v.contains(&p.variant) {
            v.push(p.variant.clone());
        }
    }
    v
}

/// The points the "largest sizes" slope uses.
pub(super) const SIZES_TOP: usize = 3;

/// A point's value of `key` (a time's median, or a counter).
pub(super) fn value(p: &SweepPoint, key: &str, unit: Unit) -> Option<f64> {
    match unit {
        Unit::Ms if key == "total" => Some(p.total.median),
        Unit::Ms => p.passes.get(key).map(|s| s.median),
        Unit::Count => p.counters.get(key).map(|&n| n as f64),
    }
}
