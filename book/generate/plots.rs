//! The book's plots (issue 9): one error-vs-time chart per chapter, the
//! workbook-wide chart of every lesson's variants, and log-log scaling plots.
//!
//! SVG through plotters without any font feature: plotters writes `<text>`
//! elements and the SVG viewer lays them out, so nothing here needs font
//! files. Where label placement needs a text's size it uses an estimate per
//! character ([`text_w`]). The output depends on the input only (no
//! timestamps, no random ids).

use std::path::Path;

use anyhow::{anyhow, Context, Result};
use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One variant of one lesson.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// Variant name, e.g. "slope_hw".
    pub label: String,
    /// Median time, ms (x).
    pub ms: f64,
    /// Interquartile range low (x error bar).
    pub ms_low: f64,
    /// Interquartile range high.
    pub ms_high: f64,
    /// Misclassified % (y), may be 0.
    pub error_pct: f64,
}

/// One lesson's variants.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<Point>,
}

/// One measured curve of a scaling plot, e.g. expected "O(n)".
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub name: String,
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    pub expected: String,
}

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
/// A title is shrunk down to this size (px) before it is wrapped.
const TITLE_MIN_PX: f64 = 14.0;
/// The widest a legend line may be outside the plot before it wraps, px.
const LEGEND_TEXT_MAX: f64 = 190.0;

const X_DESC: &str = "median frame time, ms (bars: interquartile range)";
const Y_DESC: &str = "misclassified % of receiver pixels (log)";

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

/// The Pareto-optimal points' indices (lower ms and lower error), sorted by
/// ms. A point is on the front when no other point is at least as good on
/// both median time and error and strictly better on one; points equal on
/// both are all kept. Points with a non-finite time or error are never on it.
pub fn pareto_front(points: &[Point]) -> Vec<usize> {
    let finite = |p: &Point| p.ms.is_finite() && p.error_pct.is_finite();
    let dominates = |q: &Point, p: &Point| {
        q.ms <= p.ms && q.error_pct <= p.error_pct && (q.ms < p.ms || q.error_pct < p.error_pct)
    };
    let mut front: Vec<usize> = (0..points.len())
        .filter(|&i| {
            let p = &points[i];
            finite(p) && !points.iter().any(|q| finite(q) && dominates(q, p))
        })
        .collect();
    front.sort_by(|&a, &b| {
        let (p, q) = (&points[a], &points[b]);
        p.ms.total_cmp(&q.ms)
            .then(p.error_pct.total_cmp(&q.error_pct))
            .then(a.cmp(&b))
    });
    front
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
    if logs.len() < 2 {
        return f64::NAN;
    }
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return f64::NAN;
    }
    sxy / sxx
}

/// One chapter's error-vs-time plot: x = median ms with a horizontal error bar
/// [ms_low, ms_high]; y = misclassified % on a log axis (values below `floor`
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

/// The workbook-wide plot: every lesson's variants, one colour and marker per
/// series (lesson), the same axes as [`error_vs_time`], a legend with the
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
    let mut legend: Vec<LegendRow> = plotted
        .iter()
        .map(|p| LegendRow {
            swatch: Swatch::LineMarker(p.marker, p.colour),
            text: p.series.name.clone(),
        })
        .collect();
    legend.push(LegendRow {
        swatch: Swatch::None,
        text: "filled: on its lesson's Pareto front".into(),
    });
    tradeoff_plot(path, title, &plotted, None, floor, legend)
        .with_context(|| format!("workbook plot {}", path.display()))
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

// ---------------------------------------------------------------------------
// The shared error-vs-time drawing.

struct PlottedSeries<'s> {
    series: &'s Series,
    colour: RGBColor,
    marker: Marker,
    /// Indices of the Pareto points, by ms.
    front: Vec<usize>,
    /// Label every point (else only the Pareto points).
    label_all: bool,
}

