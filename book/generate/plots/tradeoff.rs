//! The error-vs-time drawing every trade-off plot shares: the points (one
//! variant each), their Pareto front, and the chart with its error bars,
//! front, floor line, baseline, legend and labels. [`super::chapter`] and
//! [`super::workbook`] call it.

use std::path::Path;

use anyhow::{anyhow, Result};
use plotters::prelude::*;

use super::axis::{fmt_num, Axis};
use super::chart::{build_chart, plot_rect, titled};
use super::draw::{
    around, darker, draw_dashed, draw_marker, draw_path, draw_text, ipx, segment_box, text_w,
    Marker, Rect, Root,
};
use super::labels::place_labels;
use super::legend::{draw_legend_column, legend_column_width, LegendRow, LEGEND_GAP};
use super::{max_of, min_of, GREY, HEIGHT, LABEL_FONT, WIDE};

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
    /// The error (y), in % of the series' [`Metric`]; may be 0.
    pub error_pct: f64,
}

/// What a series' errors measure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metric {
    /// Misclassified % of the receiver pixels (a hard shadow).
    Misclassified,
    /// Mean |ΔV| over the reference's penumbra, in % (a soft shadow).
    PenumbraMeanAbs,
}

impl Metric {
    /// The y axis's description when every series measures this.
    pub fn axis(self) -> &'static str {
        match self {
            Metric::Misclassified => "misclassified % of receiver pixels (log)",
            Metric::PenumbraMeanAbs => "mean |ΔV| over the reference's penumbra, % (log)",
        }
    }

    /// A short name, for a legend that mixes metrics.
    pub fn short(self) -> &'static str {
        match self {
            Metric::Misclassified => "misclassified %",
            Metric::PenumbraMeanAbs => "penumbra |ΔV| %",
        }
    }
}

/// One lesson's variants.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<Point>,
    /// What `error_pct` measures.
    pub metric: Metric,
}

const X_DESC: &str =
    "median frame cost, ms: wall clock, CPU and GPU (bars: spread over frames and runs)";
/// The y axis of a plot whose series measure different errors (its
/// legend names the series that measure penumbra |ΔV|).
const Y_MIXED: &str = "misclassified % or penumbra |ΔV| % (log)";

/// The y axis's description for these series.
pub(super) fn y_desc(plotted: &[PlottedSeries]) -> &'static str {
    match plotted.first().map(|p| p.series.metric) {
        Some(m) if plotted.iter().all(|p| p.series.metric == m) => m.axis(),
        Some(_) => Y_MIXED,
        None => Metric::Misclassified.axis(),
    }
}

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

pub(super) struct PlottedSeries<'s> {
    pub(super) series: &'s Series,
    pub(super) colour: RGBColor,
    pub(super) marker: Marker,
    /// Indices of the Pareto points, by ms.
    pub(super) front: Vec<usize>,
    /// Label every point (else only the Pareto points).
    pub(super) label_all: bool,
}

/// Draws the error-vs-time plot of `plotted` into the SVG file `path`:
/// the axes fitted to the points, the baseline, the floor line, each
/// series' error bars and front, the markers, the legend column and the
/// labels, in that order (each drawn over the ones before).
pub(super) fn tradeoff_plot(
    path: &Path,
    title: &str,
    plotted: &[PlottedSeries],
    baseline_ms: Option<f64>,
    floor: f64,
    legend: Vec<LegendRow>,
) -> Result<()> {
    let points = drawable_points(plotted, floor)?;
    let baseline_ms = baseline_ms.filter(|b| b.is_finite() && *b > 0.0);
    let axes = fit_axes(&points, baseline_ms, floor);

    // The legend goes in a column right of the plot, where it hides nothing.
    let root = SVGBackend::new(path, (WIDE, HEIGHT)).into_drawing_area();
    root.fill(&WHITE)?;
    let area = titled(&root, title, legend_column_width(&legend) + LEGEND_GAP)?;
    let chart = build_chart(&area, &axes.x, &axes.y, &axes.x_desc, y_desc(plotted))?;
    let to_px = |ms: f64, err: f64| -> (f64, f64) {
        let (px, py) = chart.backend_coord(&(axes.x.t(ms), axes.y.t(err)));
        (px as f64, py as f64)
    };
    let canvas = Canvas {
        root: &root,
        plot: plot_rect(&chart),
        to_px: &to_px,
        floor,
    };
    let mut obstacles: Vec<Rect> = Vec::new();
    if let Some(b) = baseline_ms {
        draw_baseline(&canvas, b, &mut obstacles)?;
    }
    if axes.clamped {
        draw_floor_line(&canvas, &points, axes.xmin, baseline_ms, &mut obstacles)?;
    }
    let mut drawn: Vec<Drawn> = Vec::new();
    for s in plotted {
        draw_error_bars(&canvas, s, &mut obstacles)?;
        draw_front(&canvas, s, &mut obstacles)?;
        drawn.extend(drawn_points(&canvas, s));
    }
    for d in &drawn {
        obstacles.push(around(d.px, 6.0));
    }
    draw_markers(&canvas, plotted)?;
    let plot = canvas.plot;
    draw_legend_column(&root, (plot.x1 + LEGEND_GAP, plot.y0), &legend)?;
    draw_labels(&canvas, &drawn, plotted.len() == 1, &obstacles)?;
    root.present()?;
    Ok(())
}

