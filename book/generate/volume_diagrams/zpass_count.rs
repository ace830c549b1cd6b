//! Picture (c), the z-pass count (`volume_zpass_count.svg`): a cross-section
//! of lesson 05's volume of a long box, and the count of its faces along
//! two view rays.

use anyhow::{bail, Result};
use common::glam::{DMat4, DVec3, Vec3};
use common::scene::mesh::builtin;
use workbook::lesson_05::adjacency::Adjacency;
use workbook::lesson_05::silhouette::{
    face_facing, light_facing_triangles_for, silhouette_edges_for, LightDir,
};

use super::draw::BLUE;
use crate::diagrams::crossings::{crossings, inside, signed, Face};
use crate::diagrams::svg::{add, fill, stroke, Svg, P};

/// The cross-section: lesson 05's functions on a long box (a prism along
/// z) lit from a point in the plane z = 0, then cut by that plane.
const LIGHT_2D: P = (-2.6, 6.4);
const EYE_2D: P = (7.6, 4.6);
const FAR_Y: f64 = -2.6;

/// The part of the section drawn: x and y, in metres.
const WX: P = (-3.6, 9.0);
const WY: P = (FAR_Y - 0.2, 7.0);
/// Pixels a metre.
const K: f64 = 740.0 / (WX.1 - WX.0);

/// A point of the section on the page.
fn page(p: P) -> P {
    (30.0 + (p.0 - WX.0) * K, 50.0 + (WY.1 - p.1) * K)
}

/// The long box: lesson 05's cube scaled, turned about z and lifted.
fn prism_model() -> DMat4 {
    DMat4::from_translation(DVec3::new(0.2, 2.7, 0.0))
        * DMat4::from_rotation_z(20f64.to_radians())
        * DMat4::from_scale(DVec3::new(1.8, 0.8, 4.0))
}

/// A segment of the cross-section.
type Segment = (P, P);

/// The caster's fill: its cross-section is drawn over the volume's.
const CASTER: &str = "#8796a8";

/// The prism's cross-section: (front cap segments, silhouette points, the
/// box's own section, counter-clockwise).
fn prism_section() -> Result<(Vec<Segment>, Vec<P>, Vec<P>)> {
    let model = prism_model();
    let cube = builtin("cube")?;
    let world: Vec<Vec3> = cube
        .positions
        .iter()
        .map(|p| model.transform_point3(p.as_dvec3()).as_vec3())
        .collect();
    let adj = Adjacency::from_triangles(&world, &cube.indices);
    let light = LightDir::Point(Vec3::new(LIGHT_2D.0 as f32, LIGHT_2D.1 as f32, 0.0));
    let facing = face_facing(&adj, light);
    let xy = |i: u32| {
        let p = adj.positions[i as usize];
        (p.x as f64, p.y as f64)
    };
    let close = |a: P, b: P| (a.0 - b.0).abs() + (a.1 - b.1).abs() < 1e-5;
    // Silhouette edges along z cut the plane in one point each.
    let points: Vec<P> = silhouette_edges_for(&adj, &facing)
        .iter()
        .filter(|e| close(xy(e.a), xy(e.b)))
        .map(|e| xy(e.a))
        .collect();
    let mut caps: Vec<(P, P)> = Vec::new();
    for t in light_facing_triangles_for(&adj, &facing) {
        let mut ends: Vec<P> = Vec::new();
        for p in t.map(xy) {
            if !ends.iter().any(|q| close(*q, p)) {
                ends.push(p);
            }
        }
        let [a, b] = ends[..] else { continue };
        if !caps
            .iter()
            .any(|&(c, d)| (close(a, c) && close(b, d)) || (close(a, d) && close(b, c)))
        {
            caps.push((a, b));
        }
    }
    if points.len() != 2 || caps.is_empty() {
        bail!(
            "prism section: {} silhouette points, {} cap segments",
            points.len(),
            caps.len()
        );
    }
    // The box runs along z, so its section is its corners' (x, y).
    let mut section: Vec<P> = Vec::new();
    for i in 0..adj.positions.len() as u32 {
        if !section.iter().any(|q| close(*q, xy(i))) {
            section.push(xy(i));
        }
    }
    let n = section.len() as f64;
    let c = section
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    section.sort_by(|a, b| {
        (a.1 - c.1)
            .atan2(a.0 - c.0)
            .total_cmp(&(b.1 - c.1).atan2(b.0 - c.0))
    });
    Ok((caps, points, section))
}

/// A silhouette point pushed away from the light to y = `y`.
fn extrude_to(p: P, y: f64) -> P {
    let t = (y - p.1) / (p.1 - LIGHT_2D.1);
    (p.0 + t * (p.0 - LIGHT_2D.0), y)
}