fn tradeoff_plot(
    path: &Path,
    title: &str,
    plotted: &[PlottedSeries],
    baseline_ms: Option<f64>,
    floor: f64,
    legend: Vec<LegendRow>,
) -> Result<()> {
    if !(floor.is_finite() && floor > 0.0) {
        return Err(anyhow!("the error floor must be positive, got {floor}"));
    }
    let drawable = |p: &Point| p.ms.is_finite() && p.ms > 0.0 && p.error_pct.is_finite();
    let points: Vec<&Point> = plotted
        .iter()
        .flat_map(|s| s.series.points.iter())
        .filter(|p| drawable(p))
        .collect();
    if points.is_empty() {
        return Err(anyhow!(
            "no point with a finite positive time and finite error"
        ));
    }

    // x: every median, bar end and the baseline; log when they span > 20x.
    let mut xs: Vec<f64> = Vec::new();
    for p in &points {
        xs.push(p.ms);
        for v in [p.ms_low, p.ms_high] {
            if v.is_finite() && v > 0.0 {
                xs.push(v);
            }
        }
    }
    if let Some(b) = baseline_ms.filter(|b| b.is_finite() && *b > 0.0) {
        xs.push(b);
    }
    let (xmin, xmax) = (min_of(xs.iter().copied()), max_of(xs.iter().copied()));
    let x_log = xmax / xmin > 20.0;
    let xa = if x_log {
        Axis::log(xmin, xmax)
    } else {
        Axis::linear(xmin, xmax)
    };
    let y_of = |p: &Point| p.error_pct.max(floor);
    let clamped = points.iter().any(|p| p.error_pct < floor);
    // Nothing lies below the floor: when points sit on it, the axis widens
    // upwards only.
    let ymin = min_of(points.iter().map(|p| y_of(p)));
    let mut ymax = max_of(points.iter().map(|p| y_of(p)));
    if clamped {
        ymax = ymax.max(floor * 10.0);
    }
    let ya = Axis::log(ymin, ymax);
    let x_desc = if x_log {
        format!("{X_DESC}, log scale")
    } else {
        X_DESC.to_string()
    };

    // The legend goes in a column right of the plot, where it hides nothing.
    let root = SVGBackend::new(path, (WIDE, HEIGHT)).into_drawing_area();
    root.fill(&WHITE)?;
    let area = titled(&root, title, legend_column_width(&legend) + LEGEND_GAP)?;
    let chart = build_chart(&area, &xa, &ya, &x_desc, Y_DESC)?;
    let plot = plot_rect(&chart);
    let to_px = |ms: f64, err: f64| -> (f64, f64) {
        let (px, py) = chart.backend_coord(&(xa.t(ms), ya.t(err)));
        (px as f64, py as f64)
    };
    let mut obstacles: Vec<Rect> = Vec::new();
    let label_px = LABEL_FONT / 1.24;

    // The baseline.
    if let Some(b) = baseline_ms.filter(|b| b.is_finite() && *b > 0.0) {
        let x = to_px(b, floor).0;
        draw_dashed(&root, (x, plot.y0), (x, plot.y1), GREY.stroke_width(2))?;
        let text = "no shadows";
        let w = text_w(text, label_px);
        let x0 = if x + 4.0 + w <= plot.x1 {
            x + 4.0
        } else {
            x - 4.0 - w
        };
        let r = Rect::new(x0, plot.y0 + 4.0, w, label_px);
        draw_text(&root, text, (r.x0, r.y0), GREY)?;
        obstacles.push(r);
        obstacles.push(Rect {
            x0: x - 2.0,
            y0: plot.y0,
            x1: x + 2.0,
            y1: plot.y1,
        });
    }

    // The floor line and its note.
    if clamped {
        let y = to_px(xmin, floor).1;
        draw_dashed(
            &root,
            (plot.x0, y),
            (plot.x1, y),
            GREY.mix(0.6).stroke_width(1),
        )?;
        let note = format!("on this line: 0 or below {} %", fmt_num(floor));
        let (w, h) = (text_w(&note, label_px), label_px);
        let on_floor: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.error_pct < floor)
            .map(|p| to_px(p.ms, floor))
            .collect();
        // Above the line, else below; right first, then sliding left: the
        // first spot clear of the points on the line and of the baseline.
        let base_x = baseline_ms
            .filter(|b| b.is_finite() && *b > 0.0)
            .map(|b| to_px(b, floor).0);
        let mut candidates = Vec::new();
        for top in [y - h - 3.0, y + 3.0] {
            let mut x = plot.x1 - w - 6.0;
            while x >= plot.x0 + 6.0 {
                candidates.push(Rect::new(x, top, w, h));
                x -= 10.0;
            }
            candidates.push(Rect::new(plot.x0 + 6.0, top, w, h));
        }
        let r = candidates
            .iter()
            .copied()
            .filter(|r| r.y1 <= plot.y1)
            .min_by_key(|r| {
                let hidden = on_floor
                    .iter()
                    .filter(|q| r.grow(8.0).contains(**q))
                    .count();
                let crossed = base_x.is_some_and(|x| x > r.x0 - 4.0 && x < r.x1 + 4.0);
                2 * hidden + crossed as usize
            })
            .unwrap_or(Rect::new(plot.x1 - w - 6.0, y - h - 3.0, w, h));
        // On white, where it must cross the baseline.
        root.draw(&Rectangle::new(
            [ipx((r.x0 - 2.0, r.y0 - 1.0)), ipx((r.x1 + 2.0, r.y1 + 1.0))],
            WHITE.mix(0.85).filled(),
        ))?;
        draw_text(&root, &note, (r.x0, r.y0), GREY)?;
        obstacles.push(r);
    }

    // Error bars, fronts, markers; then the legend; then the labels.
    struct Drawn {
        px: (f64, f64),
        label: String,
        colour: RGBColor,
        on_front: bool,
        wanted: bool,
    }
    let mut drawn: Vec<Drawn> = Vec::new();
    for s in plotted {
        let bar_style = s.colour.mix(0.55).stroke_width(2);
        for p in s.series.points.iter().filter(|p| drawable(p)) {
            let (x, y) = to_px(p.ms, y_of(p));
            let lo = if p.ms_low.is_finite() && p.ms_low > 0.0 {
                to_px(p.ms_low, floor).0
            } else {
                x
            };
            let hi = if p.ms_high.is_finite() && p.ms_high > 0.0 {
                to_px(p.ms_high, floor).0
            } else {
                x
            };
            if hi - lo >= 1.0 {
                draw_path(&root, &[(lo, y), (hi, y)], bar_style)?;
                for e in [lo, hi] {
                    draw_path(&root, &[(e, y - 4.0), (e, y + 4.0)], bar_style)?;
                }
                obstacles.push(Rect {
                    x0: lo,
                    y0: y - 4.0,
                    x1: hi,
                    y1: y + 4.0,
                });
            }
        }
        let step: Vec<(f64, f64)> = s
            .front
            .iter()
            .map(|&i| &s.series.points[i])
            .filter(|p| drawable(p))
            .map(|p| to_px(p.ms, y_of(p)))
            .collect();
        let mut path = Vec::new();
        for (k, &q) in step.iter().enumerate() {
            if k > 0 {
                path.push((q.0, step[k - 1].1));
            }
            path.push(q);
        }
        draw_path(&root, &path, s.colour.mix(0.8).stroke_width(2))?;
        for w in path.windows(2) {
            obstacles.push(segment_box(w[0], w[1]));
        }
        for (i, p) in s.series.points.iter().enumerate() {
            if !drawable(p) {
                continue;
            }
            let on_front = s.front.contains(&i);
            let q = to_px(p.ms, y_of(p));
            drawn.push(Drawn {
                px: q,
                label: p.label.clone(),
                colour: s.colour,
                on_front,
                wanted: s.label_all || on_front,
            });
        }
    }
    for d in &drawn {
        obstacles.push(around(d.px, 6.0));
    }
    // Markers: dominated first, so that the front is drawn on top.
    for pass in [false, true] {
        for s in plotted {
            for (i, p) in s.series.points.iter().enumerate() {
                if drawable(p) && s.front.contains(&i) == pass {
                    draw_marker(&root, s.marker, to_px(p.ms, y_of(p)), 5.0, s.colour, pass)?;
                }
            }
        }
    }
    draw_legend_column(&root, (plot.x1 + LEGEND_GAP, plot.y0), &legend)?;

    // Labels: the front's first, then by time, so that placement is stable.
    let mut order: Vec<usize> = (0..drawn.len()).filter(|&k| drawn[k].wanted).collect();
    order.sort_by(|&a, &b| {
        (!drawn[a].on_front)
            .cmp(&!drawn[b].on_front)
            .then(drawn[a].px.0.total_cmp(&drawn[b].px.0))
            .then(drawn[a].px.1.total_cmp(&drawn[b].px.1))
            .then(a.cmp(&b))
    });
    let all_px: Vec<(f64, f64)> = drawn.iter().map(|d| d.px).collect();
    let widths: Vec<f64> = drawn.iter().map(|d| text_w(&d.label, label_px)).collect();
    let placed = place_labels(&all_px, &order, &widths, label_px, plot, &obstacles);
    let single = plotted.len() == 1;
    for (k, r, leader) in placed {
        let d = &drawn[k];
        if let Some(end) = leader {
            let (dx, dy) = (end.0 - d.px.0, end.1 - d.px.1);
            let len = dx.hypot(dy).max(1e-9);
            let start = (d.px.0 + dx / len * 6.5, d.px.1 + dy / len * 6.5);
            draw_path(&root, &[start, end], GREY.mix(0.7).stroke_width(1))?;
        }
        let colour = if single {
            RGBColor(30, 30, 30)
        } else {
            darker(d.colour)
        };
        draw_text(&root, &d.label, (r.x0, r.y0), colour)?;
    }
    root.present()?;
    Ok(())
}

