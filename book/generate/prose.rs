//! Measured figures inside the chapters' sentences, written by the
//! generator. A chapter never types a number a run produced: it names the
//! record cell, and `workbook book` / `workbook tables` writes the value
//! between the markers (invisible in the rendered book). A sentence that
//! compares figures carries a claim the generator checks on the same
//! records (`crate::claims`):
//!
//! ```text
//! <!--fig:lesson_07/results:clamp:misclassified_pct-->1.889 %<!--/fig-->
//! ```
//!
//! The key is `RUN:VARIANT:FIELD`: `RUN` a record under
//! `book/src/generated/` (`lesson_07/results` for `lesson_07/results.json`),
//! `VARIANT` a variant's name (or `baseline` for the no-shadow frame), and
//! `FIELD` one of
//!
//! - `misclassified_pct`, `false_shadow_pct`, `false_lit_pct`: `1.889 %`;
//! - `mean_abs`: mean |ΔV| as the tables print it, `0.123 %`;
//! - a soft shadow's (lesson 10) `penumbra_mean_abs` (as the tables print
//!   it, `3.210 %`), `light_bleeding_pct`, `umbra_misclassified_pct`,
//!   `penumbra_pixels`, `umbra_pixels`, and its per-class figures as the
//!   classes table prints them: `umbra_mean_abs`, `lit_mean_abs`,
//!   `spill_mean_abs` (`0.657 %`), `leak_pct` (`0.452 %`) and
//!   `penumbra_width_error_px` (`0.61 px`);
//! - a counter's name: `37 390`;
//! - `frame`, `cpu_total` or a pass (`lighting`, `volume`, ...): its median,
//!   `12.4 ms`;
//! - `cost`: the frame's time over the no-shadow baseline's, `+5.1 ms`, or
//!   `no measurable difference` when their spreads overlap.
//!
//! `tests/book_prose.rs` fails when a chapter's marked value is not the
//! record's, and when a sentence quotes a measured-looking figure that is
//! neither marked nor in the chapter's included generated output.

use std::path::Path;

use anyhow::{bail, Context, Result};

use crate::record::{Record, Stat};
use crate::table::{count, ms, pct};

/// Opens a marker: `<!--fig:KEY-->`.
pub const OPEN: &str = "<!--fig:";
/// Closes a marker's value.
pub const CLOSE: &str = "<!--/fig-->";

/// The text with every marker's value written from `lookup(key)`.
pub fn fill(text: &str, lookup: &mut dyn FnMut(&str) -> Result<String>) -> Result<String> {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(OPEN) {
        let line = text[..text.len() - rest.len() + at].lines().count().max(1);
        out.push_str(&rest[..at]);
        let after = &rest[at + OPEN.len()..];
        let Some(end_key) = after.find("-->") else {
            bail!("line {line}: a `{OPEN}` marker without `-->`");
        };
        let key = &after[..end_key];
        let value_start = &after[end_key + 3..];
        let Some(end_value) = value_start.find(CLOSE) else {
            bail!("line {line}: the marker `{key}` has no `{CLOSE}`");
        };
        if value_start[..end_value].contains('\n') || value_start[..end_value].contains(OPEN) {
            bail!("line {line}: the marker `{key}` is not closed on its own line");
        }
        let value = lookup(key).with_context(|| format!("line {line}: `{key}`"))?;
        out.push_str(OPEN);
        out.push_str(key);
        out.push_str("-->");
        out.push_str(&value);
        out.push_str(CLOSE);
        rest = &value_start[end_value + CLOSE.len()..];
    }
    out.push_str(rest);
    Ok(out)
}

/// The value of one key, read from the records under `generated`.
pub fn lookup(generated: &Path, key: &str) -> Result<String> {
    let (record, variant, field) = read(generated, key)?;
    value(&record, variant, field)
}

/// A key's record, variant and field: `RUN:VARIANT:FIELD`.
pub fn read<'k>(generated: &Path, key: &'k str) -> Result<(Record, &'k str, &'k str)> {
    let mut parts = key.split(':');
    let (Some(run), Some(variant), Some(field), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        bail!("a key is RUN:VARIANT:FIELD");
    };
    let path = generated.join(format!("{run}.json"));
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("no record {}", path.display()))?;
    let record: Record =
        serde_json::from_str(&text).with_context(|| format!("{}: not a record", path.display()))?;
    Ok((record, variant, field))
}

/// What one field of one variant measures, before it is formatted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Measured {
    /// A percentage, as the tables print it (`1.889` for `1.889 %`).
    Pct(f64),
    /// A count.
    Count(u64),
    /// A distance in pixels, as the tables print it (`0.61` for `0.61 px`).
    Pixels(f64),
    /// A time: its median and spread, in milliseconds.
    Time(Stat),
    /// The frame's time over the no-shadow baseline's.
    Cost { frame: Stat, baseline: Stat },
}

impl Measured {
    /// The figure as a number: the percentage, the count, the median, the
    /// difference of the medians.
    pub fn number(&self) -> f64 {
        match *self {
            Measured::Pct(x) | Measured::Pixels(x) => x,
            Measured::Count(n) => n as f64,
            Measured::Time(s) => s.median,
            Measured::Cost { frame, baseline } => frame.median - baseline.median,
        }
    }
}

