//! Log-log scaling plots (the scaling chapter's sweeps, chapter 09's
//! cascades) and the measured order they report, [`loglog_slope`].

use std::path::Path;

use anyhow::{anyhow, Context, Result};
use plotters::prelude::*;

use super::axis::Axis;
use super::chart::{build_chart, plot_rect, titled};
use super::draw::{draw_marker, draw_path, Marker};
use super::legend::{
    draw_legend_column, legend_column_height, legend_column_width, LegendRow, Swatch, LEGEND_GAP,
};
use super::{max_of, min_of, COLOURS, HEIGHT, WIDE};

/// One measured curve of a scaling plot, e.g. expected "O(n)".
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub name: String,
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    pub expected: String,
}

/// The least-squares slope of log(y) on log(x) (the measured order). Pairs
/// with a non-positive or non-finite value are left out; NaN when fewer than
/// two pairs remain or all their x are equal.
pub fn loglog_slope(xs: &[f64], ys: &[f64]) -> f64 {
    let logs: Vec<(f64, f64)> = xs
        .iter()
        .zip(ys)
        .filter(|(x, y)| x.is_finite() && y.is_finite() && **x > 0.0 && **y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    line_fit(&logs).map_or(f64::NAN, |l| l.slope)
}

/// A least-squares line `y = intercept + slope · x` and how well it fits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    pub slope: f64,
    pub intercept: f64,
    /// The share of y's variance the line explains (1: every point on it).
    pub r2: f64,
}

/// The least-squares line through `points` (x, y); `None` when fewer than
/// two remain or all their x are equal.
pub fn line_fit(points: &[(f64, f64)]) -> Option<Line> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = points.iter().map(|p| (p.1 - my) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let residual: f64 = points
        .iter()
        .map(|p| (p.1 - intercept - slope * p.0).powi(2))
        .sum();
    Some(Line {
        slope,
        intercept,
        r2: 1.0 - residual / syy,
    })
}

/// A log-log scaling plot: one line with markers per curve, legend entries
/// "<name>", "expected <expected>", "measured slope <s:.2>" (slope from
/// [`loglog_slope`]) in a column right of the plot. The x axis is labelled at
/// the data's x values (or at least at the first and last). Non-positive
/// values cannot be drawn and are left out.
pub fn scaling_plot(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    curves: &[Curve],
) -> Result<()> {
    let inner = || -> Result<()> {
        let good = |v: f64| v.is_finite() && v > 0.0;
        let pts: Vec<Vec<(f64, f64)>> = curves
            .iter()
            .map(|c| {
                c.xs.iter()
                    .zip(&c.ys)
                    .map(|(&x, &y)| (x, y))
                    .filter(|&(x, y)| good(x) && good(y))
                    .collect()
            })
            .collect();
        let all: Vec<(f64, f64)> = pts.iter().flatten().copied().collect();
        if all.is_empty() {
            return Err(anyhow!("no positive points to plot"));
        }
        let mut xs: Vec<f64> = all.iter().map(|p| p.0).collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        let xa = Axis::log(xs[0], xs[xs.len() - 1]).ticks_at(&xs);
        let ya = Axis::log(
            min_of(all.iter().map(|p| p.1)),
            max_of(all.iter().map(|p| p.1)),
        );

        let legend: Vec<LegendRow> = curves
            .iter()
            .enumerate()
            .map(|(i, c)| LegendRow {
                swatch: Swatch::LineMarker(
                    Marker::ALL[i % Marker::ALL.len()],
                    COLOURS[i % COLOURS.len()],
                ),
                text: if c.expected.is_empty() {
                    format!(
                        "{}\nmeasured slope {:.2}",
                        c.name,
                        loglog_slope(&c.xs, &c.ys)
                    )
                } else {
                    format!(
                        "{}\nexpected {}\nmeasured slope {:.2}",
                        c.name,
                        c.expected,
                        loglog_slope(&c.xs, &c.ys)
                    )
                },
            })
            .collect();

        // The legend goes in a column right of the plot, where it hides
        // nothing; the canvas grows when that column is taller than it
        // (90 px: the title, up to two lines, and the margins).
        let height = HEIGHT.max((legend_column_height(&legend) + 90.0).ceil() as u32);
        let root = SVGBackend::new(path, (WIDE, height)).into_drawing_area();
        root.fill(&WHITE)?;
        let area = titled(&root, title, legend_column_width(&legend) + LEGEND_GAP)?;
        let chart = build_chart(&area, &xa, &ya, x_label, y_label)?;
        let plot = plot_rect(&chart);
        let to_px = |x: f64, y: f64| -> (f64, f64) {
            let (px, py) = chart.backend_coord(&(xa.t(x), ya.t(y)));
            (px as f64, py as f64)
        };
        for (i, p) in pts.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let marker = Marker::ALL[i % Marker::ALL.len()];
            let px: Vec<(f64, f64)> = p.iter().map(|&(x, y)| to_px(x, y)).collect();
            draw_path(&root, &px, colour.stroke_width(2))?;
            for &q in &px {
                draw_marker(&root, marker, q, 4.0, colour, true)?;
            }
        }
        draw_legend_column(&root, (plot.x1 + LEGEND_GAP, plot.y0), &legend)?;
        root.present()?;
        Ok(())
    };
    inner().with_context(|| format!("scaling plot {}", path.display()))
}