// ---------------------------------------------------------------------------
// Axes.

/// One axis in plotting space: log axes are drawn in log10(value), so the
/// chart is always linear f64 and the ticks are chosen here.
struct Axis {
    log: bool,
    lo: f64,
    hi: f64,
    bold: Vec<f64>,
    light: Vec<f64>,
    decimals: usize,
    /// Log labels in full ([`fmt_exact`]) rather than rounded ([`fmt_num`]).
    exact: bool,
}

impl Axis {
    /// A linear axis over [min, max] with some room, ticks at 1, 2 or 5
    /// times a power of ten; it does not go below 0 when min >= 0.
    fn linear(min: f64, max: f64) -> Axis {
        let span = if max > min {
            max - min
        } else {
            (min.abs() * 0.2).max(1e-6)
        };
        let mut lo = min - 0.08 * span;
        let hi = max + 0.08 * span;
        if min >= 0.0 && lo < 0.0 {
            lo = 0.0;
        }
        let step = nice_step((hi - lo) / 6.0);
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        let bold = (first..=last).map(|k| k as f64 * step).collect();
        let light = (2 * first - 1..=2 * last + 1)
            .map(|k| k as f64 * step / 2.0)
            .filter(|v| *v >= lo && *v <= hi)
            .collect();
        Axis {
            log: false,
            lo,
            hi,
            bold,
            light,
            decimals: (-step.log10().floor()).max(0.0) as usize,
            exact: false,
        }
    }

    /// A log axis over [min, max] (both > 0) spanning at least a decade:
    /// ticks at 1, 2, 5 times a power of ten over up to 2.5 decades, at the
    /// powers of ten (every n-th when many) beyond.
    fn log(min: f64, max: f64) -> Axis {
        let (mut a, mut b) = (min.log10(), max.log10());
        if b - a < 1.0 {
            let mid = (a + b) / 2.0;
            a = mid - 0.5;
            b = mid + 0.5;
        }
        let pad = 0.06 * (b - a);
        let (lo, hi) = (a - pad, b + pad);
        let span = hi - lo;
        let (bold_m, light_m, every): (&[f64], &[f64], i64) = if span <= 2.5 {
            (&[1.0, 2.0, 5.0], &[3.0, 4.0, 6.0, 7.0, 8.0, 9.0], 1)
        } else if span <= 8.0 {
            (&[1.0], &[2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], 1)
        } else {
            (&[1.0], &[], (span / 8.0).ceil() as i64)
        };
        let (e0, e1) = (lo.floor() as i64, hi.ceil() as i64);
        let mut bold = Vec::new();
        let mut light = Vec::new();
        let in_range = |t: &f64| *t >= lo && *t <= hi;
        for e in e0..=e1 {
            if e.rem_euclid(every) == 0 {
                bold.extend(bold_m.iter().map(|m| e as f64 + m.log10()).filter(in_range));
            }
            light.extend(
                light_m
                    .iter()
                    .map(|m| e as f64 + m.log10())
                    .filter(in_range),
            );
        }
        Axis {
            log: true,
            lo,
            hi,
            bold,
            light,
            decimals: 0,
            exact: false,
        }
    }

    /// This log axis labelled at `values` (sorted, distinct, positive: the
    /// data's x) when they are few and far enough apart for their labels,
    /// its own ticks as the light grid; else its own labelled ticks plus the
    /// first and last value (ticks too close to those dropped). Either way
    /// the data's ends are labelled, in full.
    fn ticks_at(mut self, values: &[f64]) -> Axis {
        if !self.log || values.is_empty() {
            return self;
        }
        let ts: Vec<f64> = values.iter().map(|v| v.log10()).collect();
        let span = self.hi - self.lo;
        // The plot is about this wide (px) next to a legend column.
        let px_per_t = 560.0 / span;
        let label_w = values
            .iter()
            .map(|&v| text_w(&fmt_exact(v), TICK_FONT / 1.24))
            .fold(0.0, f64::max);
        let min_gap = ts
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        self.exact = true;
        if ts.len() <= 8 && min_gap * px_per_t >= label_w + 12.0 {
            let near = |t: &f64| ts.iter().any(|d| (d - t).abs() < span / 40.0);
            let mut light: Vec<f64> = self
                .bold
                .iter()
                .chain(&self.light)
                .copied()
                .filter(|t| !near(t))
                .collect();
            light.sort_by(f64::total_cmp);
            self.bold = ts;
            self.light = light;
        } else {
            let (first, last) = (ts[0], ts[ts.len() - 1]);
            let room = (label_w + 12.0) / px_per_t;
            let mut bold: Vec<f64> = self
                .bold
                .iter()
                .copied()
                .filter(|t| (t - first).abs() >= room && (t - last).abs() >= room)
                .collect();
            bold.push(first);
            if last > first {
                bold.push(last);
            }
            bold.sort_by(f64::total_cmp);
            self.bold = bold;
        }
        self
    }

    /// A value in plotting space.
    fn t(&self, v: f64) -> f64 {
        if self.log {
            v.log10()
        } else {
            v
        }
    }

