//! Picture (a), the similar triangles (`soft_similar_triangles.svg`): the
//! rays from the emitter's edges through the plank's edge, which bound the
//! penumbra on the receiver's plane, and the footprint the receiver p sees
//! on the plank's plane. The distances are the text's: from the light,
//! along its axis ([`Setup::along_axis`]).

use super::setup::{f, Setup, EMITTER, FOOT, PLANK, RAY};
use crate::diagrams::svg::{add, fill, stroke, Svg, INK, P};

/// Where the line through `a` and `b` (across, distance along the axis)
/// meets distance `y`.
fn at_height(a: P, b: P, y: f64) -> f64 {
    a.0 + (b.0 - a.0) * (y - a.1) / (b.1 - a.1)
}

/// Pixels per metre along the axis, and where the emitter's plane is drawn.
const KY: f64 = 84.0;
const TOP: f64 = 92.0;

/// A two-headed dimension line from `a` to `b`.
fn dimension(s: &mut Svg, a: P, b: P) {
    let m = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    s.arrow(m, a, "#222");
    s.arrow(m, b, "#222");
}

/// What the picture draws, in a section through the light's axis: across,
/// the offset from the line through the emitter's centre and p (p and the
/// plank's edge at 0); down, the distance from the light along its axis.
pub(super) struct Triangles {
    /// The receiver's and the blocker's planes, square to the axis.
    pub(super) d_r: f64,
    pub(super) d_b: f64,
    /// The emitter's radius R.
    pub(super) r: f64,
    /// (a) Where the rays from the emitter's two ends through the plank's
    /// edge meet the receiver's plane: the penumbra, lowest first.
    pub(super) penumbra: (f64, f64),
    /// (b) Where the rays from p to the emitter's two ends cross the
    /// blocker's plane: the footprint, lowest first.
    pub(super) footprint: (f64, f64),
}

/// The triangles, by intersecting the drawn rays with the planes (not by
/// the formulas the text derives from them).
pub(super) fn triangles(u: &Setup) -> Triangles {
    let (d_r, d_b, r) = (u.d_r, u.d_b, u.radius);
    let ends = [(-r, 0.0), (r, 0.0)];
    let sorted = |v: Vec<f64>| (v[0].min(v[1]), v[0].max(v[1]));
    let penumbra = sorted(
        ends.iter()
            .map(|&q| at_height(q, (0.0, d_b), d_r))
            .collect(),
    );
    let footprint = sorted(
        ends.iter()
            .map(|&q| at_height((0.0, d_r), q, d_b))
            .collect(),
    );
    Triangles {
        d_r,
        d_b,
        r,
        penumbra,
        footprint,
    }
}

