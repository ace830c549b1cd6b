//! Picture (b), the volume's sides and caps (`volume_sides_caps.svg`): the
//! silhouette extruded away from the light, the light-facing faces as the
//! front cap, and their extrusion as the back cap.

use common::glam::{DVec3, Vec3};
use workbook::lesson_05::extrusion::cpu_volume;
use workbook::lesson_05::silhouette::{silhouette_edges_for, LightDir};
use workbook::lesson_05::volumes::CasterDraw;

use super::caster::Caster;
use super::draw::{legend, light_marker, Fit, AWAY, LIT};
use crate::diagrams::svg::{fill, Svg, P};

/// How far from the light the drawing puts the far ends: `FAR` times
/// the vertex's distance. The lesson puts them at infinity (w = 0).
const FAR: f64 = 2.2;

pub(super) fn sides_and_caps(c: &Caster) -> String {
    let title = "The cube's shadow volume: sides and caps (cpu_volume, lesson 05)";
    let (w, mut s) = (760.0, Svg::new(760.0, 0.0, title));
    let mut verts = Vec::new();
    let ranges = cpu_volume(&c.adj, LightDir::Point(c.light.as_vec3()), &mut verts);
    let place = |v: &workbook::lesson_05::extrusion::CpuVertex| {
        let p = Vec3::from(v.position).as_dvec3();
        if v.w == 0.0 {
            c.light + FAR * (p - c.light)
        } else {
            p
        }
    };
    // Polygons: (points, style, depth). The unlit faces of the cube first.
    let mut polys: Vec<(Vec<DVec3>, String)> = Vec::new();
    for (f, t) in c.adj.triangles.iter().enumerate() {
        if !c.facing[f] {
            polys.push((t.map(|i| c.pos(i)).to_vec(), fill(AWAY, "#888")));
        }
    }
    let part = |r: &std::ops::Range<u32>| -> Vec<Vec<DVec3>> {
        verts[r.start as usize..r.end as usize]
            .chunks_exact(3)
            .map(|t| t.iter().map(place).collect())
            .collect()
    };
    let side = r##"fill="#1f5fbf" fill-opacity="0.22" stroke="#1f5fbf" stroke-width="1.2""##;
    let back = r##"fill="#9467bd" fill-opacity="0.25" stroke="#9467bd" stroke-width="1.5" stroke-dasharray="5,3""##;
    for t in part(&ranges.sides) {
        polys.push((t, side.to_string()));
    }
    for t in part(&ranges.front) {
        polys.push((t, fill(LIT, "#a80")));
    }
    for t in part(&ranges.back) {
        polys.push((t, back.to_string()));
    }
    let px: Vec<P> = polys
        .iter()
        .flat_map(|(t, _)| t.iter().map(|&p| c.screen(p)))
        .collect();
    let (lo, hi) = ((20.0, 40.0), (460.0, 480.0));
    let fit = Fit::new(&px, (30.0, 80.0), (420.0, 390.0));
    let at = |p: DVec3| fit.at(c.screen(p));
    polys.sort_by(|a, b| c.depth(&a.0).total_cmp(&c.depth(&b.0)));
    for (t, style) in &polys {
        let pts: Vec<P> = t.iter().map(|&p| at(p)).collect();
        s.poly(&pts, true, style);
    }
    light_marker(&mut s, at(c.centre), at(c.light), lo, hi);
    let count = |r: &std::ops::Range<u32>| (r.end - r.start) / 3;
    let edges = silhouette_edges_for(&c.adj, &c.facing).len();
    // Which caps lesson 05's z-pass draws (none): lesson 06's z-fail does.
    let zpass = CasterDraw::zpass(0);
    let drawn = |cap: bool| match cap {
        true => " (z-pass draws it)",
        false => " (not drawn by z-pass; lesson 06's z-fail draws it)",
    };
    let rows = [
        (
            fill(LIT, "#a80"),
            format!(
                "front cap: the {} light-facing triangles{}",
                count(&ranges.front),
                drawn(zpass.front_cap)
            ),
        ),
        (
            side.to_string(),
            format!(
                "sides: {} triangles, two for each of the {edges} silhouette edges, \
                 extruded away from the light (lesson 05's z-pass draws these)",
                count(&ranges.sides)
            ),
        ),
        (
            back.to_string(),
            format!(
                "back cap: the same {} triangles, reversed, at infinity{}",
                count(&ranges.back),
                drawn(zpass.back_cap)
            ),
        ),
        (
            fill(AWAY, "#888"),
            "the cube's faces turned from the light".into(),
        ),
    ];
    let y = legend(&mut s, 480.0, 90.0, &rows);
    let note = format!(
        "Drawn here at {FAR} times each vertex's distance from the light; the lesson's far \
         vertices have w = 0 and lie at infinity. Inside the closed volume, every point is \
         hidden from the light by the cube."
    );
    let y = s.para((480.0, y + 14.0), 12.0, "start", w - 500.0, &note);
    s.h = y.max(490.0);
    s.finish()
}
