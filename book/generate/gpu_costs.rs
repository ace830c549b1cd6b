//! The choosing chapter's GPU cost table: each lesson's recommended
//! variants on an NVIDIA H100 at 1920×1080, each lesson run alone through
//! its own timing protocol (variants warmed up until their frames settle,
//! timed between blocks of the no-shadow frame), against the half
//! millisecond over the no-shadow frame a shadow technique should cost on
//! such a GPU. The runs are the lessons' own reports, copied unedited
//! under `book/src/generated/gpu_1080p/<set>/lesson_NN/report.json`, of
//! the code of commit [`ORIGIN`]: a variant changed since
//! ([`crate::sets::CHANGES`]) is left out of the table and named under it.
//! A row whose variant is not its lesson's most accurate (the families
//! table's) says why in its own cell; the generator fails on a row with no
//! reason ([`NOT_THE_MOST_ACCURATE`]).
//!
//! Also written here: the sentences that say which variants meet the half
//! millisecond (`choosing/gpu_budget.md`), each lesson's lines for its
//! chapter ([`lesson_lines`]), and the volume routes' table of every
//! committed set of another adapter (`choosing/volumes_build_sets.md`).

use std::path::Path;

use anyhow::{bail, Context, Result};
use common::measure::report::{Report, VariantReport};

use crate::manifest::{FAMILIES, VOLUME_BUILDS};
use crate::origins::Origin;
use crate::record::{Record, Stat};
use crate::sets;
use crate::table::{pct, row, stat};

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

/// Why a row measures another variant than its lesson's most accurate:
/// `(lesson, variant, why)`.
const NOT_THE_MOST_ACCURATE: &[(&str, &str, &str)] = &[
    ("04", "depth_1024", "hardware depth: an ordinary depth-only shadow pass, where `linear_2048` runs a fragment shader over six 2048² faces ([lesson 04](lesson_04.md))"),
    ("05", "zpass_compute", "the compute route, which tests the edges on the GPU: the route a GPU favours as the casters grow ([three ways to build the volumes](#three-ways-to-build-the-volumes))"),
    ("06", "zfail_selective", "z-fail only for the casters whose volume may hold the eye, z-pass for the rest: fewer draws than `zfail_cpu` ([lesson 06](lesson_06.md))"),
    ("07", "infinite", "the other cure for the far plane: the far plane at infinity, no depth clamp ([lesson 07](lesson_07.md))"),
    ("08", "bounds_scissor", "the decision table's pick: the bounds cut each light's fill to its range ([lesson 08](lesson_08.md#counting-the-work))"),
    ("08", "cull_bounds_scissor", "`bounds_scissor` with the cull: a caster whose bounding sphere misses the light's range casts no volume ([lesson 08](lesson_08.md#counting-the-work))"),
    ("09", "k4", "the decision table's pick: the snapped sphere does not shimmer, where `k4_aabb`'s box follows the camera and does ([lesson 09](lesson_09.md#shimmer-along-a-camera-path))"),
    ("10", "hard_pcf", "lesson 03's rotated 16-tap Poisson disk, no light size: the hard shadow's edge, filtered ([lesson 10](lesson_10.md))"),
    ("10", "pcf_wide_16", "PCSS's 16 filter taps on a fixed 8-texel disk, one width everywhere: what PCSS's blocker search sizes per pixel ([lesson 10](lesson_10.md))"),
    ("10", "pcf_wide_32", "32 taps on the same disk, as many as PCSS's search and filter together ([lesson 10](lesson_10.md))"),
    ("10", "vsm", "a variance map blurred 9×9 texels: one filtered lookup a pixel ([lesson 10](lesson_10.md))"),
    ("10", "vsm_bleed_cut", "`vsm` with the cut against light bleeding ([lesson 10](lesson_10.md))"),
    ("10", "evsm", "an exponential variance map (EVSM4): `vsm`'s lookup on warped depths, the lower bound of two warps ([lesson 10](lesson_10.md))"),
];

