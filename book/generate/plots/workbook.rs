//! The workbook-wide plot: every lesson's variants on one error-vs-time
//! chart, one colour and marker per lesson.

use std::path::Path;

use anyhow::{Context, Result};

use super::draw::Marker;
use super::legend::{LegendRow, Swatch};
use super::tradeoff::{pareto_front, tradeoff_plot, Metric, PlottedSeries, Series};
use super::COLOURS;

/// The workbook-wide plot: every lesson's variants, one colour and marker per
/// series (lesson), the same axes as [`super::error_vs_time`], a legend with the
/// lesson names; labels only on each series' Pareto points.
pub fn workbook_plot(path: &Path, title: &str, series: &[Series], floor: f64) -> Result<()> {
    let plotted: Vec<PlottedSeries> = series
        .iter()
        .enumerate()
        .map(|(i, s)| PlottedSeries {
            series: s,
            colour: COLOURS[i % COLOURS.len()],
            marker: Marker::ALL[i % Marker::ALL.len()],
            front: pareto_front(&s.points),
            label_all: false,
        })
        .collect();
    // A lesson whose error is not misclassified % names its own (the y
    // axis says so too).
    let mut legend: Vec<LegendRow> = plotted
        .iter()
        .map(|p| LegendRow {
            swatch: Swatch::LineMarker(p.marker, p.colour),
            text: match p.series.metric {
                Metric::Misclassified => p.series.name.clone(),
                m => format!("{} ({})", p.series.name, m.short()),
            },
        })
        .collect();
    legend.push(LegendRow {
        swatch: Swatch::None,
        text: "filled: on its lesson's Pareto front".into(),
    });
    tradeoff_plot(path, title, &plotted, None, floor, legend)
        .with_context(|| format!("workbook plot {}", path.display()))
}
