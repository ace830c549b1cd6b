//! What the generator keeps of a run (`book/src/generated/<lesson>/<run>.json`):
//! errors, counters and pooled times, and the committed ones read back
//! ([`load_records`]). The markdown tables made from it are in
//! [`crate::table`]. `tests/generated.rs` re-runs the lessons and
//! compares the error columns and counters with these records.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};

use crate::manifest::RUNS;

/// A median with its spread (an interquartile range, see [`Stat::of_runs`]), in milliseconds.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct Stat {
    pub median: f64,
    pub q25: f64,
    pub q75: f64,
}

impl Stat {
    /// The median and interquartile range of pooled samples.
    pub fn of(samples: &[f64]) -> Stat {
        Stat {
            median: common::measure::timing::quantile(samples, 0.5),
            q25: common::measure::timing::quantile(samples, 0.25),
            q75: common::measure::timing::quantile(samples, 0.75),
        }
    }

    /// The spread of a time measured in several runs (one sample list a
    /// run): the median of all samples; from the lower of their first
    /// quartile and the lowest run's own median, to the higher of their
    /// third quartile and the highest run's median. A run that went
    /// faster or slower as a whole widens the spread instead of hiding
    /// in the pooled frames.
    pub fn of_runs(runs: &[&[f64]]) -> Stat {
        let all: Vec<f64> = runs.iter().flat_map(|r| r.iter().copied()).collect();
        let pooled = Stat::of(&all);
        let medians: Vec<f64> = runs
            .iter()
            .filter(|r| !r.is_empty())
            .map(|r| common::measure::timing::quantile(r, 0.5))
            .collect();
        let lo = medians.iter().copied().fold(pooled.q25, f64::min);
        let hi = medians.iter().copied().fold(pooled.q75, f64::max);
        Stat {
            median: pooled.median,
            q25: lo,
            q75: hi,
        }
    }

    /// Two times differ measurably only when their spreads do not overlap.
    pub fn differs_from(&self, other: &Stat) -> bool {
        self.q75 < other.q25 || other.q75 < self.q25
    }
}

/// GPU total and per-pass times (`frame` and `cpu_total` among them),
/// pooled over the repeats.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Timing {
    pub total: Stat,
    pub passes: BTreeMap<String, Stat>,
    /// Why the times cannot be quoted (the protocol's base-pass check
    /// failed in a repeat), or absent when they can.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unstable: Option<String>,
    /// Runs left out of the pool because the check failed in them (the
    /// other runs' frames make the figures).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub left_out: Option<String>,
}

impl Timing {
    /// The frame cost (`frame`: wall clock, start to GPU completion); the
    /// GPU total in records older than the key.
    pub fn frame(&self) -> &Stat {
        self.passes.get(FRAME).unwrap_or(&self.total)
    }

    /// The CPU's time per frame (`cpu_total`), when recorded.
    pub fn cpu(&self) -> Option<&Stat> {
        self.passes.get(CPU_TOTAL)
    }

    /// Whether the times can be quoted.
    pub fn stable(&self) -> bool {
        self.unstable.is_none()
    }
}

use common::measure::timing::{CPU_TOTAL, FRAME};

/// One variant: its error against the reference, counters and times.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct VariantRecord {
    pub name: String,
    pub receiver_pixels: u64,
    pub misclassified_pct: f64,
    pub false_shadow_pct: f64,
    pub false_lit_pct: f64,
    pub mean_abs: f64,
    pub coverage_mismatch_pct: f64,
    pub counters: BTreeMap<String, u64>,
    pub timing: Option<Timing>,
    /// Shimmer over the scene's `[camera_path]` (lesson 09), when it has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_path: Option<CameraPathRecord>,
    /// The error per class of pixels (lesson 09: per cascade), when the
    /// lesson gives classes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub classes: Vec<ClassRecord>,
    /// The soft shadow's own figures (lesson 10: a light with a size),
    /// when the scene's light has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub soft: Option<SoftRecord>,
    /// How far each figure and counter could move on another adapter, as
    /// this run measured it (`--fragile`, `common::reference::fragile`):
    /// the drift test allows a figure on another adapter to move by this
    /// bound plus that adapter's own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fragile: Option<common::reference::fragile::Fragile>,
}

/// A soft shadow's error (lesson 10): the penumbra's mean |ΔV|, the
/// umbra's misclassified % and light bleeding, as the report gives them
/// (see `common::reference::metrics::SoftError`).
pub type SoftRecord = common::reference::metrics::SoftError;

/// Shimmer over a camera path (lesson 09): the report's own figures,
/// kept as they are (see `common::scene::camera_path`).
pub type CameraPathRecord = common::measure::report::CameraPathReport;

impl ClassRecord {
    /// What the book keeps of a report's per-class errors.
    pub fn of(v: &common::measure::report::VariantReport) -> Vec<ClassRecord> {
        v.classes
            .iter()
            .flatten()
            .map(|c| ClassRecord {
                name: c.name.clone(),
                pixels: c.pixels,
                misclassified_pct: c.misclassified_pct,
                false_shadow_pct: c.false_shadow_pct,
                false_lit_pct: c.false_lit_pct,
            })
            .collect()
    }
}

/// The error over one class of pixels (one cascade).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct ClassRecord {
    pub name: String,
    pub pixels: u64,
    pub misclassified_pct: f64,
    pub false_shadow_pct: f64,
    pub false_lit_pct: f64,
}

