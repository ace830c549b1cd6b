//! The choosing chapter's GPU cost table: each lesson's recommended
//! variants on an NVIDIA H100 at 1920×1080, each lesson run alone through
//! its own timing protocol (variants warmed up until their frames settle,
//! timed between blocks of the no-shadow frame), against the half
//! millisecond over the no-shadow frame a shadow technique should cost on
//! such a GPU. The runs are the lessons' own reports, copied unedited
//! under `book/src/generated/gpu_1080p/<set>/lesson_NN/report.json`, of
//! the code of commit [`ORIGIN`]: a variant changed since
//! ([`crate::origins::CHANGES`]) is left out of the table and named under it.
//! A row whose variant is not its lesson's most accurate (the families
//! table's) says why in its own cell; the generator fails on a row with no
//! reason (`table::NOT_THE_MOST_ACCURATE`).
//!
//! Also written here: the sentences that say which variants meet the half
//! millisecond (`choosing/gpu_budget.md`) and each lesson's lines for its
//! chapter ([`sentences::lesson_lines`]).
//!
//! This file holds whose runs they are and the budget, and writes the
//! pages; [`costs`] reads the runs and weighs each cost against the budget,
//! [`table`] makes the table, [`sentences`] the sentences.

mod costs;
mod sentences;
mod table;

use std::path::Path;

use anyhow::{bail, Context, Result};

use crate::origins::Origin;
use crate::record::Record;
pub use costs::load;
use sentences::budget;
pub use sentences::lesson_lines;
use table::table;

/// What a shadow technique may cost over the no-shadow frame on a GPU like
/// the H100 at 1920×1080.
pub const BUDGET_MS: f64 = 0.5;

/// The folder of the runs at 1920×1080, under `book/src/generated/`.
pub const DIR: &str = "gpu_1080p";

/// Whose runs they are: the GPU's set name, the commit, the day.
pub const ORIGIN: Origin = Origin {
    set: "nvidia-h100-80gb-hbm3-vulkan",
    commit: "d7678c5",
    measured: "2026-11-26",
};

/// Writes `choosing/gpu_costs.md` and `choosing/gpu_budget.md`.
pub fn write(_root: &Path, generated: &Path, records: &[Record]) -> Result<()> {
    let full = load(generated)?;
    if full.reports.is_empty() {
        bail!(
            "no runs at 1920×1080 under {}",
            generated.join(DIR).join(ORIGIN.set).display()
        );
    }
    let sets = crate::origins::load_sets(generated)?;
    let note = crate::gpus::set_note(ORIGIN.set, &sets);
    let files = [
        ("gpu_costs.md", table(&full, records, note.as_deref())?),
        ("gpu_budget.md", budget(&full)),
    ];
    for (name, text) in files {
        let path = generated.join("choosing").join(name);
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use costs::{rows, Verdict};

    /// The committed H100 runs at 1920×1080 (commit d7678c5): which of the
    /// lessons' variants meet the half millisecond, as its README lists them.
    #[test]
    fn the_committed_runs_say_which_variants_meet_half_a_millisecond() {
        let generated = crate::repo_root().join("book/src/generated");
        let full = load(&generated).unwrap();
        assert_eq!(full.reports.len(), 10);
        let verdict = |lesson: &str, variant: &str| {
            full.reports
                .iter()
                .flat_map(|r| rows(r).0)
                .find(|x| x.lesson == lesson && x.variant.name == variant)
                .and_then(|x| x.gpu_cost)
                .map(|c| c.verdict())
        };
        for (l, v) in [
            ("02", "front_cull"),
            ("05", "zpass_cpu"),
            ("06", "zfail_selective"),
            ("07", "infinite"),
            ("08", "cull_bounds_scissor"),
        ] {
            assert_eq!(verdict(l, v), Some(Verdict::Within), "{l} {v}");
        }
        for (l, v) in [
            ("01", "res_2048"),
            ("03", "poisson_16"),
            ("04", "depth_1024"),
            ("10", "pcss"),
        ] {
            assert_eq!(verdict(l, v), Some(Verdict::Over), "{l} {v}");
        }
        // Lesson 09's shadow passes changed since d7678c5 (caster culling):
        // every variant left out.
        assert_eq!(verdict("09", "k4"), None, "09 k4");
        // Lesson 10's ports changed since d7678c5: left out, and named.
        let (_, out) = rows(
            full.reports
                .iter()
                .find(|r| r.lesson == "lesson_10")
                .unwrap(),
        );
        assert!(
            out.contains(&"bevy_pcss") && out.contains(&"threejs_vsm"),
            "{out:?}"
        );
        let text = budget(&full);
        assert!(
            text.contains("lesson 08 `cull_bounds_scissor` (−0.19 ms)"),
            "{text}"
        );
        assert!(!text.contains("bevy_pcss"), "{text}");
    }
}
