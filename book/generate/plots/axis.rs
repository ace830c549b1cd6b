//! Axes: linear and log axes in plotting space, their ticks and tick
//! labels, and the plotters coordinate that draws them.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};

use super::draw::text_w;
use super::TICK_FONT;

/// One axis in plotting space: log axes are drawn in log10(value), so the
/// chart is always linear f64 and the ticks are chosen here.
pub(super) struct Axis {
    log: bool,
    lo: f64,
    hi: f64,
    pub(super) bold: Vec<f64>,
    light: Vec<f64>,
    decimals: usize,
    /// Log labels in full ([`fmt_exact`]) rather than rounded ([`fmt_num`]).
    exact: bool,
}

impl Axis {
    /// A linear axis over [min, max] with some room, ticks at 1, 2 or 5
    /// times a power of ten; it does not go below 0 when min >= 0.
    pub(super) fn linear(min: f64, max: f64) -> Axis {
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
    pub(super) fn log(min: f64, max: f64) -> Axis {
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
    pub(super) fn ticks_at(mut self, values: &[f64]) -> Axis {
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
    pub(super) fn t(&self, v: f64) -> f64 {
        if self.log {
            v.log10()
        } else {
            v
        }
    }

    /// A tick label for a value in plotting space.
    pub(super) fn label(&self, t: f64) -> String {
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
pub(super) fn fmt_num(v: f64) -> String {
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
pub(super) fn fmt_exact(v: f64) -> String {
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
pub(super) struct Ticks {
    lo: f64,
    hi: f64,
    pub(super) bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ticks {
    pub(super) fn of(a: &Axis) -> Ticks {
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