/// The cell that says why a row's variant is measured: the lesson's most
/// accurate, or as accurate as it, or less accurate, and then why.
fn why(records: &[Record], lesson: &str, variant: &str) -> Result<String> {
    let Some(r) = crate::choosing::default_of(records, &format!("lesson_{lesson}")) else {
        bail!("no default record of lesson {lesson}");
    };
    let Some(best) = crate::choosing::most_accurate(r) else {
        bail!("lesson {lesson}'s record has no variants");
    };
    if best.name == variant {
        return Ok("the most accurate (the families table's)".into());
    }
    let Some(v) = r.variants.iter().find(|v| v.name == variant) else {
        bail!("lesson {lesson} has no variant `{variant}`");
    };
    let Some((_, _, reason)) = NOT_THE_MOST_ACCURATE
        .iter()
        .find(|(l, n, _)| *l == lesson && *n == variant)
    else {
        bail!(
            "gpu_costs: lesson {lesson}'s `{variant}` is not its most accurate (`{}`): give the \
             reason in NOT_THE_MOST_ACCURATE",
            best.name
        );
    };
    let accuracy = if v.error_pct() == best.error_pct() {
        format!(
            "as accurate as `{}` (the families table names the first of equals)",
            best.name
        )
    } else {
        format!(
            "`{}` is more accurate ({} % against {} %)",
            best.name,
            pct(best.error_pct()),
            pct(v.error_pct())
        )
    };
    Ok(format!("{accuracy}; {reason}"))
}

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
fn time(
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
    fn of(v: &Stat, base: &Stat) -> Cost {
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
    fn cell(&self) -> String {
        if self.low <= 0.0 && self.high >= 0.0 {
            "no measurable difference".into()
        } else {
            format!("{} ms", signed(self.median))
        }
    }
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
        if sets::changed(ORIGIN.commit, &r.lesson, &v.name).is_some() {
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

fn caption(full: &FullHd) -> String {
    let Some(r) = full.reports.first() else {
        return String::new();
    };
    let warm = r.timing_protocol.as_ref().map_or(String::new(), |p| {
        format!(
            " (≥ {:.0} ms, until its frame times settle)",
            p.warm_up_min_ms
        )
    });
    format!(
        "*{}, {} · {}×{} · the default scenes · the code of commit `{}` (measured {}) · each lesson alone, its variants warmed up{warm} and timed, {} frames each, between blocks of the no-shadow frame · GPU ms from timestamps: median [spread: the frames' interquartile range]*\n\n",
        r.adapter.name, r.adapter.backend, r.width, r.height, ORIGIN.commit, ORIGIN.measured, r.frames
    )
}

fn verdict_cell(c: Option<Cost>) -> String {
    match c.map(|c| c.verdict()) {
        Some(Verdict::Within) => "yes".into(),
        Some(Verdict::Over) => "no".into(),
        Some(Verdict::OnTheLine) => "on the line".into(),
        None => "—".into(),
    }
}

/// The table.
pub fn table(full: &FullHd, records: &[Record]) -> Result<String> {
    let mut s = caption(full);
    let head = [
        "lesson".to_string(),
        "variant".into(),
        "GPU ms".into(),
        "no shadows, GPU ms".into(),
        "shadows cost, GPU".into(),
        format!("within {BUDGET_MS} ms?"),
        "shadows cost, frame".into(),
        "CPU ms".into(),
        "why this variant".into(),
    ];
    s += &row(&head);
    s += &row(&vec!["---".to_string(); head.len()]);
    let mut notes = String::new();
    for r in &full.reports {
        let (rows, left_out) = rows(r);
        for x in &rows {
            let unstable = || "unstable".to_string();
            s += &row(&[
                format!("[{}]({}.md)", x.lesson, r.lesson),
                format!("`{}`", x.variant.name),
                x.gpu.as_ref().map_or_else(unstable, stat),
                x.base_gpu.as_ref().map_or_else(unstable, stat),
                x.gpu_cost.map_or_else(unstable, |c| c.cell()),
                verdict_cell(x.gpu_cost),
                x.frame_cost.map_or_else(unstable, |c| c.cell()),
                x.cpu.as_ref().map_or("—".into(), stat),
                why(records, &x.lesson, &x.variant.name)?,
            ]);
        }
        let whose = format!("lesson {}'s", &r.lesson[7..]);
        // Times only: what the errors are measured against does not matter.
        notes += &sets::changes_note(ORIGIN.commit, &r.lesson, &left_out, false, Some(&whose));
    }
    let within = format!(
        "`yes` where the shadows' GPU cost is at most {BUDGET_MS} ms even at the high end of its spread (the variant's third quartile less the no-shadow frame's first), what a shadow technique may cost on such a GPU at 1920×1080; `no` where it is over {BUDGET_MS} ms even at the low end; `on the line` where {BUDGET_MS} ms lies within its spread"
    );
    let own = [
        ("lesson", "the lesson, on its default scene, linked to its chapter"),
        ("variant", "the lesson's variant: its most accurate (the families table's), or another where the last column says why"),
        ("GPU ms", "the GPU's time for the whole frame, first timestamp to last: median [spread], ms"),
        ("no shadows, GPU ms", "the same for the lesson's no-shadow baseline (the scene drawn without shadows), timed in the blocks between the variants: median [spread], ms"),
        ("shadows cost, GPU", "GPU ms − no shadows, GPU ms (medians): what the shadows add to the GPU's frame; no measurable difference where the two spreads overlap"),
        (head[5].as_str(), within.as_str()),
        ("shadows cost, frame", "the same for the frame's wall clock, from the start of recording to the GPU's completion, which counts the CPU's work (a silhouette found on the CPU, culling, recording): frame ms − the no-shadow frame's (medians); no measurable difference where the two spreads overlap"),
        ("CPU ms", "the CPU's time to record and submit the frame, waits for the GPU left out (`cpu_total`): median [spread], ms"),
        ("why this variant", "whether the variant is the lesson's most accurate on today's records (the families table's) and, where it is not, why the row measures it"),
    ];
    s += &crate::legend::legend_own(&head, &own);
    s += &notes;
    Ok(s)
}

/// A signed time as the sentences print it: `+0.54`, `−0.19`.
fn signed(x: f64) -> String {
    format!("{x:+.2}").replace('-', "−")
}

/// `lesson 05 `zpass_cpu` (+0.22 ms)`.
fn named(x: &Row, c: Cost) -> String {
    format!(
        "lesson {} `{}` ({} ms)",
        x.lesson,
        x.variant.name,
        signed(c.median)
    )
}

/// `a`, `a and b`, `a, b and c`.
fn and_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// `lesson 02`, `lessons 05, 06 and 07`.
fn lessons(ns: &[String]) -> String {
    match ns.len() {
        1 => format!("lesson {}", ns[0]),
        _ => format!("lessons {}", and_list(ns)),
    }
}

/// List items, the last ending the sentence.
fn items(lines: &[String]) -> String {
    let mut s = String::new();
    for (i, l) in lines.iter().enumerate() {
        let end = if i + 1 == lines.len() { '.' } else { ';' };
        s += &format!("- {l}{end}\n");
    }
    s
}

/// One family's line: its lessons with a variant within the budget, and
/// the others with their least costly variant.
fn family_line(family: &str, members: &[&str], all: &[Row]) -> Option<String> {
    let mut yes: Vec<String> = Vec::new();
    let mut no: Vec<(String, String)> = Vec::new();
    for lesson in members {
        let n = lesson.trim_start_matches("lesson_");
        let mine: Vec<(&Row, Cost)> = all
            .iter()
            .filter(|x| x.lesson == n)
            .filter_map(|x| Some((x, x.gpu_cost?)))
            .collect();
        if mine.iter().any(|(_, c)| c.verdict() == Verdict::Within) {
            yes.push(n.to_string());
        } else if let Some((x, c)) = mine.iter().min_by(|a, b| a.1.median.total_cmp(&b.1.median)) {
            no.push((
                n.to_string(),
                format!("`{}` {} ms", x.variant.name, signed(c.median)),
            ));
        }
    }
    if yes.is_empty() && no.is_empty() {
        return None;
    }
    let ns: Vec<String> = members
        .iter()
        .map(|l| l.trim_start_matches("lesson_").to_string())
        .collect();
    let span = match ns.as_slice() {
        [one] => format!("lesson {one}"),
        [first, .., last] => format!("lessons {first}–{last}"),
        [] => String::new(),
    };
    let least = |no: &[(String, String)]| -> String {
        match no {
            [(_, v)] => format!("none (its least costly: {v})"),
            _ => {
                let ns: Vec<String> = no.iter().map(|(n, _)| n.clone()).collect();
                let vs: Vec<String> = no.iter().map(|(_, v)| v.clone()).collect();
                format!(
                    "none in lessons {} (their least costly: {})",
                    and_list(&ns),
                    and_list(&vs)
                )
            }
        }
    };
    let text = match (yes.is_empty(), no.is_empty()) {
        (false, true) if yes.len() > 1 => "every lesson".to_string(),
        (false, true) => lessons(&yes),
        (true, _) => least(&no),
        (false, false) => format!("{}; {}", lessons(&yes), least(&no)),
    };
    Some(format!("{family} ({span}): {text}"))
}

/// The sentences that say which variants meet [`BUDGET_MS`], by variant
/// and by family, and why a cost can be below zero or the frame's over
/// the budget where the GPU's is not.
pub fn budget(full: &FullHd) -> String {
    let Some(first) = full.reports.first() else {
        return String::new();
    };
    let all: Vec<Row> = full.reports.iter().flat_map(|r| rows(r).0).collect();
    let with = |v: Verdict| -> Vec<String> {
        all.iter()
            .filter_map(|x| Some((x, x.gpu_cost?)))
            .filter(|(_, c)| c.verdict() == v)
            .map(|(x, c)| named(x, c))
            .collect()
    };
    let mut s = format!(
        "On the {} at {}×{}, the shadows' GPU time over the no-shadow frame (the table above):\n\n",
        first.adapter.name, first.width, first.height
    );
    let mut lines = Vec::new();
    for (v, what) in [
        (Verdict::Within, format!("within {BUDGET_MS} ms")),
        (Verdict::Over, format!("over {BUDGET_MS} ms")),
        (
            Verdict::OnTheLine,
            format!("on the line ({BUDGET_MS} ms lies within the spread)"),
        ),
    ] {
        let names = with(v);
        if !names.is_empty() {
            lines.push(format!("**{what}**: {}", and_list(&names)));
        }
    }
    s += &items(&lines);
    s += &format!("\nBy family, the lessons with a variant within {BUDGET_MS} ms:\n\n");
    let lines: Vec<String> = FAMILIES
        .iter()
        .filter_map(|(family, members)| family_line(family, members, &all))
        .collect();
    s += &items(&lines);
    let gpu_within = || {
        all.iter()
            .filter(|x| x.gpu_cost.is_some_and(|c| c.verdict() == Verdict::Within))
            .filter_map(|x| Some((x, x.frame_cost?)))
    };
    let frame_over: Vec<String> = gpu_within()
        .filter(|(_, c)| c.verdict() == Verdict::Over)
        .map(|(x, c)| named(x, c))
        .collect();
    let frame_line: Vec<String> = gpu_within()
        .filter(|(_, c)| c.verdict() == Verdict::OnTheLine)
        .map(|(x, c)| named(x, c))
        .collect();
    if !frame_over.is_empty() || !frame_line.is_empty() {
        let mut lines = Vec::new();
        if !frame_over.is_empty() {
            lines.push(format!("over {BUDGET_MS} ms: {}", and_list(&frame_over)));
        }
        if !frame_line.is_empty() {
            lines.push(format!(
                "on the line ({BUDGET_MS} ms within the spread): {}",
                and_list(&frame_line)
            ));
        }
        s += &format!(
            "\nWhere the GPU's time is within {BUDGET_MS} ms, the frame's, which counts the CPU's work too, need not be (the frame's cost in brackets):\n\n{}",
            items(&lines)
        );
    }
    for x in &all {
        let Some(c) = x.gpu_cost.filter(|c| c.high < 0.0) else {
            continue;
        };
        let r = full
            .reports
            .iter()
            .find(|r| r.lesson.ends_with(&x.lesson))
            .and_then(|r| r.baseline.as_ref());
        let Some(b) = r else {
            continue;
        };
        let quicker: Vec<String> = x
            .variant
            .timing_ms
            .keys()
            .filter(|k| !["total", "frame"].contains(&k.as_str()) && !k.starts_with("cpu"))
            .filter_map(|k| {
                let v = time(&x.variant.timing_ms, &x.variant.timing_spread_ms, k)?;
                let base = time(&b.timing_ms, &b.timing_spread_ms, k)?;
                (v.q75 < base.q25).then(|| {
                    format!(
                        "`{k}` takes {:.2} ms against the no-shadow frame's {:.2} ms",
                        v.median, base.median
                    )
                })
            })
            .collect();
        s += &format!(
            "\nBelow the no-shadow frame: lesson {} `{}` ({} ms of GPU time), where {}.\n",
            x.lesson,
            x.variant.name,
            signed(c.median),
            if quicker.is_empty() {
                "no pass alone is measurably quicker".into()
            } else {
                quicker.join(", ")
            }
        );
    }
    s
}

/// A lesson's lines for its chapter, under its set's tables: each variant
/// at 1920×1080, its shadows' GPU and frame cost and whether it meets the
/// budget; and the variants left out (changed since [`ORIGIN`]).
pub fn lesson_lines(full: &FullHd, lesson: &str) -> (String, Vec<String>) {
    let Some(r) = full.reports.iter().find(|r| r.lesson == lesson) else {
        return (String::new(), Vec::new());
    };
    let (rows, left_out) = rows(r);
    let mut s = format!(
        "\nAt {}×{} on the same GPU, the code of commit `{}`: the lesson run alone through its protocol, {} frames a variant (with every lesson's, against the half millisecond a shadow technique should cost there, in [Choosing a technique](choosing.md#on-a-gpu)):\n\n",
        r.width, r.height, ORIGIN.commit, r.frames
    );
    for x in &rows {
        let gpu = x.gpu_cost.map_or("unstable".into(), |c| c.cell());
        let frame = x.frame_cost.map_or("unstable".into(), |c| c.cell());
        let verdict = match x.gpu_cost.map(|c| c.verdict()) {
            Some(Verdict::Within) => format!("within {BUDGET_MS} ms"),
            Some(Verdict::Over) => format!("over {BUDGET_MS} ms"),
            Some(Verdict::OnTheLine) => format!("{BUDGET_MS} ms within its spread"),
            None => "—".into(),
        };
        s += &format!(
            "- `{}`: shadows {gpu} of GPU time ({verdict}); {frame} of frame time, the CPU's work included\n",
            x.variant.name
        );
    }
    (s, left_out.into_iter().map(String::from).collect())
}

/// Every other set's table of the three ways to build the volumes
/// ([`crate::choosing::volumes_build`] on the set's records), less the
/// variants changed since the set's commit.
pub fn volumes_build_sets(generated: &Path) -> Result<String> {
    let mut s = String::new();
    for (name, records) in sets::load_sets(generated)? {
        let commit = sets::origin(&name).map(|o| o.commit);
        let mut left_out = Vec::new();
        let mine: Vec<Record> = records
            .iter()
            .filter(|r| VOLUME_BUILDS.iter().any(|(id, _)| *id == r.id()))
            .map(|r| {
                let mut r = r.clone();
                r.variants.retain(|v| {
                    let gone =
                        commit.is_some_and(|c| sets::changed(c, &r.lesson, &v.name).is_some());
                    if gone && !left_out.contains(&v.name) {
                        left_out.push(v.name.clone());
                    }
                    !gone
                });
                r
            })
            .collect();
        if mine.is_empty() {
            continue;
        }
        if !s.is_empty() {
            s += "\n";
        }
        s += &match sets::origin(&name) {
            Some(o) => format!(
                "**The code of commit `{}`** (measured {})\n\n",
                o.commit, o.measured
            ),
            None => String::new(),
        };
        s += &crate::choosing::volumes_build(&mine);
        if let Some(c) = commit {
            let names: Vec<&str> = left_out.iter().map(String::as_str).collect();
            s += &sets::changes_note(c, "lesson_05", &names, false, None);
        }
    }
    if s.is_empty() {
        s = "*No set of another adapter has lesson 05's runs.*\n".into();
    }
    Ok(s)
}

/// Writes `choosing/gpu_costs.md`, `choosing/gpu_budget.md` and
/// `choosing/volumes_build_sets.md`.
pub fn write(_root: &Path, generated: &Path, records: &[Record]) -> Result<()> {
    let full = load(generated)?;
    if full.reports.is_empty() {
        bail!(
            "no runs at 1920×1080 under {}",
            generated.join(DIR).join(ORIGIN.set).display()
        );
    }
    let files = [
        ("gpu_costs.md", table(&full, records)?),
        ("gpu_budget.md", budget(&full)),
        ("volumes_build_sets.md", volumes_build_sets(generated)?),
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
        assert_eq!(
            and_list(&["a".into(), "b".into(), "c".into()]),
            "a, b and c"
        );
    }

    /// The committed H100 runs at 1920×1080 (commit d7678c5): which of the
    /// lessons' variants meet the half millisecond, as its README lists them.
    #[test]
    fn the_committed_runs_say_which_variants_meet_half_a_millisecond() {
        let generated = Path::new(env!("CARGO_MANIFEST_DIR")).join("book/src/generated");
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
            ("09", "k4"),
            ("10", "pcss"),
        ] {
            assert_eq!(verdict(l, v), Some(Verdict::Over), "{l} {v}");
        }
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