/// A label's text height, px.
const LABEL_PX: f64 = LABEL_FONT / 1.24;

/// Whether a point can be placed: a finite positive time, a finite error.
fn drawable(p: &Point) -> bool {
    p.ms.is_finite() && p.ms > 0.0 && p.error_pct.is_finite()
}

/// Every series' drawable points; an error for a non-positive floor or no point at all.
fn drawable_points<'s>(plotted: &[PlottedSeries<'s>], floor: f64) -> Result<Vec<&'s Point>> {
    if !(floor.is_finite() && floor > 0.0) {
        return Err(anyhow!("the error floor must be positive, got {floor}"));
    }
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
    Ok(points)
}

/// A trade-off plot's axes.
struct Axes {
    x: Axis,
    y: Axis,
    x_desc: String,
    /// The least time on the x axis, ms.
    xmin: f64,
    /// Whether a point's error lies below the floor (drawn on it).
    clamped: bool,
}

/// The axes: x over the times, bars and baseline (log past 20×); y log from the floor up.
fn fit_axes(points: &[&Point], baseline_ms: Option<f64>, floor: f64) -> Axes {
    let mut xs: Vec<f64> = Vec::new();
    for p in points {
        xs.push(p.ms);
        for v in [p.ms_low, p.ms_high] {
            if v.is_finite() && v > 0.0 {
                xs.push(v);
            }
        }
    }
    if let Some(b) = baseline_ms {
        xs.push(b);
    }
    let (xmin, xmax) = (min_of(xs.iter().copied()), max_of(xs.iter().copied()));
    let x_log = xmax / xmin > 20.0;
    let x = if x_log {
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
    let x_desc = if x_log {
        format!("{X_DESC}, log scale")
    } else {
        X_DESC.to_string()
    };
    Axes {
        x,
        y: Axis::log(ymin, ymax),
        x_desc,
        xmin,
        clamped,
    }
}

/// Where a trade-off plot is drawn: the canvas, the plot's rectangle in
/// it, and a time and an error's pixel.
struct Canvas<'a, 'b> {
    root: &'a Root<'b>,
    plot: Rect,
    to_px: &'a dyn Fn(f64, f64) -> (f64, f64),
    /// Errors below it are drawn on it.
    floor: f64,
}

impl Canvas<'_, '_> {
    /// The pixel of a time (ms) and an error (%).
    fn px(&self, ms: f64, err: f64) -> (f64, f64) {
        (self.to_px)(ms, err)
    }

    /// A point's pixel: its error raised to the floor.
    fn at(&self, p: &Point) -> (f64, f64) {
        self.px(p.ms, p.error_pct.max(self.floor))
    }
}

/// The no-shadow frame's time: a dashed vertical line and its label.
fn draw_baseline(canvas: &Canvas, baseline_ms: f64, obstacles: &mut Vec<Rect>) -> Result<()> {
    let (root, plot) = (canvas.root, canvas.plot);
    let x = canvas.px(baseline_ms, canvas.floor).0;
    draw_dashed(root, (x, plot.y0), (x, plot.y1), GREY.stroke_width(2))?;
    let text = "no shadows";
    let w = text_w(text, LABEL_PX);
    let x0 = if x + 4.0 + w <= plot.x1 {
        x + 4.0
    } else {
        x - 4.0 - w
    };
    let r = Rect::new(x0, plot.y0 + 4.0, w, LABEL_PX);
    draw_text(root, text, (r.x0, r.y0), GREY)?;
    obstacles.push(r);
    obstacles.push(Rect {
        x0: x - 2.0,
        y0: plot.y0,
        x1: x + 2.0,
        y1: plot.y1,
    });
    Ok(())
}

/// The floor's dashed line and its note, where it hides the fewest points on the line.
fn draw_floor_line(
    canvas: &Canvas,
    points: &[&Point],
    xmin: f64,
    baseline_ms: Option<f64>,
    obstacles: &mut Vec<Rect>,
) -> Result<()> {
    let (root, plot, floor) = (canvas.root, canvas.plot, canvas.floor);
    let y = canvas.px(xmin, floor).1;
    draw_dashed(
        root,
        (plot.x0, y),
        (plot.x1, y),
        GREY.mix(0.6).stroke_width(1),
    )?;
    let note = format!("on this line: 0 or below {} %", fmt_num(floor));
    let (w, h) = (text_w(&note, LABEL_PX), LABEL_PX);
    let on_floor: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.error_pct < floor)
        .map(|p| canvas.px(p.ms, floor))
        .collect();
    // Above the line, else below; right first, then sliding left: the
    // first spot clear of the points on the line and of the baseline.
    let base_x = baseline_ms.map(|b| canvas.px(b, floor).0);
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
    draw_text(root, &note, (r.x0, r.y0), GREY)?;
    obstacles.push(r);
    Ok(())
}