    /// A tick label for a value in plotting space.
    fn label(&self, t: f64) -> String {
        if self.log && self.exact {
            fmt_exact(10f64.powf(t))
        } else if self.log {
            fmt_num(10f64.powf(t))
        } else {
            format!("{:.*}", self.decimals, t)
        }
    }
}

/// 1, 2 or 5 times a power of ten, at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let p = 10f64.powf(raw.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if m * p >= raw * 0.999_999 {
            return m * p;
        }
    }
    10.0 * p
}

/// A value with a few significant digits and no float noise: 0.001, 0.02, 5,
/// 20, 1e6.
fn fmt_num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor();
    if mag >= 6.0 || mag <= -7.0 {
        return format!("{v:.0e}");
    }
    let decimals = (2.0 - mag).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A value as the tables print it: a whole number in full, its thousands
/// apart (`1 048 576`), anything else as [`fmt_num`].
fn fmt_exact(v: f64) -> String {
    let r = v.round();
    if !(v.is_finite() && r >= 1.0 && (v - r).abs() <= 1e-9 * r && r < 1e15) {
        return fmt_num(v);
    }
    let digits = format!("{}", r as u64);
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

/// A linear f64 coordinate whose ticks are the axis's own (plotters'
/// `WithKeyPoints` over f64 has no default label formatting).
struct Ticks {
    lo: f64,
    hi: f64,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ticks {
    fn of(a: &Axis) -> Ticks {
        Ticks {
            lo: a.lo,
            hi: a.hi,
            bold: a.bold.clone(),
            light: a.light.clone(),
        }
    }
}

impl Ranged for Ticks {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let f = (v - self.lo) / (self.hi - self.lo);
        limit.0 + (f * (limit.1 - limit.0) as f64).round() as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.light.clone()
        } else {
            self.bold.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Ticks, Ticks>>;

fn build_chart<'a, 'b>(
    area: &'a Root<'b>,
    xa: &Axis,
    ya: &Axis,
    x_desc: &str,
    y_desc: &str,
) -> Result<Chart<'a, 'b>> {
    // Room for the widest y tick label and, left of it, the y description.
    let y_labels_w = ya
        .bold
        .iter()
        .map(|t| text_w(&ya.label(*t), TICK_FONT / 1.24))
        .fold(0.0, f64::max);
    let y_area = 68.max((y_labels_w + 34.0).ceil() as u32);
    let mut chart = ChartBuilder::on(area)
        .margin(MARGIN as u32)
        .margin_top(6)
        .x_label_area_size(50)
        .y_label_area_size(y_area)
        .build_cartesian_2d(Ticks::of(xa), Ticks::of(ya))?;
    let xf = |v: &f64| xa.label(*v);
    let yf = |v: &f64| ya.label(*v);
    chart
        .configure_mesh()
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style((FONT, TICK_FONT))
        .axis_desc_style((FONT, DESC_FONT))
        .bold_line_style(BLACK.mix(0.18))
        .light_line_style(BLACK.mix(0.06))
        .axis_style(BLACK.mix(0.8))
        .draw()?;
    Ok(chart)
}

/// The title's font size (px) and lines: one line at the largest size from
/// the title font down to [`TITLE_MIN_PX`] whose estimated width ([`text_w`])
/// fits `avail`, else two lines split at the space that makes the longer one
/// shortest, at the largest size that fits (never below 8 px).
fn title_lines(title: &str, avail: f64) -> (f64, Vec<String>) {
    let full = TITLE_FONT / 1.24;
    let fit = |lines: &[String]| {
        let n = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0);
        // text_w(l, px) <= avail, solved for px.
        ((avail - 2.0) / (0.56 * n.max(1) as f64)).min(full)
    };
    let one = vec![title.to_string()];
    let px = fit(&one);
    if px >= TITLE_MIN_PX {
        return (px, one);
    }
    let chars: Vec<char> = title.chars().collect();
    let split = (0..chars.len())
        .filter(|&i| chars[i] == ' ')
        .min_by_key(|&i| i.max(chars.len() - i - 1));
    let Some(i) = split else {
        return (px.max(8.0), one);
    };
    let two = vec![
        chars[..i].iter().collect::<String>(),
        chars[i + 1..].iter().collect::<String>(),
    ];
    (fit(&two).max(8.0), two)
}

/// Draws `title` centred across the top of `root`, fitted to its width, and
/// returns the area below it, less `right` pixels on the right (a column for
/// a legend outside the plot).
fn titled<'b>(root: &Root<'b>, title: &str, right: f64) -> Result<Root<'b>> {
    let (w, _) = root.dim_in_pixel();
    let (px, lines) = title_lines(title, w as f64 - 2.0 * MARGIN);
    let line_h = (px * 1.25).ceil();
    let style = TextStyle::from((FONT, px * 1.24).into_font())
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Top));
    for (k, line) in lines.iter().enumerate() {
        let y = MARGIN + line_h * k as f64;
        root.draw(&Text::new(
            line.clone(),
            ipx((w as f64 / 2.0, y)),
            style.clone(),
        ))?;
    }
    let top = MARGIN + line_h * lines.len() as f64 + 4.0;
    Ok(root.margin(top as i32, 0, 0, right.ceil() as i32))
}

fn plot_rect(chart: &Chart<'_, '_>) -> Rect {
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    Rect {
        x0: xr.start as f64,
        y0: yr.start as f64,
        x1: xr.end as f64,
        y1: yr.end as f64,
    }
}

// ---------------------------------------------------------------------------
// Pixel-space drawing.

type Root<'a> = DrawingArea<SVGBackend<'a>, Shift>;

fn ipx(p: (f64, f64)) -> (i32, i32) {
    (p.0.round() as i32, p.1.round() as i32)
}

fn draw_path(root: &Root, pts: &[(f64, f64)], style: ShapeStyle) -> Result<()> {
    if pts.len() >= 2 {
        root.draw(&PathElement::new(
            pts.iter().map(|&p| ipx(p)).collect::<Vec<_>>(),
            style,
        ))?;
    }
    Ok(())
}

fn draw_dashed(root: &Root, a: (f64, f64), b: (f64, f64), style: ShapeStyle) -> Result<()> {
    root.draw(&DashedPathElement::new(vec![ipx(a), ipx(b)], 6, 4, style))?;
    Ok(())
}

