//! The frame of every plot: the title fitted to the canvas, and the chart
//! (mesh, tick labels, axis descriptions) on the area below it.

use anyhow::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axis::{Axis, Ticks};
use super::draw::{ipx, text_w, Rect, Root};
use super::{DESC_FONT, FONT, MARGIN, TICK_FONT, TITLE_FONT};

/// A title is shrunk down to this size (px) before it is wrapped.
const TITLE_MIN_PX: f64 = 14.0;

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Ticks, Ticks>>;

pub(super) fn build_chart<'a, 'b>(
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
pub(super) fn titled<'b>(root: &Root<'b>, title: &str, right: f64) -> Result<Root<'b>> {
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

pub(super) fn plot_rect(chart: &Chart<'_, '_>) -> Rect {
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    Rect {
        x0: xr.start as f64,
        y0: yr.start as f64,
        x1: xr.end as f64,
        y1: yr.end as f64,
    }
}
