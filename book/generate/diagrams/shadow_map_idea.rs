//! The introduction's shadow-map idea (`shadow_map_idea.svg`, Figure 0.1): a
//! side view of a light, a box caster and the floor. The shadow drawn on
//! the floor is computed from that geometry: the extreme projections of the
//! box's four corners from the light. Two receivers, one inside that
//! shadow and one outside it, are each compared with the depth the map
//! stores along its ray.

use anyhow::{ensure, Result};

use super::svg::{add, fill, stroke, Svg, P};

/// The shadow-map family's idea in a side view: a point light, a box caster
/// over a floor (y = 0, from `FLOOR.0` to `FLOOR.1`), and two receiver
/// points, each compared with the depth the map stores along its ray (the
/// nearest surface the light sees). Metres.
const MAP_LIGHT: P = (-1.0, 6.0);
const MAP_BOX: (P, P) = ((0.2, 2.4), (2.2, 3.2));
const FLOOR: (f64, f64) = (-2.0, 9.5);

/// The box's four corners.
fn corners() -> [P; 4] {
    let (lo, hi) = MAP_BOX;
    [(lo.0, lo.1), (hi.0, lo.1), (hi.0, hi.1), (lo.0, hi.1)]
}

/// Where the ray from the light through `p` (below the light) meets the floor.
fn on_floor(p: P) -> f64 {
    MAP_LIGHT.0 + (p.0 - MAP_LIGHT.0) * MAP_LIGHT.1 / (MAP_LIGHT.1 - p.1)
}

/// The box's shadow on the floor: from the least to the greatest of its
/// corners' projections from the light (a convex caster's shadow is the
/// hull of its corners' shadows). Also the two corners that bound it.
fn floor_shadow() -> ((f64, f64), (P, P)) {
    let cs = corners();
    let by_shadow = |a: &&P, b: &&P| on_floor(**a).total_cmp(&on_floor(**b));
    let first = *cs.iter().min_by(by_shadow).expect("four corners");
    let last = *cs.iter().max_by(by_shadow).expect("four corners");
    ((on_floor(first), on_floor(last)), (first, last))
}

/// The distance from the light to the first surface along the ray
/// towards `dir`: the box's sides or the floor (y = 0).
fn first_hit(dir: P) -> f64 {
    let mut best = -MAP_LIGHT.1 / dir.1;
    let cs = corners();
    for i in 0..4 {
        let (a, b) = (cs[i], cs[(i + 1) % 4]);
        let e = (b.0 - a.0, b.1 - a.1);
        let den = dir.0 * e.1 - dir.1 * e.0;
        if den.abs() < 1e-12 {
            continue;
        }
        let w = (a.0 - MAP_LIGHT.0, a.1 - MAP_LIGHT.1);
        let (t, u) = (
            (w.0 * e.1 - w.1 * e.0) / den,
            (w.0 * dir.1 - w.1 * dir.0) / den,
        );
        if t > 0.0 && (0.0..=1.0).contains(&u) {
            best = best.min(t);
        }
    }
    best
}

/// The page's scale (px a metre) and where (x, y) = (`FLOOR.0`, 6.6 m) is drawn.
const K: f64 = 62.0;
const ORIGIN: P = (40.0, 50.0);

fn at(p: P) -> P {
    (ORIGIN.0 + (p.0 - FLOOR.0) * K, ORIGIN.1 + (6.6 - p.1) * K)
}

