//! Chapter 01's shadow-map idea (`shadow_map_idea.svg`): a side view of
//! a light, a box caster and two receivers, each compared with the depth
//! the map stores along its ray.

use anyhow::Result;

use super::svg::{add, fill, stroke, Svg, P};

/// The shadow-map family's idea in a side view: a point light, a box caster
/// over a floor, and two receiver points, each compared with the depth the
/// map stores along its ray (the nearest surface the light sees).
const MAP_LIGHT: P = (-1.0, 6.0);
const MAP_BOX: (P, P) = ((0.2, 2.4), (2.2, 3.2));

/// The distance from the light to the first surface along the ray
/// towards `dir`: the box's sides or the floor (y = 0).
fn first_hit(dir: P) -> f64 {
    let (lo, hi) = MAP_BOX;
    let mut best = -MAP_LIGHT.1 / dir.1;
    let sides = [
        ((lo.0, lo.1), (hi.0, lo.1)),
        ((lo.0, hi.1), (hi.0, hi.1)),
        ((lo.0, lo.1), (lo.0, hi.1)),
        ((hi.0, lo.1), (hi.0, hi.1)),
    ];
    for (a, b) in sides {
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

pub(super) fn shadow_map_idea() -> Result<String> {
    let title = "The shadow-map idea: store the nearest depth per ray, then compare";
    let mut s = Svg::new(800.0, 0.0, title);
    let (lo, hi) = MAP_BOX;
    // The box's shadow on the floor, from its lower-left and upper-right corners.
    let on_floor = |p: P| MAP_LIGHT.0 + (p.0 - MAP_LIGHT.0) * MAP_LIGHT.1 / (MAP_LIGHT.1 - p.1);
    let (s0, s1) = (on_floor((lo.0, hi.1)), on_floor((hi.0, lo.1)));
    let receivers = [("A", ((s0 + s1) / 2.0, 0.0)), ("B", (s1 + 1.6, 0.0))];
    let (x0, y1, k) = (-2.0, 6.6, 62.0);
    let at = |p: P| (40.0 + (p.0 - x0) * k, 50.0 + (y1 - p.1) * k);
    s.line(
        at((x0, 0.0)),
        at((x0 + 11.5, 0.0)),
        &stroke("#8b5a2b", 3.0, ""),
    );
    s.text(
        add(at((x0, 0.0)), 4.0, 18.0),
        12.0,
        "start",
        "receiver (floor)",
    );
    let corner = at((lo.0, hi.1));
    s.rect(
        corner,
        ((hi.0 - lo.0) * k, (hi.1 - lo.1) * k),
        &fill("#c9553f", "#222"),
    );
    s.text(add(at((hi.0, hi.1)), 8.0, -4.0), 12.0, "start", "caster");
    let (a, b) = (at((s0, 0.0)), at((s1, 0.0)));
    s.line(a, b, &stroke("#555", 7.0, ""));
    s.text(add(at((s0, 0.0)), 0.0, 18.0), 12.0, "start", "shadow");
    let mut lines = Vec::new();
    for (name, p) in receivers {
        let d = (p.0 - MAP_LIGHT.0, p.1 - MAP_LIGHT.1);
        let depth = (d.0 * d.0 + d.1 * d.1).sqrt();
        let dir = (d.0 / depth, d.1 / depth);
        let stored = first_hit(dir);
        let hit = (MAP_LIGHT.0 + stored * dir.0, MAP_LIGHT.1 + stored * dir.1);
        let shadowed = depth > stored + 1e-9;
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
    ];
    let mut y = at((0.0, 0.0)).1 + 64.0;
    for (c, t) in legend {
        s.rect((40.0, y - 10.0), (14.0, 10.0), &fill(c, "none"));
        s.text((62.0, y), 12.0, "start", t);
        y += 18.0;
    }
    y = s.texts((40.0, y + 8.0), 13.0, "start", &lines);
    let note = "Pass 1 renders the scene from the light and keeps, per texel (per ray), the         distance to the nearest surface. Pass 2 takes each point the eye sees, finds its texel         and compares: farther than what the light saw means something is in between.";
    s.h = s.para((40.0, y + 4.0), 12.0, "start", 720.0, note);
    Ok(s.finish())
}
