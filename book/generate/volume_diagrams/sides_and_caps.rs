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

const SIDE: &str = r##"fill="#1f5fbf" fill-opacity="0.22" stroke="#1f5fbf" stroke-width="1.2""##;
const BACK: &str = r##"fill="#9467bd" fill-opacity="0.25" stroke="#9467bd" stroke-width="1.5" stroke-dasharray="5,3""##;

/// Where a world point lands on the page: the caster's camera, fitted to
/// the panel by every point drawn (`pts`).
fn layout<'a>(c: &'a Caster, pts: &[DVec3]) -> impl Fn(DVec3) -> P + 'a {
    let px: Vec<P> = pts.iter().map(|&p| c.screen(p)).collect();
    let fit = Fit::new(&px, (30.0, 80.0), (420.0, 390.0));
    move |p| fit.at(c.screen(p))
}

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
    let (side, back) = (SIDE, BACK);
    for t in part(&ranges.sides) {
        polys.push((t, side.to_string()));
    }
    for t in part(&ranges.front) {
        polys.push((t, fill(LIT, "#a80")));
    }
    for t in part(&ranges.back) {
        polys.push((t, back.to_string()));
    }
    let all: Vec<DVec3> = polys.iter().flat_map(|(t, _)| t.iter().copied()).collect();
    let (lo, hi) = ((20.0, 40.0), (460.0, 480.0));
    let at = layout(c, &all);
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

#[cfg(test)]
mod tests {
    use super::super::independent::{
        cube_triangles, faces_point, near, point_light, points, scene, silhouette,
    };
    use super::*;
    use crate::diagrams::svg::tests::{elements, texts};

    /// Twice the signed area of a page polygon.
    fn area(p: &[P]) -> f64 {
        (0..p.len())
            .map(|i| {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                a.0 * b.1 - b.0 * a.1
            })
            .sum::<f64>()
            .abs()
    }

    /// The volume drawn is the cube's, built here from the scene's mesh
    /// and light alone: the front cap is the triangles facing the light,
    /// the back cap the same triangles pushed away from the light to
    /// `FAR` times their distance, and each silhouette edge (between a lit
    /// and an unlit triangle) is swept away from the light into one side,
    /// the quad `a, b, b', a'` drawn as two triangles that cover it.
    #[test]
    fn volume_drawn_is_the_silhouette_swept_away_from_the_light() {
        let scene = scene();
        let c = Caster::from_scene(&scene).unwrap();
        let svg = sides_and_caps(&c);
        let light = point_light(&scene);
        let tris = cube_triangles(&scene);
        let lit: Vec<bool> = tris.iter().map(|t| faces_point(t, light)).collect();
        let sil = silhouette(&tris, &lit);
        let away = |p: DVec3| light + FAR * (p - light);
        let front: Vec<[DVec3; 3]> = (tris.iter().zip(&lit))
            .filter(|(_, l)| **l)
            .map(|(t, _)| *t)
            .collect();
        let unlit: Vec<[DVec3; 3]> = (tris.iter().zip(&lit))
            .filter(|(_, l)| !**l)
            .map(|(t, _)| *t)
            .collect();
        let back: Vec<[DVec3; 3]> = front.iter().map(|t| t.map(away)).collect();
        let quads: Vec<[DVec3; 4]> = sil.iter().map(|&(a, b)| [a, b, away(b), away(a)]).collect();
        let mut all: Vec<DVec3> = [&unlit, &front, &back]
            .iter()
            .flat_map(|v| v.iter().flatten().copied())
            .collect();
        all.extend(quads.iter().flatten());
        let at = layout(&c, &all);
        let polygons = elements(&svg, "polygon");
        let drawn = |fill: &str| -> Vec<Vec<P>> {
            (polygons.iter())
                .filter(|e| e["fill"] == fill)
                .map(|e| points(&e["points"]))
                .collect()
        };
        let same = |a: &[P], b: &[P]| {
            a.len() == b.len() && a.iter().all(|p| b.iter().any(|q| near(*p, *q)))
        };
        for (name, fill, want) in [
            ("front cap", LIT, &front),
            ("back cap", "#9467bd", &back),
            ("unlit face", AWAY, &unlit),
        ] {
            let got = drawn(fill);
            assert_eq!(got.len(), want.len(), "{name} triangles drawn: {got:?}");
            for t in want {
                let t = t.map(&at);
                assert!(got.iter().any(|g| same(g, &t)), "{name} {t:?} is not drawn");
            }
        }
        let sides = drawn("#1f5fbf");
        assert_eq!(sides.len(), 2 * quads.len(), "side triangles drawn");
        for q in &quads {
            let q = q.map(&at);
            let halves: Vec<&Vec<P>> = sides
                .iter()
                .filter(|t| t.iter().all(|p| q.iter().any(|c| near(*p, *c))))
                .collect();
            let covered: f64 = halves.iter().map(|t| area(t)).sum();
            assert!(
                halves.len() == 2 && (covered / area(&q) - 1.0).abs() < 1e-3,
                "side {q:?}: drawn as {halves:?}"
            );
        }
        let words: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
        let words = words.join(" ");
        for count in [
            format!("the {} light-facing triangles", front.len()),
            format!(
                "{} triangles, two for each of the {} silhouette edges",
                2 * quads.len(),
                quads.len()
            ),
        ] {
            assert!(words.contains(&count), "the legend lacks {count:?}");
        }
    }
}
