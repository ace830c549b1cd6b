//! The legend: a column of swatches and wrapped texts right of the plot,
//! where it hides no data.

use anyhow::Result;
use plotters::prelude::*;

use super::draw::{
    draw_dashed, draw_marker, draw_path, draw_text, ipx, text_w, Marker, Rect, Root,
};
use super::LABEL_FONT;

/// The widest a legend line may be outside the plot before it wraps, px.
const LEGEND_TEXT_MAX: f64 = 190.0;

pub(super) enum Swatch {
    None,
    Marker(Marker, RGBColor, bool),
    Line(RGBColor, bool),
    LineMarker(Marker, RGBColor),
}

pub(super) struct LegendRow {
    pub(super) swatch: Swatch,
    pub(super) text: String,
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
pub(super) const LEGEND_GAP: f64 = 12.0;
/// Between two rows of a legend column, px.
const LEGEND_ROW_GAP: f64 = 6.0;

/// The width of the legend column [`draw_legend_column`] draws.
pub(super) fn legend_column_width(rows: &[LegendRow]) -> f64 {
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
pub(super) fn legend_column_height(rows: &[LegendRow]) -> f64 {
    let text_px = LABEL_FONT / 1.24;
    let line_h = text_px + 4.0;
    let lines: usize = rows.iter().map(|r| wrap(&r.text, text_px).len()).sum();
    LEGEND_PAD * 2.0 + line_h * lines as f64 - 4.0 * rows.len() as f64
        + LEGEND_ROW_GAP * rows.len().saturating_sub(1) as f64
}

/// Draws the legend as a box with its top-left corner at `at`, outside the
/// plot (long texts wrapped), so that it hides no data.
pub(super) fn draw_legend_column(root: &Root, at: (f64, f64), rows: &[LegendRow]) -> Result<()> {
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
