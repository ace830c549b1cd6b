//! The runs at 1920×1080 and what the shadows cost in them: each lesson's
//! report read back ([`FullHd`]), each variant's time over its no-shadow
//! frame with the least and most it can be within the spreads ([`Cost`]),
//! and whether it meets the budget ([`Verdict`]).

use std::path::Path;

use anyhow::{bail, Context, Result};
use common::measure::report::{Report, VariantReport};

use super::{BUDGET_MS, DIR, ORIGIN};
use crate::origins::changed;
use crate::record::Stat;

/// The runs at 1920×1080: one report a lesson, in lesson order.
pub struct FullHd {
    /// The GPU's set name ([`Origin::set`]).
    pub set: &'static str,
    pub reports: Vec<Report>,
}

/// Reads `generated/gpu_1080p/<set>/lesson_NN/report.json` for every
/// lesson that has one.
pub fn load(generated: &Path) -> Result<FullHd> {
    let dir = generated.join(DIR).join(ORIGIN.set);
    let mut reports = Vec::new();
    let mut lessons: Vec<&str> = crate::manifest::RUNS.iter().map(|r| r.lesson).collect();
    lessons.dedup();
    for lesson in lessons {
        let path = dir.join(lesson).join("report.json");
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let r: Report = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a lesson's report", path.display()))?;
        if r.lesson != lesson {
            bail!("{}: the report of {}", path.display(), r.lesson);
        }
        reports.push(r);
    }
    Ok(FullHd {
        set: ORIGIN.set,
        reports,
    })
}

/// A time of a report: its median and interquartile range.
pub(super) fn time(
    median: &std::collections::BTreeMap<String, f64>,
    spread: &std::collections::BTreeMap<String, [f64; 2]>,
    key: &str,
) -> Option<Stat> {
    let m = *median.get(key)?;
    let [q25, q75] = spread.get(key).copied().unwrap_or([m, m]);
    Some(Stat {
        median: m,
        q25,
        q75,
    })
}

/// Whether a cost meets [`BUDGET_MS`], its spread considered.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum Verdict {
    /// At most the budget, even at the high end of its spread.
    Within,
    /// Over the budget, even at the low end of its spread.
    Over,
    /// The budget lies within its spread.
    OnTheLine,
}

/// A time over the no-shadow frame's: the medians' difference, and the
/// least and most it can be within the two spreads.
#[derive(Clone, Copy, Debug)]
pub struct Cost {
    pub median: f64,
    pub low: f64,
    pub high: f64,
}

impl Cost {
    pub(super) fn of(v: &Stat, base: &Stat) -> Cost {
        Cost {
            median: v.median - base.median,
            low: v.q25 - base.q75,
            high: v.q75 - base.q25,
        }
    }

    pub fn verdict(&self) -> Verdict {
        if self.high <= BUDGET_MS {
            Verdict::Within
        } else if self.low > BUDGET_MS {
            Verdict::Over
        } else {
            Verdict::OnTheLine
        }
    }

    /// `+0.54 ms`, or no measurable difference when the spreads overlap.
    pub(super) fn cell(&self) -> String {
        if self.low <= 0.0 && self.high >= 0.0 {
            "no measurable difference".into()
        } else {
            format!("{} ms", signed(self.median))
        }
    }
}

/// A signed time as the sentences print it: `+0.54`, `−0.19`.
pub(super) fn signed(x: f64) -> String {
    format!("{x:+.2}").replace('-', "−")
}

/// One variant of one run at 1920×1080, its times against the run's
/// no-shadow frame (`None` where a block was unstable).
pub struct Row<'a> {
    /// `01`.
    pub lesson: String,
    pub variant: &'a VariantReport,
    pub gpu: Option<Stat>,
    pub base_gpu: Option<Stat>,
    pub gpu_cost: Option<Cost>,
    pub frame_cost: Option<Cost>,
    pub cpu: Option<Stat>,
}

/// The rows of one report, less the variants changed since [`ORIGIN`];
/// and the names of those left out.
pub fn rows(r: &Report) -> (Vec<Row<'_>>, Vec<&str>) {
    let lesson = r.lesson.replace("lesson_", "");
    let base = r.baseline.as_ref().filter(|b| b.stable());
    let base_time = |k: &str| base.and_then(|b| time(&b.timing_ms, &b.timing_spread_ms, k));
    let mut out = Vec::new();
    let mut left_out = Vec::new();
    for v in &r.variants {
        if changed(ORIGIN.commit, &r.lesson, &v.name).is_some() {
            left_out.push(v.name.as_str());
            continue;
        }
        let t = |k: &str| {
            v.timing_stable()
                .then(|| time(&v.timing_ms, &v.timing_spread_ms, k))
                .flatten()
        };
        let cost = |k: &str| Some(Cost::of(&t(k)?, &base_time(k)?));
        out.push(Row {
            lesson: lesson.clone(),
            variant: v,
            gpu: t("total"),
            base_gpu: base_time("total"),
            gpu_cost: cost("total"),
            frame_cost: cost(common::measure::timing::FRAME),
            cpu: t(common::measure::timing::CPU_TOTAL),
        });
    }
    (out, left_out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stat(median: f64, q25: f64, q75: f64) -> Stat {
        Stat { median, q25, q75 }
    }

    #[test]
    fn a_verdict_weighs_the_spreads() {
        let base = stat(1.0, 0.99, 1.01);
        // Well under, well over, and 0.5 ms inside the spread.
        let under = Cost::of(&stat(1.3, 1.29, 1.31), &base);
        let over = Cost::of(&stat(1.6, 1.59, 1.61), &base);
        let line = Cost::of(&stat(1.5, 1.45, 1.55), &base);
        assert_eq!(under.verdict(), Verdict::Within);
        assert_eq!(over.verdict(), Verdict::Over);
        assert_eq!(line.verdict(), Verdict::OnTheLine);
        // Overlapping spreads: no measurable difference, even below zero.
        assert_eq!(
            Cost::of(&stat(0.99, 0.9, 1.1), &base).cell(),
            "no measurable difference"
        );
        assert_eq!(Cost::of(&stat(0.8, 0.79, 0.81), &base).cell(), "−0.20 ms");
    }
}
