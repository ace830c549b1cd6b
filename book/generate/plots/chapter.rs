//! One chapter's error-vs-time plot (`figures/lesson_NN/error_vs_time.svg`):
//! every variant labelled, the Pareto front, the no-shadow baseline.

use std::path::Path;

use anyhow::{Context, Result};

use super::draw::Marker;
use super::legend::{LegendRow, Swatch};
use super::tradeoff::{pareto_front, tradeoff_plot, PlottedSeries, Series};
use super::{COLOURS, GREY};

/// One chapter's error-vs-time plot: x = median ms with a horizontal error bar
/// [ms_low, ms_high]; y = the series' error (misclassified %, or a soft
/// shadow's penumbra mean |ΔV| %) on a log axis (values below `floor`
/// are drawn at `floor`, e.g. 1e-3, and the plot says so on a line there);
/// every point labelled with its variant; the Pareto front drawn as a step
/// line, its points filled and the dominated ones hollow; an optional vertical
/// dashed line at the no-shadow baseline time, labelled "no shadows".
pub fn error_vs_time(
    path: &Path,
    title: &str,
    series: &Series,
    baseline_ms: Option<f64>,
    floor: f64,
) -> Result<()> {
    let colour = COLOURS[0];
    let front = pareto_front(&series.points);
    let mut legend = vec![
        LegendRow {
            swatch: Swatch::Marker(Marker::Circle, colour, true),
            text: "Pareto-optimal (no variant faster and more exact)".into(),
        },
        LegendRow {
            swatch: Swatch::Marker(Marker::Circle, colour, false),
            text: "dominated".into(),
        },
        LegendRow {
            swatch: Swatch::Line(colour, false),
            text: "Pareto front".into(),
        },
    ];
    if baseline_ms.is_some() {
        legend.push(LegendRow {
            swatch: Swatch::Line(GREY, true),
            text: "no shadows (baseline time)".into(),
        });
    }
    let plotted = PlottedSeries {
        series,
        colour,
        marker: Marker::Circle,
        front,
        label_all: true,
    };
    tradeoff_plot(path, title, &[plotted], baseline_ms, floor, legend)
        .with_context(|| format!("error-vs-time plot {}", path.display()))
}
