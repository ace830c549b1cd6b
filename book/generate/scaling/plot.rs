//! A sweep's two log-log plots (`book/src/figures/scaling/<sweep>_{time,counters}.svg`).

use std::path::Path;

use anyhow::Result;

use super::sweep::{value, Sweep, Unit};
use super::table::curve_name;
use crate::plots::{self, Curve};

/// The sweep's two log-log plots: times, and counters.
pub(super) fn plot(sweep: &Sweep, x_label: &str, figures: &Path) -> Result<()> {
    for (unit, suffix, y_label) in [
        (Unit::Ms, "time", "median ms (log)"),
        (Unit::Count, "counters", "count per frame (log)"),
    ] {
        let curves: Vec<Curve> = sweep
            .curves
            .iter()
            .filter(|c| c.unit == unit)
            .filter_map(|c| {
                let mine: Vec<&str> = c.variant.split(", ").collect();
                let (xs, ys): (Vec<f64>, Vec<f64>) = sweep
                    .points
                    .iter()
                    .filter(|p| mine.contains(&p.variant.as_str()))
                    .filter_map(|p| value(p, &c.key, unit).map(|y| (p.x, y)))
                    .filter(|&(_, y)| y > 0.0)
                    .unzip();
                (!xs.is_empty()).then(|| Curve {
                    name: curve_name(sweep, c).replace('`', ""),
                    xs,
                    ys,
                    expected: c.expected.clone(),
                })
            })
            .collect();
        if curves.is_empty() {
            continue;
        }
        let what = if unit == Unit::Ms { "time" } else { "counters" };
        let title = format!("{}: {what}", sweep.title);
        let path = figures.join(format!("{}_{suffix}.svg", sweep.name));
        plots::scaling_plot(&path, &title, x_label, y_label, &curves)?;
    }
    Ok(())
}