pub(super) fn shadow_map_idea() -> Result<String> {
    let title = "The shadow-map idea: store the nearest depth per ray, then compare";
    let mut s = Svg::new(800.0, 0.0, title);
    let (lo, hi) = MAP_BOX;
    let ((s0, s1), edge_corners) = floor_shadow();
    ensure!(
        FLOOR.0 < s0 && s1 < FLOOR.1,
        "the shadow leaves the floor drawn"
    );
    // A in the middle of the shadow; B in the middle of the lit floor past it.
    let receivers = [
        ("A", ((s0 + s1) / 2.0, 0.0)),
        ("B", ((s1 + FLOOR.1) / 2.0, 0.0)),
    ];
    s.line(
        at((FLOOR.0, 0.0)),
        at((FLOOR.1, 0.0)),
        &stroke("#8b5a2b", 3.0, ""),
    );
    s.text(
        add(at((FLOOR.0, 0.0)), 4.0, 18.0),
        12.0,
        "start",
        "receiver (floor)",
    );
    // The shadow's edges: the rays through the corners that bound it.
    for (c, x) in [(edge_corners.0, s0), (edge_corners.1, s1)] {
        s.line(at(MAP_LIGHT), at((x, 0.0)), &stroke("#999", 1.0, "4,3"));
        s.circle(at(c), 3.0, &fill("#222", "none"));
    }
    s.rect(
        at((lo.0, hi.1)),
        ((hi.0 - lo.0) * K, (hi.1 - lo.1) * K),
        &fill("#c9553f", "#222"),
    );
    s.text(add(at((hi.0, hi.1)), 8.0, -4.0), 12.0, "start", "caster");
    s.line(at((s0, 0.0)), at((s1, 0.0)), &stroke("#555", 7.0, ""));
    s.text(add(at((s0, 0.0)), 0.0, 18.0), 12.0, "start", "shadow");
    let mut lines = Vec::new();
    for (name, p) in receivers {
        let d = (p.0 - MAP_LIGHT.0, p.1 - MAP_LIGHT.1);
        let depth = (d.0 * d.0 + d.1 * d.1).sqrt();
        let dir = (d.0 / depth, d.1 / depth);
        let stored = first_hit(dir);
        let hit = (MAP_LIGHT.0 + stored * dir.0, MAP_LIGHT.1 + stored * dir.1);
        let shadowed = depth > stored + 1e-9;
        // The layout puts A in the shadow and B out of it: the map must agree.
        ensure!(
            shadowed == (s0..=s1).contains(&p.0),
            "{name}: the map's verdict disagrees with the shadow drawn"
        );
        let colour = ["#2ca02c", "#d62728"][shadowed as usize];
        s.line(at(MAP_LIGHT), at(hit), &stroke("#a80", 2.0, ""));
        if shadowed {
            s.line(at(hit), at(p), &stroke("#a80", 1.5, "5,4"));
        }
        s.circle(at(hit), 5.0, &fill("#1f5fbf", "none"));
        s.circle(at(p), 6.0, &fill(colour, "#222"));
        s.text(add(at(p), 0.0, 34.0), 14.0, "middle", name);
        let (sign, verdict) = if shadowed {
            (">", "in shadow")
        } else {
            ("≤", "lit")
        };
        lines.push(format!(
            "{name}: its depth {depth:.2} {sign} stored {stored:.2} → {verdict}"
        ));
    }
    s.circle(at(MAP_LIGHT), 10.0, &fill("#ffd400", "#a80"));
    s.text(add(at(MAP_LIGHT), 14.0, 5.0), 12.0, "start", "light");
    let legend = [
        (
            "#1f5fbf",
            "the depth the map stores: the first surface along the ray",
        ),
        ("#2ca02c", "receiver point as far as the stored depth: lit"),
        (
            "#d62728",
            "receiver point farther than the stored depth: shadowed",
        ),
        (
            "#999",
            "the rays through the box's outermost corners: the shadow's edges",
        ),
    ];
    let mut y = at((0.0, 0.0)).1 + 64.0;
    for (c, t) in legend {
        s.rect((40.0, y - 10.0), (14.0, 10.0), &fill(c, "none"));
        s.text((62.0, y), 12.0, "start", t);
        y += 18.0;
    }
    y = s.texts((40.0, y + 8.0), 13.0, "start", &lines);
    let note = "Pass 1 renders the scene from the light and keeps, per texel (per ray), the \
        distance to the nearest surface. Pass 2 takes each point the eye sees, finds its texel \
        and compares: farther than what the light saw means something is in between.";
    s.h = s.para((40.0, y + 4.0), 12.0, "start", 720.0, note);
    Ok(s.finish())
}

#[cfg(test)]
mod tests {
    use super::super::svg::tests::{elements, is, number, texts};
    use super::*;