/// Text with its top-left corner at `at`.
fn draw_text(root: &Root, text: &str, at: (f64, f64), colour: RGBColor) -> Result<()> {
    let style = TextStyle::from((FONT, LABEL_FONT).into_font())
        .color(&colour)
        .pos(Pos::new(HPos::Left, VPos::Top));
    root.draw(&Text::new(text.to_string(), ipx(at), style))?;
    Ok(())
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
    TriangleDown,
    Hexagon,
}

impl Marker {
    const ALL: [Marker; 6] = [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
        Marker::TriangleDown,
        Marker::Hexagon,
    ];
}

/// A marker of radius `r` at `c`: filled, or hollow (white inside, outlined).
fn draw_marker(
    root: &Root,
    m: Marker,
    c: (f64, f64),
    r: f64,
    colour: RGBColor,
    filled: bool,
) -> Result<()> {
    let outline = colour.stroke_width(2);
    if m == Marker::Circle {
        let (ci, ri) = (ipx(c), r.round() as i32);
        root.draw(&Circle::new(ci, ri, WHITE.filled()))?;
        root.draw(&Circle::new(
            ci,
            ri,
            if filled { colour.filled() } else { outline },
        ))?;
        return Ok(());
    }
    let corners: Vec<(f64, f64)> = match m {
        Marker::Square => vec![(-0.9, -0.9), (0.9, -0.9), (0.9, 0.9), (-0.9, 0.9)],
        Marker::Triangle => vec![(0.0, -1.2), (1.1, 0.8), (-1.1, 0.8)],
        Marker::TriangleDown => vec![(0.0, 1.2), (1.1, -0.8), (-1.1, -0.8)],
        Marker::Diamond => vec![(0.0, -1.25), (1.0, 0.0), (0.0, 1.25), (-1.0, 0.0)],
        _ => (0..6)
            .map(|k| {
                let a = std::f64::consts::PI / 3.0 * k as f64;
                (1.05 * a.cos(), 1.05 * a.sin())
            })
            .collect(),
    };
    let pts: Vec<(i32, i32)> = corners
        .iter()
        .map(|&(dx, dy)| ipx((c.0 + dx * r, c.1 + dy * r)))
        .collect();
    let fill = if filled { colour } else { WHITE };
    root.draw(&Polygon::new(pts.clone(), fill.filled()))?;
    let mut closed = pts;
    closed.push(closed[0]);
    root.draw(&PathElement::new(closed, outline))?;
    Ok(())
}

fn darker(c: RGBColor) -> RGBColor {
    let f = |v: u8| (v as f64 * 0.7).round() as u8;
    RGBColor(f(c.0), f(c.1), f(c.2))
}

// ---------------------------------------------------------------------------
// Legend.

enum Swatch {
    None,
    Marker(Marker, RGBColor, bool),
    Line(RGBColor, bool),
    LineMarker(Marker, RGBColor),
}

struct LegendRow {
    swatch: Swatch,
    text: String,
}

/// A legend row's text in lines no wider than [`LEGEND_TEXT_MAX`] (a word
/// longer than that stays whole); a `\n` starts a new line.
fn wrap(text: &str, px: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for para in text.split('\n') {
        let mut line: Option<String> = None;
        for word in para.split(' ') {
            line = match line {
                Some(l) if text_w(&format!("{l} {word}"), px) <= LEGEND_TEXT_MAX => {
                    Some(format!("{l} {word}"))
                }
                Some(l) => {
                    lines.push(l);
                    Some(word.to_string())
                }
                None => Some(word.to_string()),
            };
        }
        lines.extend(line);
    }
    lines
}

const LEGEND_PAD: f64 = 8.0;
const LEGEND_SWATCH_W: f64 = 30.0;
/// Between the plot and a legend column, px.
const LEGEND_GAP: f64 = 12.0;
/// Between two rows of a legend column, px.
const LEGEND_ROW_GAP: f64 = 6.0;

/// The width of the legend column [`draw_legend_column`] draws.
fn legend_column_width(rows: &[LegendRow]) -> f64 {
    let text_px = LABEL_FONT / 1.24;
    let text = rows
        .iter()
        .flat_map(|r| {
            let indent = if matches!(r.swatch, Swatch::None) {
                0.0
            } else {
                LEGEND_SWATCH_W
            };
            wrap(&r.text, text_px)
                .into_iter()
                .map(move |l| indent + text_w(&l, text_px))
        })
        .fold(0.0, f64::max);
    (LEGEND_PAD * 2.0 + text).ceil()
}

/// The height of the legend column [`draw_legend_column`] draws.
fn legend_column_height(rows: &[LegendRow]) -> f64 {
    let text_px = LABEL_FONT / 1.24;
    let line_h = text_px + 4.0;
    let lines: usize = rows.iter().map(|r| wrap(&r.text, text_px).len()).sum();
    LEGEND_PAD * 2.0 + line_h * lines as f64 - 4.0 * rows.len() as f64
        + LEGEND_ROW_GAP * rows.len().saturating_sub(1) as f64
}

/// Draws the legend as a box with its top-left corner at `at`, outside the
/// plot (long texts wrapped), so that it hides no data.
fn draw_legend_column(root: &Root, at: (f64, f64), rows: &[LegendRow]) -> Result<()> {
    if rows.is_empty() {
        return Ok(());
    }
    let text_px = LABEL_FONT / 1.24;
    let line_h = text_px + 4.0;
    let row_gap = LEGEND_ROW_GAP;
    let wrapped: Vec<Vec<String>> = rows.iter().map(|r| wrap(&r.text, text_px)).collect();
    let w = legend_column_width(rows);
    let h = legend_column_height(rows);
    let b = Rect::new(at.0, at.1, w, h);
    root.draw(&Rectangle::new(
        [ipx((b.x0, b.y0)), ipx((b.x1, b.y1))],
        BLACK.mix(0.35).stroke_width(1),
    ))?;
    let mut top = b.y0 + LEGEND_PAD;
    for (row, lines) in rows.iter().zip(&wrapped) {
        let mid = top + text_px / 2.0;
        let (sx0, sx1) = (b.x0 + LEGEND_PAD, b.x0 + LEGEND_PAD + LEGEND_SWATCH_W - 6.0);
        draw_swatch(root, &row.swatch, sx0, sx1, mid)?;
        let text_x = if matches!(row.swatch, Swatch::None) {
            sx0
        } else {
            b.x0 + LEGEND_PAD + LEGEND_SWATCH_W
        };
        for (k, l) in lines.iter().enumerate() {
            draw_text(
                root,
                l,
                (text_x, top + line_h * k as f64),
                RGBColor(30, 30, 30),
            )?;
        }
        top += line_h * lines.len() as f64 - 4.0 + row_gap;
    }
    Ok(())
}