/// One field of one variant of a record, formatted as the tables print it.
pub fn value(record: &Record, variant: &str, field: &str) -> Result<String> {
    Ok(match measure(record, variant, field)? {
        Measured::Pct(x) => format!("{} %", pct(x)),
        Measured::Count(n) => count(n),
        Measured::Pixels(x) => format!("{x:.2} px"),
        Measured::Time(s) => format!("{} ms", ms(s.median)),
        Measured::Cost { frame, baseline } => {
            if frame.differs_from(&baseline) {
                format!("{:+.1} ms", frame.median - baseline.median)
            } else {
                "no measurable difference".into()
            }
        }
    })
}

/// One field of one variant of a record, as a number (with its spread
/// when it is a time).
pub fn measure(record: &Record, variant: &str, field: &str) -> Result<Measured> {
    let timing = |name: &str| {
        if name == "baseline" {
            return record.baseline.as_ref();
        }
        record
            .variants
            .iter()
            .find(|v| v.name == name)
            .and_then(|v| v.timing.as_ref())
    };
    if variant == "baseline" || ["frame", "cost"].contains(&field) || is_pass(record, field) {
        let Some(t) = timing(variant) else {
            bail!("no times for `{variant}` in the record");
        };
        if !t.stable() {
            bail!("`{variant}`'s times are not quotable: {:?}", t.unstable);
        }
        if field == "cost" {
            let Some(base) = record.baseline.as_ref() else {
                bail!("no baseline in the record");
            };
            return Ok(Measured::Cost {
                frame: *t.frame(),
                baseline: *base.frame(),
            });
        }
        let stat = if field == "frame" {
            Some(t.frame())
        } else {
            t.passes.get(field)
        };
        let Some(stat) = stat else {
            bail!("no time `{field}` for `{variant}`");
        };
        return Ok(Measured::Time(*stat));
    }
    let Some(v) = record.variants.iter().find(|v| v.name == variant) else {
        bail!("no variant `{variant}` in the record");
    };
    Ok(match field {
        "misclassified_pct" => Measured::Pct(v.misclassified_pct),
        "false_shadow_pct" => Measured::Pct(v.false_shadow_pct),
        "false_lit_pct" => Measured::Pct(v.false_lit_pct),
        "mean_abs" => Measured::Pct(100.0 * v.mean_abs),
        "penumbra_mean_abs"
        | "light_bleeding_pct"
        | "umbra_misclassified_pct"
        | "penumbra_pixels"
        | "umbra_pixels"
        | "umbra_mean_abs"
        | "lit_mean_abs"
        | "spill_mean_abs"
        | "leak_pct"
        | "penumbra_width_error_px" => {
            let Some(e) = &v.soft else {
                bail!("`{variant}` has no soft-shadow figures (its light has no size)");
            };
            match field {
                "penumbra_mean_abs" => Measured::Pct(100.0 * e.penumbra_mean_abs),
                "light_bleeding_pct" => Measured::Pct(e.light_bleeding_pct),
                "umbra_misclassified_pct" => Measured::Pct(e.umbra_misclassified_pct),
                "penumbra_pixels" => Measured::Count(e.penumbra_pixels),
                "umbra_mean_abs" => Measured::Pct(100.0 * e.umbra_mean_abs),
                "lit_mean_abs" => Measured::Pct(100.0 * e.lit_mean_abs),
                "spill_mean_abs" => Measured::Pct(100.0 * e.spill_mean_abs),
                "leak_pct" => Measured::Pct(e.leak_pct),
                "penumbra_width_error_px" => match e.penumbra_width_error_px {
                    Some(w) => Measured::Pixels(w),
                    None => bail!("`{variant}` has no penumbra width error (a contour is missing)"),
                },
                _ => Measured::Count(e.umbra_pixels),
            }
        }
        counter => match v.counters.get(counter) {
            Some(&n) => Measured::Count(n),
            None => bail!("`{variant}` has no field or counter `{counter}`"),
        },
    })
}

/// Whether `field` names a timed pass of some variant in the record.
fn is_pass(record: &Record, field: &str) -> bool {
    record
        .variants
        .iter()
        .filter_map(|v| v.timing.as_ref())
        .any(|t| t.passes.contains_key(field))
}

/// The chapters under `src` (not the generated files), sorted.
pub fn chapters(src: &Path) -> Result<Vec<std::path::PathBuf>> {
    let mut out = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).with_context(|| format!("{}", dir.display()))? {
            let p = e?.path();
            if p.is_dir() {
                if !["generated", "figures", "katex"]
                    .iter()
                    .any(|x| p.ends_with(x))
                {
                    stack.push(p);
                }
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Rewrites every chapter under `src` (not the generated files) with its
/// markers' values from `generated`; returns the chapters changed.
pub fn write_chapters(src: &Path, generated: &Path) -> Result<Vec<String>> {
    let mut changed = Vec::new();
    for p in chapters(src)? {
        let text = std::fs::read_to_string(&p)?;
        if !text.contains(OPEN) {
            continue;
        }
        let new = fill(&text, &mut |k| lookup(generated, k))
            .with_context(|| format!("{}", p.display()))?;
        if new != text {
            std::fs::write(&p, &new)?;
            changed.push(p.display().to_string());
        }
    }
    Ok(changed)
}