/// The penumbra's similar triangles at the default scene's plank, in a
/// section through the light's axis: (a) the emitter's two ends through
/// the plank's edge onto the receiver's plane, w_penumbra; (b) the emitter
/// seen from p, its footprint 2 r_b on the plank's plane.
pub(super) fn similar_triangles(u: &Setup) -> String {
    let t = triangles(u);
    let (d_r, d_b, r) = (t.d_r, t.d_b, t.r);
    let (w, title) = (
        800.0,
        "The penumbra's similar triangles on lesson 10's default scene",
    );
    let mut s = Svg::new(w, 0.0, title);
    // Down: the distance along the axis, the emitter's plane at 0. Across,
    // the scale is stretched: similar triangles survive it.
    let (ky, top) = (KY, TOP);
    let kx = 4.0 * ky;
    let ends = [(-r, 0.0), (r, 0.0)];
    let mut bottom: f64 = 0.0;
    for (panel, left) in [(0, 0.0), (1, w / 2.0)] {
        let cx = left + 235.0;
        let px = |p: P| (cx + p.0 * kx, top + p.1 * ky);
        let heading = [
            "(a) the penumbra on the receiver's plane",
            "(b) the emitter seen from p: its footprint",
        ][panel];
        s.text((left + 20.0, 54.0), 14.0, "start", heading);
        // The emitter, the plank (its edge at 0, reaching left), the
        // receiver's plane.
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
        // Distances along the axis, each label beside its own span: d_b
        // and the rest of the way to the receiver, d_r − d_b, on the left;
        // d_r, the whole way, on the right.
        let x0 = left + 14.0;
        dimension(&mut s, (x0, px((0.0, 0.0)).1), (x0, px((0.0, d_b)).1));
        dimension(&mut s, (x0, px((0.0, d_b)).1), (x0, px((0.0, d_r)).1));
        let x1 = left + w / 2.0 - 14.0;
        dimension(&mut s, (x1, px((0.0, 0.0)).1), (x1, px((0.0, d_r)).1));
        s.text(
            (x0 + 6.0, px((0.0, d_b / 2.0)).1),
            13.0,
            "start",
            &format!("d_b = {} m", f(d_b, 2)),
        );
        s.text(
            (x0 + 6.0, px((0.0, (d_b + d_r) / 2.0)).1 + 4.0),
            13.0,
            "start",
            &format!("d_r − d_b = {} m", f(d_r - d_b, 2)),
        );
        s.text(
            (x1 - 6.0, px((0.0, d_r / 2.0)).1),
            13.0,
            "end",
            &format!("d_r = {} m", f(d_r, 2)),
        );
        let floor = px((0.0, d_r)).1;
        if panel == 0 {
            // Each end of the emitter through the edge, to the receiver's plane.
            for (&q, &x) in ends.iter().zip([t.penumbra.1, t.penumbra.0].iter()) {
                s.line(px(q), px((x, d_r)), &stroke(RAY, 1.5, ""));
            }
            let (lo, hi) = t.penumbra;
            // The receiver's plane: umbra, penumbra, lit.
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
            for &q in &ends {
                s.line(px(p), px(q), &stroke(RAY, 1.5, ""));
            }
            let (lo, hi) = t.footprint;
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
    // The way from the plank's edge down to p, on the ray from the light:
    // its drop, its length, its slant from the vertical and from the axis.
    let way = u.p - u.edge;
    let slant = (-way.y / way.length()).acos().to_degrees();
    let off_axis = (way.normalize().dot(u.axis)).acos().to_degrees();
    let note = format!(
        "A section through the light's axis (scenes/lesson_10.toml). p is the floor point under \
         the middle of the plank's far long edge, as the light's centre sees it; d_r and d_b are \
         the distances of p and of that edge from the light, measured along its axis, as the \
         text defines them and the shadow map stores them. The edge is {} m above the floor; \
         the ray from it down to p falls {}° from the vertical, {} m long, and along the \
         light's axis ({}° from the ray) it measures d_r − d_b = {} m. \
         The planes are the derivation's, \
         square to the axis, with the emitter's disk of radius R = {} m; p is drawn under the \
         emitter's centre (sliding each plane sideways keeps every width on it), and across, \
         the scale is 4 times the one along the axis: lines stay lines and the ratios hold. \
         The widths are where the drawn rays cross the planes, not a formula: (a) the edges of \
         the emitter through the plank's edge bound the penumbra, 2 w_penumbra wide, with \
         Fernando's w_penumbra = (d_r − d_b) w_light / d_b and w_light = R; (b) the rays from p \
         to the emitter's edges cross the blocker's plane on the footprint of radius \
         r_b = R (d_r − d_b) / d_r, of which the plank covers half: p, under the edge, sees \
         half the emitter.",
        f(-way.y, 2),
        f(slant, 0),
        f(way.length(), 2),
        f(off_axis, 0),
        f(d_r - d_b, 2),
        f(r, 2),
    );
    s.h = s.para((20.0, bottom + 30.0), 12.0, "start", w - 40.0, &note);
    s.finish()
}

#[cfg(test)]
mod tests {

    use common::glam::DVec3;
    use common::scene::camera::light_view_proj;
    use common::scene::Scene;

    use super::super::setup::Setup;
    use super::*;

    /// The numbers the SVG prints after `label = `, in metres (`d_b = `, not
    /// the `d_b = ` of `d_r − d_b = `).
    fn printed(svg: &str, label: &str) -> Vec<f64> {
        svg.match_indices(&format!("{label} = "))
            .filter(|(i, _)| !svg[..*i].ends_with("− "))
            .filter_map(|(i, m)| {
                let rest = &svg[i + m.len()..];
                rest.split(" m").next()?.parse().ok()
            })
            .collect()
    }

    /// The printed distances are the text's definition for the drawn p,
    /// computed here another way: the light's own matrix (its clip w is the
    /// distance along the axis) at p, and at the point where the segment
    /// from p to the light crosses the plank's top (found from the scene's
    /// triangles, not from the figure's setup); the footprint's radius is
    /// R (d_r − d_b) / d_r and the penumbra's half width R (d_r − d_b) / d_b.
    #[test]
    fn printed_distances_and_widths_follow_the_texts_definition() {
        let root = &crate::repo_root();
        let scene = Scene::load(&root.join("scenes/lesson_10.toml")).unwrap();
        let u = Setup::from_scene(&scene).unwrap();
        let m = light_view_proj(&scene, 0).unwrap();
        let w = |x: DVec3| (m * x.as_vec3().extend(1.0)).w as f64;
        // The plank: the caster whose top lies 60 cm up, by its triangles.
        let tris = scene.world_triangles();
        let top = tris
            .iter()
            .filter(|(_, o)| *o == 4)
            .flat_map(|(t, _)| t.iter().map(|p| p.y as f64))
            .fold(f64::MIN, f64::max);
        // (The triangles are origin-relative; the scene's floor is at y = 0.)
        let o = scene.origin().y;
        assert!(
            (top + o - 0.62).abs() < 1e-3,
            "the plank's top at {}",
            top + o
        );
        // p is on the floor; the blocker in front of it on its ray to the light.
        assert!((u.p.y + o).abs() < 1e-6, "p is not on the floor: {}", u.p);
        let b = u.light + (u.p - u.light) * ((u.light.y - top) / (u.light.y - u.p.y));
        let (d_r, d_b) = (w(u.p), w(b));
        let t = triangles(&u);
        assert!((t.d_r - d_r).abs() < 1e-4, "d_r {} against {d_r}", t.d_r);
        assert!((t.d_b - d_b).abs() < 1e-4, "d_b {} against {d_b}", t.d_b);
        let svg = similar_triangles(&u);
        // Printed to 2 decimals (3 for the widths): within half the last digit.
        let near = |got: Vec<f64>, want: f64, half: f64, label: &str| {
            assert!(!got.is_empty(), "the figure prints no {label}");
            for g in got {
                assert!(
                    (g - want).abs() <= half * 1.02,
                    "printed {label} = {g}, the definition gives {want}"
                );
            }
        };
        for (label, want) in [("d_r", d_r), ("d_b", d_b), ("d_r − d_b", d_r - d_b)] {
            near(printed(&svg, label), want, 0.005, label);
        }
        // Each distance's label beside its own span, in both panels: d_b's
        // and d_r − d_b's on the left, each between the ends of its span;
        // d_r's on the right, beside the one arrow drawn there, the whole
        // way from the emitter to the receiver's plane.
        let at = |d: f64| TOP + d * KY;
        let labels = |label: &str| -> Vec<(f64, f64)> {
            crate::diagrams::svg::tests::texts(&svg)
                .into_iter()
                .filter(|(_, _, t)| t.starts_with(&format!("{label} = ")))
                .map(|(x, y, _)| (x % 400.0, y))
                .collect()
        };
        for (label, lo, hi, left) in [
            ("d_b", 0.0, d_b, true),
            ("d_r − d_b", d_b, d_r, true),
            ("d_r", 0.0, d_r, false),
        ] {
            let found = labels(label);
            assert_eq!(found.len(), 2, "{label}: one label a panel");
            for (x, y) in found {
                assert!(
                    y > at(lo) && y < at(hi),
                    "{label}'s label at y {y}, its span {lo}..{hi}"
                );
                assert_eq!(x < 100.0, left, "{label}'s label at x {x} of its panel");
            }
        }
        // The edge's height above the floor, as the note prints it: the
        // plank's top, from the scene's triangles above.
        let words: Vec<String> = crate::diagrams::svg::tests::texts(&svg)
            .into_iter()
            .map(|(_, _, t)| t)
            .collect();
        let words = words.join(" ");
        let key = "The edge is ";
        let gap: f64 = words
            [words.find(key).expect("the note gives the edge's height") + key.len()..]
            .split(" m")
            .next()
            .and_then(|x| x.parse().ok())
            .expect("a height");
        assert!(
            (gap - (top + o)).abs() <= 0.005 * 1.02,
            "printed edge height {gap}"
        );
        // The ray's length from the edge to p, from the independent b.
        let key = " m long";
        let at_key = words.find(key).expect("the note gives the ray's length");
        let long: f64 = words[..at_key]
            .rsplit(' ')
            .next()
            .and_then(|x| x.parse().ok())
            .expect("a length");
        let want = (u.p - b).length();
        assert!(
            (long - want).abs() <= 0.005 * 1.02,
            "printed length {long}, the scene gives {want}"
        );
        let r = u.radius;
        let r_b = r * (d_r - d_b) / d_r;
        let foot = (t.footprint.1 - t.footprint.0) / 2.0;
        assert!(
            (foot - r_b).abs() < 1e-4,
            "footprint radius {foot} against {r_b}"
        );
        assert!(
            t.footprint.0 < 0.0 && t.footprint.1 > 0.0,
            "p under the edge sees half"
        );
        let w_pen = r * (d_r - d_b) / d_b;
        let pen = (t.penumbra.1 - t.penumbra.0) / 2.0;
        assert!(
            (pen - w_pen).abs() < 1e-4,
            "penumbra half width {pen} against {w_pen}"
        );
        near(printed(&svg, "2 r_b"), 2.0 * r_b, 0.0005, "2 r_b");
        near(
            printed(&svg, "2 w_penumbra"),
            2.0 * w_pen,
            0.0005,
            "2 w_penumbra",
        );
    }
}
