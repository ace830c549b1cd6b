//! The book's plots (issue 9): one error-vs-time chart per chapter, the
//! workbook-wide chart of every lesson's variants, and log-log scaling plots.
//!
//! SVG through plotters without any font feature: plotters writes `<text>`
//! elements and the SVG viewer lays them out, so nothing here needs font
//! files. Where label placement needs a text's size it uses an estimate per
//! character ([`draw::text_w`]). The output depends on the input only (no
//! timestamps, no random ids).
//!
//! The plots, one module a chart:
//! - [`chapter`]: one chapter's error-vs-time plot.
//! - [`workbook`]: the workbook-wide plot of every lesson's variants.
//! - [`scaling`]: log-log scaling plots and their measured slope.
//! - [`bar_chart`]: a horizontal bar chart of two values per row (chapter 09).
//!
//! And what they are drawn with:
//! - [`tradeoff`]: the points, the Pareto front and the shared error-vs-time drawing.
//! - [`axis`]: linear and log axes, their ticks and tick labels.
//! - [`chart`]: the title and the chart frame every plot starts with.
//! - [`legend`]: the legend column right of the plot.
//! - [`labels`]: label placement beside the points, or in columns with leaders.
//! - [`draw`]: pixel-space rectangles, text widths, paths and markers.

mod axis;
mod bar_chart;
mod chapter;
mod chart;
mod draw;
mod labels;
mod legend;
mod scaling;
mod tradeoff;
mod workbook;

pub use bar_chart::bars;
pub use chapter::error_vs_time;
pub use scaling::{line_fit, loglog_slope, scaling_plot, Curve, Line};
pub use tradeoff::{pareto_front, Metric, Point, Series};
pub use workbook::workbook_plot;

use plotters::style::RGBColor;

const HEIGHT: u32 = 480;
/// plotters writes `font-size = size / 1.24` into the SVG; these give 12.9,
/// 13.7, 17.7 and 12.5 px.
const TICK_FONT: f64 = 16.0;
const DESC_FONT: f64 = 17.0;
const TITLE_FONT: f64 = 22.0;
const LABEL_FONT: f64 = 15.5;
const FONT: &str = "sans-serif";
/// The canvas width of every plot: the plot and, right of it, the legend
/// column.
const WIDE: u32 = 960;
/// Space around the chart, px.
const MARGIN: f64 = 14.0;

/// Series colours (Tableau 10), in order.
const COLOURS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
const GREY: RGBColor = RGBColor(90, 90, 90);

fn min_of(it: impl Iterator<Item = f64>) -> f64 {
    it.fold(f64::INFINITY, f64::min)
}

fn max_of(it: impl Iterator<Item = f64>) -> f64 {
    it.fold(f64::NEG_INFINITY, f64::max)
}

#[cfg(test)]
mod tests;