fn draw_swatch(root: &Root, swatch: &Swatch, sx0: f64, sx1: f64, mid: f64) -> Result<()> {
    let sc = ((sx0 + sx1) / 2.0, mid);
    match *swatch {
        Swatch::None => {}
        Swatch::Marker(m, c, filled) => draw_marker(root, m, sc, 5.0, c, filled)?,
        Swatch::Line(c, false) => draw_path(root, &[(sx0, mid), (sx1, mid)], c.stroke_width(2))?,
        Swatch::Line(c, true) => draw_dashed(root, (sx0, mid), (sx1, mid), c.stroke_width(2))?,
        Swatch::LineMarker(m, c) => {
            draw_path(root, &[(sx0, mid), (sx1, mid)], c.stroke_width(2))?;
            draw_marker(root, m, sc, 4.5, c, true)?;
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Label placement in pixel space.

#[derive(Clone, Copy, Debug, PartialEq)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    fn new(x0: f64, y0: f64, w: f64, h: f64) -> Rect {
        Rect {
            x0,
            y0,
            x1: x0 + w,
            y1: y0 + h,
        }
    }
    fn overlap(&self, o: &Rect) -> f64 {
        let w = self.x1.min(o.x1) - self.x0.max(o.x0);
        let h = self.y1.min(o.y1) - self.y0.max(o.y0);
        if w > 0.0 && h > 0.0 {
            w * h
        } else {
            0.0
        }
    }
    fn contains(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }
    fn grow(&self, d: f64) -> Rect {
        Rect {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }
    /// The point of the rectangle nearest to `p`.
    fn nearest(&self, p: (f64, f64)) -> (f64, f64) {
        (p.0.clamp(self.x0, self.x1), p.1.clamp(self.y0, self.y1))
    }
    /// The area outside `area`.
    fn outside(&self, area: &Rect) -> f64 {
        (self.x1 - self.x0) * (self.y1 - self.y0) - self.overlap(area)
    }
}

/// Estimated width of `text` at `px` pixels in a sans-serif font.
fn text_w(text: &str, px: f64) -> f64 {
    0.56 * px * text.chars().count() as f64 + 2.0
}

fn around(c: (f64, f64), r: f64) -> Rect {
    Rect {
        x0: c.0 - r,
        y0: c.1 - r,
        x1: c.0 + r,
        y1: c.1 + r,
    }
}

fn segment_box(a: (f64, f64), b: (f64, f64)) -> Rect {
    Rect {
        x0: a.0.min(b.0) - 1.5,
        y0: a.1.min(b.1) - 1.5,
        x1: a.0.max(b.0) + 1.5,
        y1: a.1.max(b.1) + 1.5,
    }
}

/// Within this distance (px) of each other, points whose labels cannot
/// touch them unambiguously are labelled together in one column.
const CROWD_PX: f64 = 36.0;
/// A touching label's gap to its marker's centre, px.
const TOUCH_PX: f64 = 9.0;

/// The distance from `p` to the nearest point of `r`.
fn rect_dist(r: &Rect, p: (f64, f64)) -> f64 {
    let n = r.nearest(p);
    (n.0 - p.0).hypot(n.1 - p.1)
}

/// Places the labels of the points `order` (indices into `pts`, in order of
/// priority; `widths[k]` and `h` the label sizes) in `plot`, around
/// `obstacles`. Each label either touches its own point, nearer to it than to
/// any other point of `pts` by a clear margin, or, where points crowd, goes
/// in a column beside its group, joined to its point by a leader line
/// ending at the returned point. Returns (index, label box, leader end).
fn place_labels(
    pts: &[(f64, f64)],
    order: &[usize],
    widths: &[f64],
    h: f64,
    plot: Rect,
    obstacles: &[Rect],
) -> Vec<Label> {
    let close = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1) <= CROWD_PX;
    // Points that cannot have a touching label, and their labelled
    // neighbours, go to columns; repeat until the rest all touch.
    let mut crowded = vec![false; pts.len()];
    let (mut out, mut obs) = loop {
        let mut obs = obstacles.to_vec();
        let mut out = Vec::new();
        let mut failed = Vec::new();
        for &k in order.iter().filter(|&&k| !crowded[k]) {
            match touching_spot(pts, k, widths[k], h, plot, &obs) {
                Some(r) => {
                    obs.push(r);
                    out.push((k, r, None));
                }
                None => failed.push(k),
            }
        }
        if failed.is_empty() {
            break (out, obs);
        }
        for f in failed {
            for &j in order {
                if j == f || close(pts[j], pts[f]) {
                    crowded[j] = true;
                }
            }
        }
    };
    // The crowded points in groups (linked within CROWD_PX), in order of
    // their first member.
    let mut group_of: Vec<Option<usize>> = vec![None; pts.len()];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for &k in order.iter().filter(|&&k| crowded[k]) {
        if group_of[k].is_some() {
            continue;
        }
        let g = groups.len();
        let mut members = vec![k];
        group_of[k] = Some(g);
        let mut i = 0;
        while i < members.len() {
            let m = members[i];
            for &j in order {
                if crowded[j] && group_of[j].is_none() && close(pts[j], pts[m]) {
                    group_of[j] = Some(g);
                    members.push(j);
                }
            }
            i += 1;
        }
        groups.push(members);
    }
    for g in groups {
        let labels: Vec<Rect> = out.iter().map(|o| o.1).collect();
        let column = place_column(pts, &g, widths, h, plot, &obs, &labels);
        for &(k, r, end) in &column {
            obs.push(r);
            out.push((k, r, Some(end)));
        }
    }
    out
}

/// A spot for point `k`'s label right beside its marker: in the plot, clear
/// of the obstacles, and nearer to point `k` than to any other point by at
/// least 5 px; the first such of eight spots around the marker, if any.
fn touching_spot(
    pts: &[(f64, f64)],
    k: usize,
    w: f64,
    h: f64,
    plot: Rect,
    obstacles: &[Rect],
) -> Option<Rect> {
    let c = pts[k];
    let d = TOUCH_PX;
    let diag = d * 0.75;
    let spots = [
        (c.0 + d, c.1 - h / 2.0),
        (c.0 - d - w, c.1 - h / 2.0),
        (c.0 + diag, c.1 - diag - h),
        (c.0 + diag, c.1 + diag),
        (c.0 - diag - w, c.1 - diag - h),
        (c.0 - diag - w, c.1 + diag),
        (c.0 - w / 2.0, c.1 - d - h),
        (c.0 - w / 2.0, c.1 + d),
    ];
    spots.iter().map(|&(x, y)| Rect::new(x, y, w, h)).find(|r| {
        let own = rect_dist(r, c);
        r.outside(&plot) == 0.0
            && obstacles.iter().all(|o| r.overlap(o) == 0.0)
            && pts
                .iter()
                .enumerate()
                .all(|(j, &q)| j == k || rect_dist(r, q) >= own + 5.0)
    })
}

/// The distance from `p` to the segment a-b.
fn seg_dist(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a.0 + t * dx - p.0).hypot(a.1 + t * dy - p.1)
}