/// The volume's section as faces: front cap segments, two sides, back cap.
fn section_faces(caps: &[(P, P)], sil: &[P]) -> (Vec<P>, Vec<Face>) {
    // The section is convex: its hull, counter-clockwise.
    let mut pts: Vec<P> = caps.iter().flat_map(|&(a, b)| [a, b]).collect();
    pts.extend(sil.iter().map(|&p| extrude_to(p, FAR_Y)));
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    pts.dedup_by(|a, b| (a.0 - b.0).abs() + (a.1 - b.1).abs() < 1e-9);
    let cross = |o: P, a: P, b: P| (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0);
    let mut hull: Vec<P> = Vec::new();
    for pass in [pts.clone(), pts.iter().rev().copied().collect()] {
        let start = hull.len();
        for p in pass {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    let n = hull.len() as f64;
    let c = hull
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    let far = |p: P| (p.1 - FAR_Y).abs() < 1e-9;
    let faces = (0..hull.len())
        .map(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            let name = match (far(a), far(b)) {
                (true, true) => "back cap (∞)",
                (false, false) => "front cap",
                _ => "side",
            };
            let mut out = (b.1 - a.1, a.0 - b.0);
            if out.0 * (a.0 - c.0) + out.1 * (a.1 - c.1) < 0.0 {
                out = (-out.0, -out.1);
            }
            Face { a, b, name, out }
        })
        .collect();
    (hull, faces)
}

pub(super) fn zpass_count() -> Result<String> {
    let (caps, sil, section) = prism_section()?;
    let (hull, faces) = section_faces(&caps, &sil);
    let floor: Vec<f64> = sil.iter().map(|&p| extrude_to(p, 0.0).0).collect();
    let (x0, x1) = (floor[0].min(floor[1]), floor[0].max(floor[1]));
    let targets = [
        ("a lit point", (x0 - 1.4, 0.0)),
        ("a shadowed point", ((x0 + x1) / 2.0, 0.0)),
    ];
    let title = "Z-pass: counting volume faces along two view rays (a cross-section)";
    let mut s = Svg::new(800.0, 0.0, title);
    let (wx, at) = (WX, page);
    let region: Vec<P> = hull.iter().map(|&p| at(p)).collect();
    s.poly(&region, true, &fill("#ddd", "none"));
    let caster: Vec<P> = section.iter().map(|&p| at(p)).collect();
    s.poly(&caster, true, &fill(CASTER, "#333"));
    for f in &faces {
        let style = match f.name {
            "front cap" => stroke("#a80", 3.0, ""),
            "side" => stroke("#555", 2.0, ""),
            _ => stroke("#9467bd", 2.0, "6,4"),
        };
        s.line(at(f.a), at(f.b), &style);
    }
    for p in &sil {
        s.line(at(LIGHT_2D), at(*p), &stroke("#a80", 1.0, "3,3"));
    }
    s.line(
        at((wx.0, 0.0)),
        at((wx.1, 0.0)),
        &stroke("#8b5a2b", 3.0, ""),
    );
    s.text(
        add(at((wx.0, 0.0)), 4.0, -6.0),
        12.0,
        "start",
        "floor (the receiver)",
    );
    s.circle(at(LIGHT_2D), 9.0, &fill("#ffd400", "#a80"));
    s.text(add(at(LIGHT_2D), 13.0, 4.0), 12.0, "start", "light");
    s.circle(at(EYE_2D), 6.0, &fill(BLUE, "none"));
    s.text(add(at(EYE_2D), 0.0, -12.0), 12.0, "middle", "eye");
    let names = [
        ("front cap", "front cap"),
        ("side", "side"),
        ("back cap (∞)", "back cap (∞, lesson 06)"),
    ];
    let mut labelled = Vec::new();
    for f in &faces {
        if labelled.contains(&f.name) {
            continue;
        }
        labelled.push(f.name);
        let label = names.iter().find(|n| n.0 == f.name).map_or(f.name, |n| n.1);
        let m = ((f.a.0 + f.b.0) / 2.0, (f.a.1 + f.b.1) / 2.0);
        let (anchor, d) = if f.out.0 < -1e-9 {
            ("end", -8.0)
        } else {
            ("start", 8.0)
        };
        let dy = match f.name {
            "front cap" => -6.0,
            "side" => 4.0,
            _ => 16.0,
        };
        s.text(add(at(m), d, dy), 12.0, anchor, label);
    }
    let n = caster.len() as f64;
    let mid = caster
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    s.text(add(mid, 0.0, 4.0), 12.0, "middle", "caster");
    let colours = ["#2ca02c", BLUE];
    let mut lines = Vec::new();
    for ((what, target), colour) in targets.iter().zip(colours) {
        s.line(at(EYE_2D), at(*target), &stroke(colour, 2.0, ""));
        s.circle(at(*target), 5.0, &fill("#fff", colour));
        let d = (target.0 - EYE_2D.0, target.1 - EYE_2D.1);
        let mut count = 0;
        let mut steps = Vec::new();
        for (t, sign, _) in crossings(EYE_2D, *target, &faces) {
            if t >= 1.0 {
                continue;
            }
            count += sign;
            let p = at((EYE_2D.0 + t * d.0, EYE_2D.1 + t * d.1));
            s.circle(p, 5.0, &fill(colour, "none"));
            let label = format!("{} → {count}", signed(sign));
            s.text(add(p, 2.0, -9.0), 13.0, "start", &label);
            steps.push(signed(sign));
        }
        let shadow = inside(&hull, *target);
        if (count != 0) != shadow {
            bail!("z-pass count {count} disagrees with the section for {what}");
        }
        let verdict = ["lit", "in shadow"][(count != 0) as usize];
        let sum = if steps.is_empty() {
            "no crossing".into()
        } else {
            steps.join(" ")
        };
        s.text(
            add(at(*target), 0.0, 18.0),
            12.0,
            "middle",
            &format!("count {count}"),
        );
        lines.push(format!(
            "Ray to {what}: {sum} = {count} at the surface → {verdict}."
        ));
    }
    let mut y = at((0.0, FAR_Y)).1 + 30.0;
    y = s.texts((30.0, y), 13.0, "start", &lines) + 4.0;
    let note = "Each volume face a ray crosses in front of the surface it hits adds +1 where \
                the ray enters the volume and −1 where it leaves it; the number after the arrow \
                is the count so far. The caster (blue-grey) is lesson 05's cube stretched into a long \
                box and cut through the light; its faces that face the light are the volume's \
                front cap, and the volume's sides run from its silhouette away from the light.";
    s.h = s.para((30.0, y), 12.0, "start", 740.0, note);
    Ok(s.finish())
}

#[cfg(test)]
mod tests {
    use common::scene::mesh::builtin;

    use super::super::independent::points;
    use super::*;
    use crate::diagrams::svg::tests::{elements, number, texts};

    /// A point of the page in the section's metres.
    fn metres(p: P) -> P {
        (WX.0 + (p.0 - 30.0) / K, WY.1 - (p.1 - 50.0) / K)
    }

    /// Is `p` inside the polygon `poly` (its winding number)?
    fn within(poly: &[P], p: P) -> bool {
        let mut winding = 0;
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let side = (b.0 - a.0) * (p.1 - a.1) - (p.0 - a.0) * (b.1 - a.1);
            if a.1 <= p.1 && b.1 > p.1 && side > 0.0 {
                winding += 1;
            } else if a.1 > p.1 && b.1 <= p.1 && side < 0.0 {
                winding -= 1;
            }
        }
        winding != 0
    }

    /// Where the segments `p0 → p1` and `q0 → q1` cross: the parameter
    /// along the first, if they do.
    fn cross(p0: P, p1: P, q0: P, q1: P) -> Option<f64> {
        let (d, e) = ((p1.0 - p0.0, p1.1 - p0.1), (q1.0 - q0.0, q1.1 - q0.1));
        let den = d.0 * e.1 - d.1 * e.0;
        if den.abs() < 1e-12 {
            return None;
        }
        let w = (q0.0 - p0.0, q0.1 - p0.1);
        let t = (w.0 * e.1 - w.1 * e.0) / den;
        let u = (w.0 * d.1 - w.1 * d.0) / den;
        ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then_some(t)
    }

    /// The long box's section by z = 0: its four corners, in turn.
    fn box_section() -> Vec<P> {
        let cube = builtin("cube").unwrap();
        let mut corners: Vec<P> = Vec::new();
        for p in &cube.positions {
            let q = prism_model().transform_point3(p.as_dvec3());
            if !corners
                .iter()
                .any(|c| (c.0 - q.x).abs() + (c.1 - q.y).abs() < 1e-9)
            {
                corners.push((q.x, q.y));
            }
        }
        assert_eq!(corners.len(), 4, "a box's section is a rectangle");
        let c = corners
            .iter()
            .fold((0.0, 0.0), |s, p| (s.0 + p.0 / 4.0, s.1 + p.1 / 4.0));
        corners.sort_by(|a, b| {
            (a.1 - c.1)
                .atan2(a.0 - c.0)
                .total_cmp(&(b.1 - c.1).atan2(b.0 - c.0))
        });
        corners
    }

    /// Does the box hide `p` from the light: does the segment from the
    /// light to `p` meet the box?
    fn hidden(p: P) -> bool {
        let rect = box_section();
        within(&rect, p) || (0..4).any(|i| cross(LIGHT_2D, p, rect[i], rect[(i + 1) % 4]).is_some())
    }

    /// The distance from `p` to the polygon's outline.
    fn to_outline(poly: &[P], p: P) -> f64 {
        (0..poly.len())
            .map(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                let e = (b.0 - a.0, b.1 - a.1);
                let t = (((p.0 - a.0) * e.0 + (p.1 - a.1) * e.1) / (e.0 * e.0 + e.1 * e.1))
                    .clamp(0.0, 1.0);
                ((p.0 - a.0 - t * e.0).powi(2) + (p.1 - a.1 - t * e.1).powi(2)).sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The caster drawn is the box's section, and the grey region drawn
    /// is the box's shadow: a point of the section (down to the back
    /// cap's line) lies in it exactly when the segment from the light to
    /// it meets the box. And the count written at each
    /// crossing of a view ray is the running sum of +1 where the ray
    /// enters that region and −1 where it leaves, found by intersecting
    /// the ray with the region's outline; the count at the floor is not 0
    /// exactly where the box hides the floor point from the light.
    #[test]
    fn counts_written_are_the_crossings_of_each_ray() {
        let svg = zpass_count().unwrap();
        let polygons = elements(&svg, "polygon");
        let region = polygons
            .iter()
            .find(|e| e["fill"] == "#ddd")
            .expect("the volume");
        let region: Vec<P> = points(&region["points"]);
        // The caster is drawn apart from its volume: its own section.
        let caster = polygons
            .iter()
            .find(|e| e["fill"] == CASTER)
            .expect("the caster");
        let caster: Vec<P> = points(&caster["points"]).into_iter().map(metres).collect();
        let rect = box_section();
        assert_eq!(caster.len(), rect.len(), "the caster's section: {caster:?}");
        for c in &rect {
            let drawn = caster
                .iter()
                .any(|p| (p.0 - c.0).abs() + (p.1 - c.1).abs() < 1e-3);
            assert!(
                drawn,
                "the box's corner {c:?} (m) is not the caster's: {caster:?}"
            );
        }
        let in_metres: Vec<P> = region.iter().map(|&p| metres(p)).collect();
        let mut sampled = 0;
        for i in 0..=250 {
            for j in 0..=200 {
                let p = (
                    WX.0 + (WX.1 - WX.0) * i as f64 / 250.0,
                    FAR_Y + (WY.1 - FAR_Y) * j as f64 / 200.0,
                );
                let edge = to_outline(&in_metres, p).min(to_outline(&box_section(), p));
                if edge < 0.03 {
                    continue;
                }
                sampled += 1;
                assert_eq!(within(&in_metres, p), hidden(p), "at {p:?} (m)");
            }
        }
        assert!(sampled > 40_000);
        let labels = texts(&svg);
        let mut crossings_found = 0;
        let rays = elements(&svg, "line");
        let rays: Vec<(P, P)> = rays
            .iter()
            .filter(|l| {
                l["stroke-width"] == "2" && (l["stroke"] == "#2ca02c" || l["stroke"] == BLUE)
            })
            .map(|l| {
                (
                    (number(l, "x1"), number(l, "y1")),
                    (number(l, "x2"), number(l, "y2")),
                )
            })
            .collect();
        assert_eq!(rays.len(), 2, "two view rays");
        let label_at = |p: P| {
            let found = labels
                .iter()
                .find(|t| (t.0 - p.0).abs() < 0.1 && (t.1 - p.1).abs() < 0.1);
            found.map(|t| t.2.clone()).unwrap_or_default()
        };
        for &(eye, target) in &rays {
            let mut ts: Vec<f64> = (0..region.len())
                .filter_map(|i| cross(eye, target, region[i], region[(i + 1) % region.len()]))
                .filter(|t| *t < 1.0 - 1e-9)
                .collect();
            ts.sort_by(f64::total_cmp);
            let mut count = 0;
            let along = |t: f64| {
                (
                    eye.0 + t * (target.0 - eye.0),
                    eye.1 + t * (target.1 - eye.1),
                )
            };
            for t in ts {
                let sign = if within(&region, along(t + 1e-3)) {
                    1
                } else {
                    -1
                };
                count += sign;
                let q = along(t);
                let want = format!("{} → {count}", if sign > 0 { "+1" } else { "−1" });
                assert_eq!(label_at((q.0 + 2.0, q.1 - 9.0)), want, "crossing at {q:?}");
                crossings_found += 1;
            }
            assert_eq!(
                label_at((target.0, target.1 + 18.0)),
                format!("count {count}")
            );
            assert_eq!(count != 0, hidden(metres(target)), "ray to {target:?}");
        }
        let written = (labels.iter())
            .filter(|t| t.2.starts_with("+1 → ") || t.2.starts_with("−1 → "))
            .count();
        assert_eq!(
            written, crossings_found,
            "a count for each crossing, and no other"
        );
        assert!(crossings_found >= 3);
    }
}
