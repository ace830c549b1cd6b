//! The markdown of a sweep (`book/src/generated/scaling/<sweep>.md`): one
//! row a point, the slopes table, and where a variant stops.

use std::fmt::Write as _;

use common::measure::timing::FRAME;

use super::legend::{points_legend, slopes_legend, stops_legend};
use super::sweep::{distinct_variants, Sweep, SweepCurve, Unit, SIZES_TOP};
use crate::table::{count, header, pct, row, stat};

/// The .md file name of a sweep's table (in `book/src/generated/scaling/`).
pub fn table_file(sweep: &Sweep) -> String {
    format!("{}.md", sweep.name)
}

fn slope_cell(s: Option<f64>) -> String {
    s.map_or("—".into(), |s| format!("{s:.2}"))
}

pub(super) fn curve_name(sweep: &Sweep, c: &SweepCurve) -> String {
    let what = match c.unit {
        Unit::Ms if c.key == "total" => "GPU ms".to_string(),
        Unit::Ms => format!("`{}` ms", c.key),
        Unit::Count => format!("`{}`", c.key),
    };
    if distinct_variants(sweep).len() > 1 && !c.variant.contains(", ") {
        format!("`{}` {what}", c.variant)
    } else {
        what
    }
}

/// The markdown of one sweep: the header line, one row a point, then the
/// slope table.
pub fn table(sweep: &Sweep) -> String {
    let size = if sweep.width > 0 {
        format!("{}×{}", sweep.width, sweep.height)
    } else {
        "frame size: see the rows".to_string()
    };
    let mut s = format!(
        "*{} · {} · {} · median of {} frames, warmed up until they settle (the book's protocol), one process a point, [interquartile range], {}*\n\n",
        crate::record::adapter_label(&sweep.adapter, &sweep.backend),
        size,
        sweep.scene,
        sweep.frames,
        sweep.timing_source.replace('_', " ")
    );
    let multi = distinct_variants(sweep).len() > 1;
    let mut head = vec![sweep.axis.clone()];
    if multi {
        head.push("variant".into());
    }
    // The frame cost where the records have it (older ones: GPU time only).
    let has_frame = sweep.points.iter().any(|p| p.passes.contains_key(FRAME));
    if has_frame {
        head.push("frame ms".into());
    }
    head.push("GPU ms".into());
    // Passes in the frame's order, counters in the tables' order
    // (`legend.rs`), whatever order the record lists them in.
    let mut passes = sweep.passes.clone();
    passes.sort_by_key(|k| crate::legend::pass_rank(k));
    let mut counters = sweep.counters.clone();
    counters.sort_by_key(|k| crate::legend::counter_rank(k));
    head.extend(passes.iter().map(|p| format!("`{p}` ms")));
    head.extend(counters.iter().map(|c| format!("`{c}`")));
    head.push("misclassified %".into());
    s += &header(&head);
    for p in &sweep.points {
        let mut cells = vec![p.label.clone()];
        if multi {
            cells.push(format!("`{}`", p.variant));
        }
        if has_frame {
            cells.push(p.passes.get(FRAME).map_or("—".into(), stat));
        }
        cells.push(stat(&p.total));
        for k in &passes {
            cells.push(p.passes.get(k).map_or("—".into(), stat));
        }
        for k in &counters {
            cells.push(p.counters.get(k).map_or("—".into(), |&n| count(n)));
        }
        cells.push(pct(p.misclassified_pct));
        s += &row(&cells);
    }
    s += &points_legend(sweep, &head, &passes, &counters);
    s += &stops_table(sweep);
    let mut xs: Vec<f64> = sweep.points.iter().map(|p| p.x).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let top = SIZES_TOP.min(xs.len());
    let _ = write!(
        s,
        "\n*Log-log slopes against {}: least squares over every point, and over the largest {top}.*\n\n",
        sweep.axis
    );
    let head = [
        "curve".to_string(),
        "expected order".into(),
        "expected slope".into(),
        "measured slope (all points)".into(),
        format!("measured slope (largest {top})"),
    ];
    s += &header(&head);
    for c in &sweep.curves {
        s += &row(&[
            curve_name(sweep, c),
            c.expected.clone(),
            format!("{:.1}", c.expected_slope),
            slope_cell(c.slope_all),
            slope_cell(c.slope_top),
        ]);
    }
    s += &slopes_legend(sweep, &head, top);
    s
}

/// Where each variant of a sweep with stops stops: the largest size it ran
/// and the first it was left out at, with the lesson's reason.
fn stops_table(sweep: &Sweep) -> String {
    if sweep.stops.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "\n*Where each variant stops on {}: the largest {} it ran, and the lesson's line where it left the variant out.*\n\n",
        crate::record::adapter_label(&sweep.adapter, &sweep.backend),
        sweep.axis
    );
    let head = [
        "variant".to_string(),
        format!("largest {} run", sweep.axis),
        "left out at".into(),
        "why".into(),
    ];
    s += &header(&head);
    let mut variants = distinct_variants(sweep);
    for t in &sweep.stops {
        if !variants.contains(&t.variant) {
            variants.push(t.variant.clone());
        }
    }
    for v in variants {
        let largest = (sweep.points.iter())
            .filter(|p| p.variant == v)
            .max_by(|a, b| a.x.total_cmp(&b.x))
            .map_or("—".to_string(), |p| p.label.clone());
        let stop = (sweep.stops.iter())
            .filter(|t| t.variant == v)
            .min_by(|a, b| a.x.total_cmp(&b.x));
        let (at, why) = stop.map_or(("—".into(), "ran every size".into()), |t| {
            (t.label.clone(), t.why.clone())
        });
        s += &row(&[format!("`{v}`"), largest, at, why]);
    }
    s += &stops_legend(sweep, &head);
    s
}