/// Whether the segment a-b meets the rectangle `r`.
fn seg_hits(a: (f64, f64), b: (f64, f64), r: &Rect) -> bool {
    if r.contains(a) || r.contains(b) {
        return true;
    }
    let corners = [(r.x0, r.y0), (r.x1, r.y0), (r.x1, r.y1), (r.x0, r.y1)];
    (0..4).any(|i| crosses(a, b, corners[i], corners[(i + 1) % 4]))
}

/// A placed label: the point's index, the label box and, where it has one,
/// its leader's end.
type Label = (usize, Rect, Option<(f64, f64)>);

/// A column label: the point's index, the label box and its leader's end.
type Placed = (usize, Rect, (f64, f64));

/// Whether the segments a-b and c-d cross.
fn crosses(a: (f64, f64), b: (f64, f64), c: (f64, f64), d: (f64, f64)) -> bool {
    let side = |p: (f64, f64), q: (f64, f64), r: (f64, f64)| {
        (q.0 - p.0) * (r.1 - p.1) - (q.1 - p.1) * (r.0 - p.0)
    };
    let (d1, d2) = (side(c, d, a), side(c, d, b));
    let (d3, d4) = (side(a, b, c), side(a, b, d));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// The labels of `group` stacked in a column right or left of it, the
/// column's side, offset and the rows' order chosen to overlap the least of
/// the obstacles (and stay in the plot), then for the shortest leader lines
/// with the fewest crossings. Returns (index, label box, leader end).
fn place_column(
    pts: &[(f64, f64)],
    group: &[usize],
    widths: &[f64],
    h: f64,
    plot: Rect,
    obstacles: &[Rect],
    labels: &[Rect],
) -> Vec<Placed> {
    let row = h + 3.0;
    let n = group.len();
    let col_h = row * n as f64 - 3.0;
    let col_w = group.iter().map(|&k| widths[k]).fold(0.0, f64::max);
    let gx0 = group
        .iter()
        .map(|&k| pts[k].0)
        .fold(f64::INFINITY, f64::min);
    let gx1 = group
        .iter()
        .map(|&k| pts[k].0)
        .fold(f64::NEG_INFINITY, f64::max);
    let gy0 = group
        .iter()
        .map(|&k| pts[k].1)
        .fold(f64::INFINITY, f64::min);
    let gy1 = group
        .iter()
        .map(|&k| pts[k].1)
        .fold(f64::NEG_INFINITY, f64::max);
    let cy = (gy0 + gy1) / 2.0;
    // Row k's box and its leader end, for a column at x0 (its left edge)
    // and top y0.
    let layout = |right: bool, x0: f64, y0: f64, rows: &[usize]| -> Vec<Placed> {
        rows.iter()
            .enumerate()
            .map(|(i, &k)| {
                let y = y0 + row * i as f64;
                let (r, end) = if right {
                    let r = Rect::new(x0, y, widths[k], h);
                    (r, (r.x0 - 2.0, y + h / 2.0))
                } else {
                    let r = Rect::new(x0 + col_w - widths[k], y, widths[k], h);
                    (r, (r.x1 + 2.0, y + h / 2.0))
                };
                (k, r, end)
            })
            .collect()
    };
    // Leader crossings, then total length, of an arrangement.
    let score = |rows: &[Placed]| -> (usize, f64) {
        let mut crossings = 0;
        for i in 0..rows.len() {
            for j in i + 1..rows.len() {
                if crosses(pts[rows[i].0], rows[i].2, pts[rows[j].0], rows[j].2) {
                    crossings += 1;
                }
            }
        }
        let len = rows
            .iter()
            .map(|&(k, _, e)| (e.0 - pts[k].0).hypot(e.1 - pts[k].1))
            .sum();
        (crossings, len)
    };
    let others: Vec<(f64, f64)> = (0..pts.len())
        .filter(|j| !group.contains(j))
        .map(|j| pts[j])
        .collect();
    let mut best: Option<((f64, usize, f64), Vec<Placed>)> = None;
    for right in [true, false] {
        for gap in [18.0, 34.0, 56.0, 84.0, 120.0, 170.0] {
            let x0 = if right { gx1 + gap } else { gx0 - gap - col_w };
            for s in 0..=30 {
                // 0, -1, +1, -2, +2, ... rows up or down.
                let shift = if s % 2 == 1 { -((s + 1) / 2) } else { s / 2 } as f64;
                let y0 = cy - col_h / 2.0 + shift * row;
                // The rows' order: by height, then improved by swapping
                // neighbours while that removes crossings or shortens leaders.
                let mut rows: Vec<usize> = group.to_vec();
                rows.sort_by(|&a, &b| {
                    pts[a]
                        .1
                        .total_cmp(&pts[b].1)
                        .then(pts[a].0.total_cmp(&pts[b].0))
                        .then(a.cmp(&b))
                });
                for _ in 0..n * n {
                    let mut improved = false;
                    for i in 0..n.saturating_sub(1) {
                        let now = score(&layout(right, x0, y0, &rows));
                        rows.swap(i, i + 1);
                        let then = score(&layout(right, x0, y0, &rows));
                        if then.0 < now.0 || (then.0 == now.0 && then.1 < now.1 - 1e-9) {
                            improved = true;
                        } else {
                            rows.swap(i, i + 1);
                        }
                    }
                    if !improved {
                        break;
                    }
                }
                let placed = layout(right, x0, y0, &rows);
                let mut cost = 0.0;
                for (_, r, _) in &placed {
                    cost += 1e3 * r.outside(&plot);
                    cost += obstacles.iter().map(|o| r.overlap(o)).sum::<f64>();
                    // A label beside another point would read as its label.
                    let near = others.iter().filter(|&&q| rect_dist(r, q) < 10.0).count();
                    cost += 200.0 * near as f64;
                }
                // A leader over another point or through a label misleads.
                for &(k, _, e) in &placed {
                    let a = pts[k];
                    let hits = (0..pts.len())
                        .filter(|&j| j != k && seg_dist(a, e, pts[j]) < 7.0)
                        .count()
                        + labels
                            .iter()
                            .filter(|r| seg_hits(a, e, &r.grow(1.0)))
                            .count();
                    cost += 300.0 * hits as f64;
                }
                let (crossings, len) = score(&placed);
                let key = (cost, crossings, len);
                let better = match &best {
                    None => true,
                    Some((b, _)) => {
                        key.0 < b.0
                            || (key.0 == b.0 && (key.1 < b.1 || (key.1 == b.1 && key.2 < b.2)))
                    }
                };
                if better {
                    best = Some((key, placed));
                }
            }
        }
    }
    best.map(|b| b.1).unwrap_or_default()
}

fn min_of(it: impl Iterator<Item = f64>) -> f64 {
    it.fold(f64::INFINITY, f64::min)
}

fn max_of(it: impl Iterator<Item = f64>) -> f64 {
    it.fold(f64::NEG_INFINITY, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(label: &str, ms: f64, error_pct: f64) -> Point {
        Point {
            label: label.into(),
            ms,
            ms_low: ms * 0.9,
            ms_high: ms * 1.1,
            error_pct,
        }
    }

    #[test]
    fn pareto_front_excludes_dominated_points_and_sorts_by_time() {
        let points = vec![
            pt("slow_exact", 9.0, 0.0),
            pt("dominated", 5.0, 2.0), // beaten by "mid" on both
            pt("fast_rough", 1.0, 5.0),
            pt("mid", 4.0, 1.0),
            pt("same_time_worse", 4.0, 1.5), // same time as "mid", more error
            pt("broken", f64::NAN, 0.0),
        ];
        assert_eq!(pareto_front(&points), vec![2, 3, 0]);
    }

    #[test]
    fn pareto_front_keeps_ties_and_handles_empty() {
        let points = vec![pt("a", 2.0, 1.0), pt("b", 2.0, 1.0), pt("c", 3.0, 1.0)];
        assert_eq!(pareto_front(&points), vec![0, 1]);
        assert!(pareto_front(&[]).is_empty());
    }

    #[test]
    fn loglog_slope_measures_the_order() {
        let xs = [1.0, 2.0, 4.0, 8.0, 16.0];
        let square: Vec<f64> = xs.iter().map(|x| 3.0 * x * x).collect();
        assert!((loglog_slope(&xs, &square) - 2.0).abs() < 1e-12);
        let linear: Vec<f64> = xs.iter().map(|x| 0.5 * x).collect();
        assert!((loglog_slope(&xs, &linear) - 1.0).abs() < 1e-12);
        let constant = [7.0; 5];
        assert!(loglog_slope(&xs, &constant).abs() < 1e-12);
        let n_log_n: Vec<f64> = xs.iter().map(|x| x * x.ln().max(1.0)).collect();
        let s = loglog_slope(&xs, &n_log_n);
        assert!(s > 1.0 && s < 1.5, "{s}");
        assert!(loglog_slope(&[1.0], &[1.0]).is_nan());
        assert!(loglog_slope(&[2.0, 2.0], &[1.0, 3.0]).is_nan());
    }

    #[test]
    fn log_axis_ticks_are_round_numbers() {
        let a = Axis::log(0.001, 5.0);
        let labels: Vec<String> = a.bold.iter().map(|t| a.label(*t)).collect();
        assert_eq!(labels, ["0.001", "0.01", "0.1", "1"]);
        let b = Axis::log(0.3, 2.0);
        let labels: Vec<String> = b.bold.iter().map(|t| b.label(*t)).collect();
        assert_eq!(labels, ["0.5", "1", "2"]);
    }

    #[test]
    fn scaling_x_axis_labels_the_data_ends() {
        let xs = [256.0, 512.0, 1024.0, 2048.0, 4096.0];
        let a = Axis::log(256.0, 4096.0).ticks_at(&xs);
        let labels: Vec<String> = a.bold.iter().map(|t| a.label(*t)).collect();
        assert_eq!(labels, ["256", "512", "1 024", "2 048", "4 096"]);
        // Too many values for a label each: round ticks plus both ends.
        let many: Vec<f64> = (0..40).map(|k| 3.0 * 1.3f64.powi(k)).collect();
        let b = Axis::log(many[0], many[39]).ticks_at(&many);
        let labels: Vec<String> = b.bold.iter().map(|t| b.label(*t)).collect();
        assert_eq!(labels.first().map(String::as_str), Some("3"));
        assert_eq!(
            labels.last().map(String::as_str),
            Some(fmt_exact(many[39]).as_str())
        );
        assert!(labels.len() > 2, "{labels:?}");
        assert_eq!(fmt_exact(1_048_576.0), "1 048 576");
        assert_eq!(fmt_exact(0.25), "0.25");
    }

    #[test]
    fn plots_are_deterministic_svg() {
        let dir = std::env::temp_dir().join(format!("plots_test_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let s = Series {
            name: "lesson".into(),
            points: vec![pt("a", 1.0, 0.0), pt("b", 2.0, 0.5), pt("c", 3.0, 0.2)],
        };
        let (p1, p2) = (dir.join("1.svg"), dir.join("2.svg"));
        error_vs_time(&p1, "t", &s, Some(0.5), 1e-3).unwrap();
        error_vs_time(&p2, "t", &s, Some(0.5), 1e-3).unwrap();
        let (a, b) = (std::fs::read(&p1).unwrap(), std::fs::read(&p2).unwrap());
        assert_eq!(a, b);
        let text = String::from_utf8(a).unwrap();
        assert!(text.contains("no shadows") && text.contains("<text"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