/// One run of one lesson (timed runs pool several processes).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Record {
    pub lesson: String,
    pub run: String,
    /// The scene file, or `default`.
    pub scene: String,
    pub title: String,
    pub adapter: String,
    pub backend: String,
    pub width: u32,
    pub height: u32,
    /// Processes and timed frames per process (0 frames: untimed).
    pub repeats: u32,
    pub frames: u32,
    pub timing_source: String,
    /// The protocol's least warm-up per timed block (`--warm-up-ms`);
    /// absent in untimed runs and in records older than the protocol.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warm_up_ms: Option<f64>,
    pub variants: Vec<VariantRecord>,
    pub baseline: Option<Timing>,
}

/// Pools the samples of every key over the runs' timing maps (one map a
/// run): each key's [`Stat::of_runs`].
pub fn pool(maps: &[&BTreeMap<String, Vec<f64>>]) -> Option<Timing> {
    let mut keys: Vec<&String> = maps.iter().flat_map(|m| m.keys()).collect();
    keys.sort();
    keys.dedup();
    let stat = |k: &str| {
        let runs: Vec<&[f64]> = maps
            .iter()
            .filter_map(|m| m.get(k))
            .map(Vec::as_slice)
            .collect();
        Stat::of_runs(&runs)
    };
    maps.iter().find(|m| m.contains_key("total"))?;
    let passes = keys
        .iter()
        .filter(|k| k.as_str() != "total")
        .map(|k| (k.to_string(), stat(k)))
        .collect();
    Some(Timing {
        total: stat("total"),
        passes,
        unstable: None,
        left_out: None,
    })
}

/// Where a report's times came from, in words.
pub fn timing_source(report: &common::measure::report::Report) -> String {
    match report.variants.first().map(|v| v.timing_source) {
        Some(common::measure::timing::TimingSource::GpuTimestamps) => "GPU timestamps".into(),
        Some(common::measure::timing::TimingSource::CpuWall) => "CPU wall clock per pass".into(),
        None => String::new(),
    }
}

/// An adapter as the book names it, with its backend. Mesa's two CPU
/// rasterisers both report themselves as `llvmpipe (LLVM …)`: on Vulkan
/// it is lavapipe, on GL llvmpipe. The book says lavapipe for the first
/// and gives the name it reports beside it, so that a reader who sees
/// `llvmpipe` in a report knows which one it was.
pub fn adapter_label(adapter: &str, backend: &str) -> String {
    if adapter.starts_with("llvmpipe") && backend == "Vulkan" {
        format!("lavapipe, Vulkan (it reports itself as {adapter})")
    } else {
        format!("{adapter}, {backend}")
    }
}

impl Record {
    /// The adapter and backend, as the book names them: [`adapter_label`].
    pub fn adapter_label(&self) -> String {
        adapter_label(&self.adapter, &self.backend)
    }

    /// `lesson_05/results`: the manifest's run id.
    pub fn id(&self) -> String {
        format!("{}/{}", self.lesson, self.run)
    }

    /// Whether the run's light has a size (lesson 10): its variants carry
    /// the soft shadow's figures, and its error is the penumbra's |ΔV|.
    pub fn soft(&self) -> bool {
        self.variants.iter().any(|v| v.soft.is_some())
    }
}

impl VariantRecord {
    /// The error a run is judged by, in %: the mean |ΔV| over the
    /// reference's penumbra for a soft shadow, else misclassified %.
    pub fn error_pct(&self) -> f64 {
        match &self.soft {
            Some(s) => 100.0 * s.penumbra_mean_abs,
            None => self.misclassified_pct,
        }
    }
}

/// Every committed record, by lesson then manifest order.
pub fn load_records(generated: &Path) -> Result<Vec<Record>> {
    RUNS.iter()
        .map(|r| {
            let path = generated.join(r.lesson).join(format!("{}.json", r.name));
            let text = std::fs::read_to_string(&path)
                .with_context(|| format!("{} is missing: run `workbook book`", path.display()))?;
            serde_json::from_str(&text).with_context(|| format!("{}: not a record", path.display()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn lavapipe_is_named_with_what_it_reports() {
        assert_eq!(
            super::adapter_label("llvmpipe (LLVM 15.0.6, 256 bits)", "Vulkan"),
            "lavapipe, Vulkan (it reports itself as llvmpipe (LLVM 15.0.6, 256 bits))"
        );
        assert_eq!(
            super::adapter_label("llvmpipe (LLVM 15.0.6, 256 bits)", "Gl"),
            "llvmpipe (LLVM 15.0.6, 256 bits), Gl"
        );
        assert_eq!(
            super::adapter_label("NVIDIA H200", "Vulkan"),
            "NVIDIA H200, Vulkan"
        );
    }

    use super::*;

    #[test]
    fn a_run_off_as_a_whole_widens_the_spread() {
        // Three runs whose frames agree within each run: the pooled
        // quartiles alone would hide the slow third run.
        let runs: [&[f64]; 3] = [
            &[10.0, 10.1, 10.2],
            &[10.0, 10.1, 10.1],
            &[13.0, 13.1, 13.2],
        ];
        let s = Stat::of_runs(&runs);
        let all: Vec<f64> = runs.iter().flat_map(|r| r.iter().copied()).collect();
        let pooled = Stat::of(&all);
        assert_eq!(s.median, pooled.median);
        assert!(pooled.q75 < 13.1 && s.q75 == 13.1, "{pooled:?} {s:?}");
        assert_eq!(s.q25, pooled.q25);
        // Runs that agree leave the interquartile range as it is.
        let same: [&[f64]; 2] = [&[1.0, 2.0, 3.0], &[1.0, 2.0, 3.0]];
        assert_eq!(
            Stat::of_runs(&same),
            Stat::of(&[1.0, 2.0, 3.0, 1.0, 2.0, 3.0])
        );
    }
}
