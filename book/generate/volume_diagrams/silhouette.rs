//! Picture (a), the silhouette (`volume_silhouette.svg`): the cube's faces
//! towards and away from the light, and the edges between them that lesson
//! 05's `silhouette_edges_for` finds.

use common::glam::DVec3;
use workbook::lesson_05::silhouette::silhouette_edges_for;

use super::caster::Caster;
use super::draw::{clip, legend, light_marker, Fit, AWAY, LIT, SIL};
use crate::diagrams::svg::{fill, stroke, Svg, P};

/// Where a world point lands on the page: the caster's camera, fitted to
/// the panel by the cube's corners.
fn layout(c: &Caster) -> impl Fn(DVec3) -> P + '_ {
    let px: Vec<P> = c
        .adj
        .positions
        .iter()
        .map(|p| c.screen(p.as_dvec3()))
        .collect();
    let fit = Fit::new(&px, (90.0, 140.0), (280.0, 260.0));
    move |p| fit.at(c.screen(p))
}

pub(super) fn silhouette(c: &Caster) -> String {
    let (w, title) = (
        760.0,
        "The silhouette of lesson 05's cube under its point light",
    );
    let mut s = Svg::new(w, 0.0, title);
    let sil = silhouette_edges_for(&c.adj, &c.facing);
    let (lo, hi) = ((20.0, 40.0), (440.0, 420.0));
    let at = layout(c);
    // Faces far to near; a face turned from the eye is drawn paler.
    let mut order: Vec<usize> = (0..c.adj.triangles.len()).collect();
    let tri = |f: usize| c.adj.triangles[f].map(|i| c.pos(i));
    order.sort_by(|&a, &b| c.depth(&tri(a)).total_cmp(&c.depth(&tri(b))));
    let eye = c.view.inverse().transform_point3(DVec3::ZERO);
    let seen = |f: usize| c.adj.face_normals[f].as_dvec3().dot(eye - tri(f)[0]) > 0.0;
    for &f in &order {
        let colour = if c.facing[f] { LIT } else { AWAY };
        let style = if seen(f) {
            fill(colour, "#555")
        } else {
            format!(r##"fill="{colour}" fill-opacity="0.35" stroke="#999" stroke-width="1""##)
        };
        s.poly(&tri(f).map(&at), true, &style);
    }
    for e in &sil {
        let v = at(c.pos(e.a));
        s.line(v, clip(v, at(c.light), lo, hi), &stroke("#a80", 1.0, "3,3"));
    }
    // A silhouette edge is hidden when both of its faces turn from the eye.
    for e in &sil {
        let (a, b) = (c.pos(e.a), c.pos(e.b));
        let hidden = (0..c.adj.triangles.len())
            .filter(|&f| c.adj.triangles[f].contains(&e.a) && c.adj.triangles[f].contains(&e.b))
            .all(|f| !seen(f));
        let dash = if hidden { "6,4" } else { "" };
        s.line(at(a), at(b), &stroke(SIL, 4.0, dash));
    }
    light_marker(&mut s, at(c.centre), at(c.light), lo, hi);
    let lit = c.facing.iter().filter(|f| **f).count();
    let n = c.adj.triangles.len();
    let rows = [
        (
            fill(LIT, "#555"),
            format!("faces the light (face_facing): {lit} of {n} triangles"),
        ),
        (
            fill(AWAY, "#555"),
            format!("faces away: {} triangles", n - lit),
        ),
        (
            fill(SIL, "none"),
            format!(
                "silhouette edge (silhouette_edges): {} edges, each between a lit and an unlit \
                 face; dashed where hidden behind the cube",
                sil.len()
            ),
        ),
        (
            stroke("#a80", 1.0, "3,3"),
            "grazing rays: from the light past each silhouette vertex".into(),
        ),
    ];
    let y = legend(&mut s, 460.0, 90.0, &rows);
    let note = "The silhouette is a closed loop around the lit faces: extruded away from \
                the light, it becomes the sides of the shadow volume.";
    let y = s.para((460.0, y + 14.0), 12.0, "start", 280.0, note);
    s.h = y.max(420.0);
    s.finish()
}

#[cfg(test)]
mod tests {
    use super::super::independent::{
        cube_triangles, faces_point, near, point_light, points, scene, silhouette,
    };
    use super::*;
    use crate::diagrams::svg::tests::{elements, number, texts};

    /// The red edges drawn are the cube's edges between a triangle that
    /// faces the light and one that does not, found from the scene's mesh
    /// and light alone; the yellow triangles are those that face it; the
    /// legend counts both.
    #[test]
    fn red_edges_lie_between_lit_and_unlit_faces() {
        let scene = scene();
        let c = Caster::from_scene(&scene).unwrap();
        let svg = super::silhouette(&c);
        let tris = cube_triangles(&scene);
        let light = point_light(&scene);
        let lit: Vec<bool> = tris.iter().map(|t| faces_point(t, light)).collect();
        let want = silhouette(&tris, &lit);
        let at = layout(&c);
        let lines = elements(&svg, "line");
        let red: Vec<(P, P)> = lines
            .iter()
            .filter(|l| l["stroke"] == SIL && l["stroke-width"] == "4")
            .map(|l| {
                let end = |x: &str, y: &str| (number(l, x), number(l, y));
                (end("x1", "y1"), end("x2", "y2"))
            })
            .collect();
        assert_eq!(red.len(), want.len(), "red edges drawn: {red:?}");
        for (a, b) in &want {
            let (a, b) = (at(*a), at(*b));
            let drawn = red
                .iter()
                .any(|&(p, q)| (near(p, a) && near(q, b)) || (near(p, b) && near(q, a)));
            assert!(
                drawn,
                "silhouette edge {a:?}-{b:?} is not drawn red: {red:?}"
            );
        }
        let polygons = elements(&svg, "polygon");
        for (t, &l) in tris.iter().zip(&lit) {
            let corners = t.map(&at);
            let face = polygons.iter().find(|e| {
                let pts = points(&e["points"]);
                pts.len() == 3 && corners.iter().all(|c| pts.iter().any(|p| near(*p, *c)))
            });
            let face = face.unwrap_or_else(|| panic!("triangle {corners:?} is not drawn"));
            assert_eq!(face["fill"] == LIT, l, "triangle {corners:?}: facing {l}");
        }
        let words: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
        let words = words.join(" ");
        let n_lit = lit.iter().filter(|l| **l).count();
        for count in [
            format!("{n_lit} of {} triangles", tris.len()),
            format!("{} edges", want.len()),
        ] {
            assert!(words.contains(&count), "the legend lacks {count:?}");
        }
    }
}