/// One series' error bars: the spread of each point's time.
fn draw_error_bars(canvas: &Canvas, s: &PlottedSeries, obstacles: &mut Vec<Rect>) -> Result<()> {
    let bar_style = s.colour.mix(0.55).stroke_width(2);
    for p in s.series.points.iter().filter(|p| drawable(p)) {
        let (x, y) = canvas.at(p);
        let lo = if p.ms_low.is_finite() && p.ms_low > 0.0 {
            canvas.px(p.ms_low, canvas.floor).0
        } else {
            x
        };
        let hi = if p.ms_high.is_finite() && p.ms_high > 0.0 {
            canvas.px(p.ms_high, canvas.floor).0
        } else {
            x
        };
        if hi - lo >= 1.0 {
            draw_path(canvas.root, &[(lo, y), (hi, y)], bar_style)?;
            for e in [lo, hi] {
                draw_path(canvas.root, &[(e, y - 4.0), (e, y + 4.0)], bar_style)?;
            }
            obstacles.push(Rect {
                x0: lo,
                y0: y - 4.0,
                x1: hi,
                y1: y + 4.0,
            });
        }
    }
    Ok(())
}

/// One series' Pareto front, a staircase through its points by time.
fn draw_front(canvas: &Canvas, s: &PlottedSeries, obstacles: &mut Vec<Rect>) -> Result<()> {
    let step: Vec<(f64, f64)> = s
        .front
        .iter()
        .map(|&i| &s.series.points[i])
        .filter(|p| drawable(p))
        .map(|p| canvas.at(p))
        .collect();
    let mut path = Vec::new();
    for (k, &q) in step.iter().enumerate() {
        if k > 0 {
            path.push((q.0, step[k - 1].1));
        }
        path.push(q);
    }
    draw_path(canvas.root, &path, s.colour.mix(0.8).stroke_width(2))?;
    for w in path.windows(2) {
        obstacles.push(segment_box(w[0], w[1]));
    }
    Ok(())
}

/// A point as drawn, for its label.
struct Drawn {
    px: (f64, f64),
    label: String,
    colour: RGBColor,
    on_front: bool,
    /// Whether it gets a label.
    wanted: bool,
}

/// One series' drawable points, where they are drawn.
fn drawn_points(canvas: &Canvas, s: &PlottedSeries) -> Vec<Drawn> {
    let mut drawn = Vec::new();
    for (i, p) in s.series.points.iter().enumerate() {
        if !drawable(p) {
            continue;
        }
        let on_front = s.front.contains(&i);
        drawn.push(Drawn {
            px: canvas.at(p),
            label: p.label.clone(),
            colour: s.colour,
            on_front,
            wanted: s.label_all || on_front,
        });
    }
    drawn
}

/// Every series' markers, dominated first so that the front is drawn on top.
fn draw_markers(canvas: &Canvas, plotted: &[PlottedSeries]) -> Result<()> {
    for pass in [false, true] {
        for s in plotted {
            for (i, p) in s.series.points.iter().enumerate() {
                if drawable(p) && s.front.contains(&i) == pass {
                    draw_marker(canvas.root, s.marker, canvas.at(p), 5.0, s.colour, pass)?;
                }
            }
        }
    }
    Ok(())
}

/// The wanted labels, clear of `obstacles`; in the series' colour unless `single`.
fn draw_labels(canvas: &Canvas, drawn: &[Drawn], single: bool, obstacles: &[Rect]) -> Result<()> {
    // The front's first, then by time, so that placement is stable.
    let mut order: Vec<usize> = (0..drawn.len()).filter(|&k| drawn[k].wanted).collect();
    order.sort_by(|&a, &b| {
        (!drawn[a].on_front)
            .cmp(&!drawn[b].on_front)
            .then(drawn[a].px.0.total_cmp(&drawn[b].px.0))
            .then(drawn[a].px.1.total_cmp(&drawn[b].px.1))
            .then(a.cmp(&b))
    });
    let all_px: Vec<(f64, f64)> = drawn.iter().map(|d| d.px).collect();
    let widths: Vec<f64> = drawn.iter().map(|d| text_w(&d.label, LABEL_PX)).collect();
    let placed = place_labels(&all_px, &order, &widths, LABEL_PX, canvas.plot, obstacles);
    for (k, r, leader) in placed {
        let d = &drawn[k];
        if let Some(end) = leader {
            let (dx, dy) = (end.0 - d.px.0, end.1 - d.px.1);
            let len = dx.hypot(dy).max(1e-9);
            let start = (d.px.0 + dx / len * 6.5, d.px.1 + dy / len * 6.5);
            draw_path(canvas.root, &[start, end], GREY.mix(0.7).stroke_width(1))?;
        }
        let colour = if single {
            RGBColor(30, 30, 30)
        } else {
            darker(d.colour)
        };
        draw_text(canvas.root, &d.label, (r.x0, r.y0), colour)?;
    }
    Ok(())
}
