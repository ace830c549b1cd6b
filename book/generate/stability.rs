//! `workbook compare A B`: how well two runs of the generator agree on
//! their times. For every timed cell (each variant's frame cost and GPU
//! total, and the baseline's, in every timed record of both folders) it
//! counts the cells whose median in B lies inside A's stated spread (the
//! spread the tables print), and the other way round, and
//! lists the worst. This is how the protocol's repeatability is measured
//! (the book's using.md quotes it).

use std::path::Path;

use anyhow::{bail, Context, Result};

use crate::record::{Record, Stat, Timing};

/// One timed cell in both runs.
pub struct Cell {
    pub id: String,
    pub a: Stat,
    pub b: Stat,
}

impl Cell {
    /// B's median inside A's spread.
    pub fn b_in_a(&self) -> bool {
        self.a.q25 <= self.b.median && self.b.median <= self.a.q75
    }

    pub fn a_in_b(&self) -> bool {
        self.b.q25 <= self.a.median && self.a.median <= self.b.q75
    }

    /// How far B's median is outside A's range, in A's spreads.
    pub fn miss(&self) -> f64 {
        let iqr = (self.a.q75 - self.a.q25).max(1e-9);
        if self.b.median < self.a.q25 {
            (self.a.q25 - self.b.median) / iqr
        } else {
            (self.b.median - self.a.q75).max(0.0) / iqr
        }
    }
}

/// The timed cells both folders' records have.
pub fn cells(a: &[Record], b: &[Record]) -> Vec<Cell> {
    let mut out = Vec::new();
    let mut push = |id: String, ta: &Timing, tb: &Timing| {
        if ta.stable() && tb.stable() {
            out.push(Cell {
                id: format!("{id} GPU"),
                a: ta.total,
                b: tb.total,
            });
            if ta.passes.contains_key(common::measure::timing::FRAME) {
                out.push(Cell {
                    id: format!("{id} frame"),
                    a: *ta.frame(),
                    b: *tb.frame(),
                });
            }
        }
    };
    for ra in a.iter().filter(|r| r.frames > 0) {
        let Some(rb) = b.iter().find(|r| r.id() == ra.id()) else {
            continue;
        };
        if let (Some(x), Some(y)) = (&ra.baseline, &rb.baseline) {
            push(format!("{} baseline", ra.id()), x, y);
        }
        for va in &ra.variants {
            let vb = rb.variants.iter().find(|v| v.name == va.name);
            if let (Some(x), Some(y)) = (&va.timing, vb.and_then(|v| v.timing.as_ref())) {
                push(format!("{} {}", ra.id(), va.name), x, y);
            }
        }
    }
    out
}

/// Where `compare --write` puts its table, under `book/src/generated/`.
pub const REPEATABILITY: &str = "protocol/repeatability.md";

/// Prints the comparison of two generated folders; with `write`, also the
/// table of it that the book's using.md includes.
pub fn compare(a: &Path, b: &Path, write: Option<&Path>) -> Result<()> {
    let (ra, rb) = (
        crate::record::load_records(a)?,
        crate::record::load_records(b)?,
    );
    let cells = cells(&ra, &rb);
    if cells.is_empty() {
        bail!(
            "no timed cell in common between {} and {}",
            a.display(),
            b.display()
        );
    }
    if let Some(path) = write {
        let text = table(&ra, &cells)?;
        std::fs::create_dir_all(path.parent().unwrap_or(Path::new(".")))?;
        std::fs::write(path, text)
            .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    }
    for kind in ["GPU", "frame"] {
        let of: Vec<&Cell> = cells.iter().filter(|c| c.id.ends_with(kind)).collect();
        if of.is_empty() {
            continue;
        }
        let b_in_a = of.iter().filter(|c| c.b_in_a()).count();
        let a_in_b = of.iter().filter(|c| c.a_in_b()).count();
        let overlap = of.iter().filter(|c| !c.a.differs_from(&c.b)).count();
        println!(
            "{kind}: {} cells; B's median inside A's spread: {b_in_a} ({:.0} %); A's inside B's: {a_in_b} ({:.0} %); spreads overlap: {overlap} ({:.0} %)",
            of.len(),
            100.0 * b_in_a as f64 / of.len() as f64,
            100.0 * a_in_b as f64 / of.len() as f64,
            100.0 * overlap as f64 / of.len() as f64,
        );
        let mut worst: Vec<&&Cell> = of.iter().filter(|c| !c.b_in_a()).collect();
        worst.sort_by(|x, y| y.miss().total_cmp(&x.miss()));
        for c in worst.iter().take(8) {
            println!(
                "  {}: A {:.3} [{:.3}–{:.3}], B {:.3} [{:.3}–{:.3}] ({:.1} spreads out)",
                c.id,
                c.a.median,
                c.a.q25,
                c.a.q75,
                c.b.median,
                c.b.q25,
                c.b.q75,
                c.miss()
            );
        }
    }
    Ok(())
}

/// The table using.md includes: per kind of time, the cells of the second
/// run inside the first's spread, both ways, and overlapping.
fn table(a: &[Record], cells: &[Cell]) -> Result<String> {
    let first = a.iter().find(|r| r.frames > 0).context("no timed record")?;
    let mut s = format!(
        "*{} · {}×{} · two runs of `workbook book`, each {} processes × {} frames a variant, compared by `workbook compare`*\n\n",
        first.adapter_label(),
        first.width,
        first.height,
        first.repeats,
        first.frames
    );
    let head = [
        "time".to_string(),
        "timed cells".into(),
        "2nd run's median inside the 1st's spread".into(),
        "1st inside the 2nd's".into(),
        "spreads overlap".into(),
    ];
    s += &crate::table::header(&head);
    for (kind, name) in [("frame", "frame cost"), ("GPU", "GPU total")] {
        let of: Vec<&Cell> = cells.iter().filter(|c| c.id.ends_with(kind)).collect();
        if of.is_empty() {
            continue;
        }
        let share = |n: usize| format!("{n} ({:.0} %)", 100.0 * n as f64 / of.len() as f64);
        s += &crate::table::row(&[
            name.into(),
            of.len().to_string(),
            share(of.iter().filter(|c| c.b_in_a()).count()),
            share(of.iter().filter(|c| c.a_in_b()).count()),
            share(of.iter().filter(|c| !c.a.differs_from(&c.b)).count()),
        ]);
    }
    s += &crate::legend::legend_own(&head, REPEATABILITY_LEGEND);
    Ok(s)
}

/// The repeatability table's own columns.
const REPEATABILITY_LEGEND: &[(&str, &str)] = &[
    ("time", "which time of each cell: the frame cost (wall clock, from the start of recording to the GPU's completion) or the GPU total (the GPU's time for the whole frame)"),
    ("timed cells", "the cells timed in both runs with times that can be quoted: every variant's and every no-shadow baseline's, in every timed record"),
    ("2nd run's median inside the 1st's spread", "the cells whose median in the second run lies inside the spread the first run's table prints for it, [low–high] inclusive; in parentheses, their share of the timed cells"),
    ("1st inside the 2nd's", "the same the other way round: the first run's median inside the second's spread"),
    ("spreads overlap", "the cells whose two spreads overlap, so that the tables would see no measurable difference between the two runs; in parentheses, their share"),
];
