//! Picture (a), the similar triangles (`soft_similar_triangles.svg`): the
//! rays from the emitter's edges through the plank's edge, which bound the
//! penumbra on the floor, and the footprint a floor point sees on the
//! plank's plane.

use super::setup::{f, Setup, EMITTER, FOOT, PLANK, RAY};
use crate::diagrams::svg::{add, fill, stroke, Svg, INK, P};

/// Where the line through `a` and `b` (x, height) meets height `y`.
fn at_height(a: P, b: P, y: f64) -> f64 {
    a.0 + (b.0 - a.0) * (y - a.1) / (b.1 - a.1)
}

/// A two-headed dimension line from `a` to `b`.
fn dimension(s: &mut Svg, a: P, b: P) {
    let m = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    s.arrow(m, a, "#222");
    s.arrow(m, b, "#222");
}

/// The penumbra's similar triangles on the default scene's plank, in a
/// vertical section: (a) the emitter's two ends through the plank's edge
/// onto the floor, w_penumbra; (b) the emitter seen from a floor point p,
/// its footprint 2 r_b on the plank's plane.
pub(super) fn similar_triangles(u: &Setup) -> String {
    let (w, title) = (
        800.0,
        "The penumbra's similar triangles on lesson 10's default scene",
    );
    let mut s = Svg::new(w, 0.0, title);
    // Heights measured down from the light: the emitter's plane at 0, the
    // plank's top at d_b, the floor at d_r (the scene's vertical
    // distances; the emitter drawn parallel to the floor).
    let d_r = u.light.y - u.floor_y;
    let d_b = u.light.y - u.plank_top[0].y;
    let r = u.radius;
    // Across, the scale is stretched: similar triangles survive it.
    let (ky, top) = (100.0, 92.0);
    let kx = 4.0 * ky;
    let ends = [(-r, 0.0), (r, 0.0)];
    let mut bottom: f64 = 0.0;
    for (panel, left) in [(0, 0.0), (1, w / 2.0)] {
        let cx = left + 235.0;
        let px = |p: P| (cx + p.0 * kx, top + p.1 * ky);
        let heading = [
            "(a) the penumbra on the receiver",
            "(b) the emitter seen from p: its footprint",
        ][panel];
        s.text((left + 20.0, 54.0), 14.0, "start", heading);
        // The emitter, the plank (its edge at x = 0, reaching left), the floor.
        s.line(px(ends[0]), px(ends[1]), &stroke(EMITTER, 6.0, ""));
        s.text(
            add(px((0.0, 0.0)), 0.0, -12.0),
            12.0,
            "middle",
            &format!("emitter: radius R = w_light = {} m", f(r, 2)),
        );
        let plank_left = -0.42;
        let (a, b) = (px((plank_left, d_b)), px((0.0, d_b + 0.04)));
        s.rect(a, (b.0 - a.0, b.1 - a.1), &fill(PLANK, "#5a3f75"));
        s.text(add(a, 0.0, -6.0), 12.0, "start", "blocker (the plank)");
        s.line(px((-0.52, d_r)), px((0.36, d_r)), INK);
        // Depths, on the left.
        let x0 = left + 14.0;
        dimension(&mut s, (x0, px((0.0, 0.0)).1), (x0, px((0.0, d_b)).1));
        dimension(
            &mut s,
            (x0 - 8.0, px((0.0, 0.0)).1),
            (x0 - 8.0, px((0.0, d_r)).1),
        );
        s.text(
            (x0 + 6.0, px((0.0, d_b / 2.0)).1),
            13.0,
            "start",
            &format!("d_b = {} m", f(d_b, 2)),
        );
        s.text(
            (x0 + 6.0, px((0.0, d_b + 0.35)).1),
            13.0,
            "start",
            &format!("d_r = {} m", f(d_r, 2)),
        );
        let floor = px((0.0, d_r)).1;
        if panel == 0 {
            // Each end of the emitter through the edge, down to the floor.
            let edge = (0.0, d_b);
            let hits: Vec<f64> = ends.iter().map(|&q| at_height(q, edge, d_r)).collect();
            for (&q, &x) in ends.iter().zip(&hits) {
                s.line(px(q), px((x, d_r)), &stroke(RAY, 1.5, ""));
            }
            let (lo, hi) = (hits[0].min(hits[1]), hits[0].max(hits[1]));
            // The floor: umbra, penumbra, lit.
            let band = |s: &mut Svg, x0: f64, x1: f64, c: &str| {
                let (a, b) = (px((x0, d_r)), px((x1, d_r)));
                s.rect(add(a, 0.0, 1.0), (b.0 - a.0, 7.0), &fill(c, c));
            };
            band(&mut s, -0.52, lo, "#555");
            band(&mut s, lo, hi, "#aaa");
            dimension(
                &mut s,
                (px((lo, 0.0)).0, floor + 22.0),
                (px((hi, 0.0)).0, floor + 22.0),
            );
            s.text(
                (px((0.0, 0.0)).0, floor + 44.0),
                13.0,
                "middle",
                &format!("2 w_penumbra = {} m", f(hi - lo, 3)),
            );
            s.text((px((-0.40, 0.0)).0, floor + 22.0), 12.0, "start", "umbra");
            s.text((px((0.33, 0.0)).0, floor + 22.0), 12.0, "end", "lit");
            bottom = bottom.max(floor + 44.0);
        } else {
            // From p, under the edge, to the emitter's two ends.
            let p = (0.0, d_r);
            let cross: Vec<f64> = ends.iter().map(|&q| at_height(p, q, d_b)).collect();
            for &q in &ends {
                s.line(px(p), px(q), &stroke(RAY, 1.5, ""));
            }
            let (lo, hi) = (cross[0].min(cross[1]), cross[0].max(cross[1]));
            let y = px((0.0, d_b)).1 - 9.0;
            s.line(
                (px((lo, 0.0)).0, y),
                (px((hi, 0.0)).0, y),
                &stroke(FOOT, 4.0, ""),
            );
            s.text(
                (px((hi, 0.0)).0 + 8.0, y + 4.0),
                13.0,
                "start",
                &format!("2 r_b = {} m", f(hi - lo, 3)),
            );
            s.circle(px(p), 4.0, &fill("#222", "#222"));
            s.text(add(px(p), 0.0, 22.0), 13.0, "middle", "p");
            bottom = bottom.max(floor + 22.0);
        }
    }
    let note = format!(
        "A vertical section through the plank's edge (scenes/lesson_10.toml): the light {} m \
         above the floor, its disk of radius R = {} m drawn parallel to the floor, the plank's \
         top {} m below it; the distances are measured vertically. Across, the scale is 4 \
         times the vertical one; lines stay lines and the ratios hold. The widths are where the \
         drawn rays cross the planes, not a formula: (a) the edges of the emitter through the \
         plank's edge bound the penumbra on the floor, 2 w_penumbra wide, with Fernando's \
         w_penumbra = (d_r − d_b) w_light / d_b and w_light = R; (b) the rays from p to the \
         emitter's edges cross the blocker's plane on the footprint of radius \
         r_b = R (d_r − d_b) / d_r, of which the plank covers half: p, under the edge, sees \
         half the emitter.",
        f(d_r, 2),
        f(r, 2),
        f(d_b, 2),
    );
    s.h = s.para((20.0, bottom + 30.0), 12.0, "start", w - 40.0, &note);
    s.finish()
}
