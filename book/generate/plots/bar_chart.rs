//! A horizontal bar chart of two values per row (chapter 09's per-cascade
//! comparison).

use std::path::Path;

use anyhow::{anyhow, Context, Result};
use plotters::prelude::*;

use super::axis::{fmt_num, Axis};
use super::chart::{build_chart, plot_rect, titled};
use super::draw::{draw_text, ipx, text_w};
use super::legend::{draw_legend_column, legend_column_width, LegendRow, Swatch, LEGEND_GAP};
use super::{max_of, COLOURS, GREY, HEIGHT, LABEL_FONT, WIDE};

/// A horizontal bar chart: one row a label, two bars in it (`(label, a,
/// b)`: a in the first colour, b in grey), on a linear x axis from 0. The
/// legend names a and b.
pub fn bars(
    path: &Path,
    title: &str,
    x_label: &str,
    names: (&str, &str),
    rows: &[(String, f64, f64)],
) -> Result<()> {
    let inner = || -> Result<()> {
        let good = |v: f64| v.is_finite() && v >= 0.0;
        if rows.is_empty() || rows.iter().any(|r| !good(r.1) || !good(r.2)) {
            return Err(anyhow!("bars need finite, non-negative values"));
        }
        let max = max_of(rows.iter().flat_map(|r| [r.1, r.2])).max(1e-9);
        let xa = Axis::linear(0.0, max);
        let n = rows.len() as f64;
        let ya = Axis::linear(0.0, n);
        let label_px = LABEL_FONT / 1.24;
        let legend = vec![
            LegendRow {
                swatch: Swatch::Line(COLOURS[0], false),
                text: names.0.to_string(),
            },
            LegendRow {
                swatch: Swatch::Line(GREY, false),
                text: names.1.to_string(),
            },
        ];
        let row_h = 34.0;
        let height = HEIGHT.max((n * row_h + 170.0).ceil() as u32);
        let root = SVGBackend::new(path, (WIDE, height)).into_drawing_area();
        root.fill(&WHITE)?;
        let area = titled(&root, title, legend_column_width(&legend) + LEGEND_GAP)?;
        let chart = build_chart(&area, &xa, &ya, x_label, "variant")?;
        let plot = plot_rect(&chart);
        let to_px = |x: f64, y: f64| -> (f64, f64) {
            let (px, py) = chart.backend_coord(&(xa.t(x), ya.t(y)));
            (px as f64, py as f64)
        };
        for (i, (label, a, b)) in rows.iter().enumerate() {
            // Row i spans [n - i - 1, n - i] on the y axis, top to bottom.
            let top = n - i as f64 - 0.15;
            let mid = n - i as f64 - 0.5;
            let bottom = n - i as f64 - 0.85;
            for (v, y0, y1, colour) in [(a, top, mid, COLOURS[0]), (b, mid, bottom, GREY)] {
                let (x0, py0) = to_px(0.0, y0);
                let (x1, py1) = to_px(*v, y1);
                root.draw(&Rectangle::new(
                    [ipx((x0, py0)), ipx((x1.max(x0 + 1.0), py1))],
                    colour.filled(),
                ))?;
            }
            let (_, py) = to_px(0.0, top);
            let text = format!("{label}: {} / {}", fmt_num(*a), fmt_num(*b));
            let w = text_w(&text, label_px);
            let (xa_end, _) = to_px(a.max(*b), top);
            let x = if xa_end + 6.0 + w <= plot.x1 {
                xa_end + 6.0
            } else {
                plot.x1 - w - 4.0
            };
            draw_text(&root, &text, (x, py), BLACK)?;
        }
        draw_legend_column(&root, (plot.x1 + LEGEND_GAP, plot.y0), &legend)?;
        root.present()?;
        Ok(())
    };
    inner().with_context(|| format!("bar chart {}", path.display()))
}
