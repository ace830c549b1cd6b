//! What chapter 05's pictures share: their colours, points fitted into a
//! panel, a segment clipped to it, the light's marker, a 3D point to
//! pixels, numbers and vectors as they print them, and legend rows.

use common::glam::{DMat4, DVec3, DVec4};

use crate::diagrams::svg::{add, fill, Svg, P};

pub(super) const BLUE: &str = "#1f5fbf";
pub(super) const LIT: &str = "#ffd66e";
pub(super) const AWAY: &str = "#a9b1bc";
pub(super) const SIL: &str = "#d62728";

/// Points `pts` fitted, aspect kept, into the rectangle at `at` of `size`.
pub(super) struct Fit {
    pub(super) k: f64,
    pub(super) from: P,
    pub(super) to: P,
}

impl Fit {
    pub(super) fn new(pts: &[P], at: P, size: P) -> Fit {
        let lo = pts
            .iter()
            .fold((f64::MAX, f64::MAX), |a, p| (a.0.min(p.0), a.1.min(p.1)));
        let hi = pts
            .iter()
            .fold((f64::MIN, f64::MIN), |a, p| (a.0.max(p.0), a.1.max(p.1)));
        let k = (size.0 / (hi.0 - lo.0)).min(size.1 / (hi.1 - lo.1));
        let pad = (
            (size.0 - k * (hi.0 - lo.0)) / 2.0,
            (size.1 - k * (hi.1 - lo.1)) / 2.0,
        );
        Fit {
            k,
            from: lo,
            to: add(at, pad.0, pad.1),
        }
    }
    pub(super) fn at(&self, p: P) -> P {
        (
            self.to.0 + (p.0 - self.from.0) * self.k,
            self.to.1 + (p.1 - self.from.1) * self.k,
        )
    }
}

/// The point of the segment `from → to` farthest along it that is still
/// inside the rectangle `lo`..`hi` (`from` is inside).
pub(super) fn clip(from: P, to: P, lo: P, hi: P) -> P {
    let mut t: f64 = 1.0;
    for (f, d, l, h) in [
        (from.0, to.0 - from.0, lo.0, hi.0),
        (from.1, to.1 - from.1, lo.1, hi.1),
    ] {
        if d > 1e-12 {
            t = t.min((h - f) / d);
        } else if d < -1e-12 {
            t = t.min((l - f) / d);
        }
    }
    (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1))
}

/// The light's marker, or where the way to it leaves the panel.
pub(super) fn light_marker(s: &mut Svg, centre: P, light: P, lo: P, hi: P) {
    let end = clip(centre, light, lo, hi);
    if end == light {
        s.circle(light, 10.0, &fill("#ffd400", "#a80"));
        s.text(add(light, -14.0, 5.0), 13.0, "end", "point light");
    } else {
        s.arrow(centre, end, "#a80");
        s.text(add(end, -10.0, 4.0), 13.0, "end", "to the point light");
    }
}

/// A 3D point through a view-projection, to pixels of a `w`×`h` image
/// (y down). `None` behind the eye.
pub(super) fn pixel(m: DMat4, w: f64, h: f64, p: DVec4) -> Option<P> {
    let c = m * p;
    (c.w > 1e-9).then(|| ((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h))
}

pub(super) fn v3(v: DVec3) -> String {
    let c = |x: f64| signed_f(x, 2);
    format!("({}, {}, {})", c(v.x), c(v.y), c(v.z))
}

/// A number with `d` decimals and a true minus sign.
pub(super) fn signed_f(x: f64, d: usize) -> String {
    format!("{:.*}", d, x + 0.0).replace('-', "−")
}

/// Legend rows (colour swatch, text) from `top`; returns the next baseline.
pub(super) fn legend(s: &mut Svg, x: f64, top: f64, rows: &[(String, String)]) -> f64 {
    let mut y = top;
    for (style, t) in rows {
        s.rect((x, y - 10.0), (16.0, 11.0), style);
        y = s.para((x + 24.0, y), 12.0, "start", s.w - x - 40.0, t) + 3.0;
    }
    y
}
