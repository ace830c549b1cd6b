//! Pixel-space drawing: rectangles, text width estimates, paths, dashed
//! lines, text and markers.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{FONT, LABEL_FONT};

pub(super) type Root<'a> = DrawingArea<SVGBackend<'a>, Shift>;

pub(super) fn ipx(p: (f64, f64)) -> (i32, i32) {
    (p.0.round() as i32, p.1.round() as i32)
}

pub(super) fn draw_path(root: &Root, pts: &[(f64, f64)], style: ShapeStyle) -> Result<()> {
    if pts.len() >= 2 {
        root.draw(&PathElement::new(
            pts.iter().map(|&p| ipx(p)).collect::<Vec<_>>(),
            style,
        ))?;
    }
    Ok(())
}

pub(super) fn draw_dashed(
    root: &Root,
    a: (f64, f64),
    b: (f64, f64),
    style: ShapeStyle,
) -> Result<()> {
    root.draw(&DashedPathElement::new(vec![ipx(a), ipx(b)], 6, 4, style))?;
    Ok(())
}

/// Text with its top-left corner at `at`.
pub(super) fn draw_text(root: &Root, text: &str, at: (f64, f64), colour: RGBColor) -> Result<()> {
    let style = TextStyle::from((FONT, LABEL_FONT).into_font())
        .color(&colour)
        .pos(Pos::new(HPos::Left, VPos::Top));
    root.draw(&Text::new(text.to_string(), ipx(at), style))?;
    Ok(())
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
    TriangleDown,
    Hexagon,
}

impl Marker {
    pub(super) const ALL: [Marker; 6] = [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
        Marker::TriangleDown,
        Marker::Hexagon,
    ];
}

/// A marker of radius `r` at `c`: filled, or hollow (white inside, outlined).
pub(super) fn draw_marker(
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

pub(super) fn darker(c: RGBColor) -> RGBColor {
    let f = |v: u8| (v as f64 * 0.7).round() as u8;
    RGBColor(f(c.0), f(c.1), f(c.2))
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rect {
    pub(super) x0: f64,
    pub(super) y0: f64,
    pub(super) x1: f64,
    pub(super) y1: f64,
}

impl Rect {
    pub(super) fn new(x0: f64, y0: f64, w: f64, h: f64) -> Rect {
        Rect {
            x0,
            y0,
            x1: x0 + w,
            y1: y0 + h,
        }
    }
    pub(super) fn overlap(&self, o: &Rect) -> f64 {
        let w = self.x1.min(o.x1) - self.x0.max(o.x0);
        let h = self.y1.min(o.y1) - self.y0.max(o.y0);
        if w > 0.0 && h > 0.0 {
            w * h
        } else {
            0.0
        }
    }
    pub(super) fn contains(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }
    pub(super) fn grow(&self, d: f64) -> Rect {
        Rect {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }
    /// The point of the rectangle nearest to `p`.
    pub(super) fn nearest(&self, p: (f64, f64)) -> (f64, f64) {
        (p.0.clamp(self.x0, self.x1), p.1.clamp(self.y0, self.y1))
    }
    /// The area outside `area`.
    pub(super) fn outside(&self, area: &Rect) -> f64 {
        (self.x1 - self.x0) * (self.y1 - self.y0) - self.overlap(area)
    }
}

/// Estimated width of `text` at `px` pixels in a sans-serif font.
pub(super) fn text_w(text: &str, px: f64) -> f64 {
    0.56 * px * text.chars().count() as f64 + 2.0
}

pub(super) fn around(c: (f64, f64), r: f64) -> Rect {
    Rect {
        x0: c.0 - r,
        y0: c.1 - r,
        x1: c.0 + r,
        y1: c.1 + r,
    }
}

pub(super) fn segment_box(a: (f64, f64), b: (f64, f64)) -> Rect {
    Rect {
        x0: a.0.min(b.0) - 1.5,
        y0: a.1.min(b.1) - 1.5,
        x1: a.0.max(b.0) + 1.5,
        y1: a.1.max(b.1) + 1.5,
    }
}