    /// Where the segment from the light to the floor point (x, 0) first
    /// enters the box, as a fraction of its length (the slab method), if
    /// it does: the box hides that floor point from the light.
    fn enters_box(x: f64) -> Option<f64> {
        let (lo, hi) = MAP_BOX;
        let d = (x - MAP_LIGHT.0, -MAP_LIGHT.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (o, d, lo, hi) in [
            (MAP_LIGHT.0, d.0, lo.0, hi.0),
            (MAP_LIGHT.1, d.1, lo.1, hi.1),
        ] {
            if d.abs() < 1e-15 {
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 < t1).then_some(t0)
    }

    /// The drawing's metres from its pixels, read off the caster's
    /// rectangle (which is `MAP_BOX`): x and y.
    fn page_to_metres(svg: &str) -> (impl Fn(f64) -> f64, impl Fn(f64) -> f64) {
        let rects = elements(svg, "rect");
        let r = rects
            .iter()
            .find(|r| is(r, "fill", "#c9553f"))
            .expect("the caster's rectangle");
        let (lo, hi) = MAP_BOX;
        let (x, y, w, h) = (
            number(r, "x"),
            number(r, "y"),
            number(r, "width"),
            number(r, "height"),
        );
        let (kx, ky) = (w / (hi.0 - lo.0), h / (hi.1 - lo.1));
        (
            move |px: f64| lo.0 + (px - x) / kx,
            move |py: f64| hi.1 - (py - y) / ky,
        )
    }

    /// The shadow drawn on the floor (the 7 px grey band) spans exactly
    /// the floor points the box hides from the light, found by casting the
    /// light's ray to every millimetre of the floor against the box.
    #[test]
    fn drawn_shadow_is_the_floor_the_box_hides() {
        let svg = shadow_map_idea().unwrap();
        let (mx, my) = page_to_metres(&svg);
        let lines = elements(&svg, "line");
        let band = lines
            .iter()
            .find(|l| is(l, "stroke", "#555") && is(l, "stroke-width", "7"))
            .expect("the shadow band");
        let (a, b) = (mx(number(band, "x1")), mx(number(band, "x2")));
        assert!(
            my(number(band, "y1")).abs() < 1e-3,
            "the band is on the floor"
        );
        let step = 1e-3;
        let n = ((FLOOR.1 - FLOOR.0) / step) as usize;
        let hidden: Vec<f64> = (0..=n)
            .map(|i| FLOOR.0 + i as f64 * step)
            .filter(|&x| enters_box(x).is_some())
            .collect();
        let (h0, h1) = (hidden[0], hidden[hidden.len() - 1]);
        assert_eq!(
            hidden.len(),
            ((h1 - h0) / step).round() as usize + 1,
            "one stretch of shadow"
        );
        let tol = step + 1e-3;
        assert!(
            (a.min(b) - h0).abs() < tol && (a.max(b) - h1).abs() < tol,
            "Figure 0.1 draws the shadow from {:.3} to {:.3} m; the box hides {h0:.3} to {h1:.3} m \
             of the floor from the light",
            a.min(b),
            a.max(b)
        );
    }

    /// Each receiver drawn is red where the box hides it and green where
    /// it does not, one of each, and the comparison printed for it gives
    /// its distance from the light and the first surface on its ray
    /// (the box's entry, or the floor), computed here with the slab method.
    #[test]
    fn receivers_are_lit_and_shadowed_where_the_geometry_says() {
        let svg = shadow_map_idea().unwrap();
        let (mx, my) = page_to_metres(&svg);
        let circles = elements(&svg, "circle");
        let words = texts(&svg);
        let mut verdicts = Vec::new();
        for name in ["A", "B"] {
            let label = words.iter().find(|t| t.2 == name).expect(name);
            let dot = circles
                .iter()
                .filter(|c| number(c, "r") == 6.0)
                .min_by(|c, d| {
                    let dx = |c: &&std::collections::HashMap<String, String>| {
                        (number(c, "cx") - label.0).abs()
                    };
                    dx(c).total_cmp(&dx(d))
                })
                .expect("a receiver dot");
            let p = (mx(number(dot, "cx")), my(number(dot, "cy")));
            assert!(p.1.abs() < 1e-3, "{name} is on the floor");
            let hidden = enters_box(p.0);
            let shadowed = hidden.is_some();
            let colour = ["#2ca02c", "#d62728"][shadowed as usize];
            assert_eq!(dot["fill"], colour, "{name} at x {:.3} m", p.0);
            let depth = (p.0 - MAP_LIGHT.0).hypot(p.1 - MAP_LIGHT.1);
            let stored = depth * hidden.unwrap_or(1.0);
            let (sign, verdict) = [("≤", "lit"), (">", "in shadow")][shadowed as usize];
            let line =
                format!("{name}: its depth {depth:.2} {sign} stored {stored:.2} → {verdict}");
            assert!(
                words.iter().any(|t| t.2 == line),
                "Figure 0.1 lacks {line:?}"
            );
            verdicts.push(shadowed);
        }
        assert!(verdicts.contains(&true) && verdicts.contains(&false));
    }
}
