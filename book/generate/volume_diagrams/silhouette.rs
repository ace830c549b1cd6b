//! Picture (a), the silhouette (`volume_silhouette.svg`): the cube's faces
//! towards and away from the light, and the edges between them that lesson
//! 05's `silhouette_edges_for` finds. The cube is drawn twice: from the
//! lesson's camera, and from the opposite side (the camera mirrored
//! through the cube's centre), so that every face, the far ones included,
//! can be seen and counted.

use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec3};
use workbook::lesson_05::silhouette::{silhouette_edges_for, SilhouetteEdge};

use super::caster::Caster;
use super::draw::{clip, legend, light_marker, pixel, Fit, AWAY, LIT, SIL};
use crate::diagrams::svg::{add, fill, stroke, Svg, P};

/// One drawing of the cube: its view matrix and the panel it is fitted
/// into (the top-left corner and the size, pixels).
struct View {
    view: DMat4,
    at: P,
    size: P,
}

impl View {
    /// The lesson's camera, in the large panel.
    fn near(c: &Caster) -> View {
        View {
            view: c.view,
            at: (90.0, 140.0),
            size: (280.0, 260.0),
        }
    }
    /// The camera mirrored through the cube's centre, in the small panel:
    /// it sees exactly the faces the lesson's camera does not.
    fn far(c: &Caster) -> View {
        let eye = c.view.inverse().transform_point3(DVec3::ZERO);
        let back = 2.0 * c.centre - eye;
        View {
            view: look_at_mat4(back, c.centre, DVec3::Y),
            at: (520.0, 318.0),
            size: (170.0, 150.0),
        }
    }
    fn eye(&self) -> DVec3 {
        self.view.inverse().transform_point3(DVec3::ZERO)
    }
}

/// Where a world point lands on the page in view `v`: the caster's
/// projection, fitted to the panel by the cube's corners.
fn layout<'a>(c: &'a Caster, v: &View) -> impl Fn(DVec3) -> P + 'a {
    let m = c.proj * v.view;
    let screen = move |p: DVec3| pixel(m, 2.0, 2.0, p.extend(1.0)).unwrap_or((0.0, 0.0));
    let px: Vec<P> = c
        .adj
        .positions
        .iter()
        .map(|p| screen(p.as_dvec3()))
        .collect();
    let fit = Fit::new(&px, v.at, v.size);
    move |p| fit.at(screen(p))
}

/// Does triangle `f` turn its front to the eye at `eye`?
fn seen_from(c: &Caster, f: usize, eye: DVec3) -> bool {
    let p0 = c.pos(c.adj.triangles[f][0]);
    c.adj.face_normals[f].as_dvec3().dot(eye - p0) > 0.0
}

/// The cube from view `v`: the faces it sees, coloured by facing, the
/// light-facing ones numbered from `first`, and the silhouette, solid
/// where this view sees it and dashed behind. Returns the next number.
fn draw_view(s: &mut Svg, c: &Caster, v: &View, sil: &[SilhouetteEdge], first: usize) -> usize {
    let at = layout(c, v);
    let eye = v.eye();
    let tri = |f: usize| c.adj.triangles[f].map(|i| c.pos(i));
    let seen: Vec<usize> = (0..c.adj.triangles.len())
        .filter(|&f| seen_from(c, f, eye))
        .collect();
    // A silhouette edge is behind the cube when no face along it is seen.
    let hidden = |e: &SilhouetteEdge| {
        (0..c.adj.triangles.len())
            .filter(|&f| c.adj.triangles[f].contains(&e.a) && c.adj.triangles[f].contains(&e.b))
            .all(|f| !seen.contains(&f))
    };
    for &f in &seen {
        let colour = if c.facing[f] { LIT } else { AWAY };
        s.poly(&tri(f).map(&at), true, &fill(colour, "#555"));
    }
    for e in sil {
        let style = if hidden(e) {
            stroke(SIL, 3.0, "6,4")
        } else {
            stroke(SIL, 4.0, "")
        };
        s.line(at(c.pos(e.a)), at(c.pos(e.b)), &style);
    }
    let mut n = first;
    for &f in seen.iter().filter(|&&f| c.facing[f]) {
        let t = tri(f).map(&at);
        let m = (
            (t[0].0 + t[1].0 + t[2].0) / 3.0,
            (t[0].1 + t[1].1 + t[2].1) / 3.0,
        );
        s.text(add(m, 0.0, 5.0), 14.0, "middle", &n.to_string());
        n += 1;
    }
    n
}

pub(super) fn silhouette(c: &Caster) -> String {
    let (w, title) = (
        760.0,
        "The silhouette of lesson 05's cube under its point light",
    );
    let mut s = Svg::new(w, 0.0, title);
    let sil = silhouette_edges_for(&c.adj, &c.facing);
    let (lo, hi) = ((20.0, 40.0), (440.0, 420.0));
    let near = View::near(c);
    let at = layout(c, &near);
    for e in &sil {
        let v = at(c.pos(e.a));
        s.line(v, clip(v, at(c.light), lo, hi), &stroke("#a80", 1.0, "3,3"));
    }
    let next = draw_view(&mut s, c, &near, &sil, 1);
    light_marker(&mut s, at(c.centre), at(c.light), lo, hi);
    let far = View::far(c);
    let last = draw_view(&mut s, c, &far, &sil, next) - 1;
    let lit = c.facing.iter().filter(|f| **f).count();
    let n = c.adj.triangles.len();
    s.text(
        (far.at.0 + far.size.0 / 2.0, far.at.1 - 12.0),
        12.0,
        "middle",
        "the far side, seen from below and behind",
    );
    let rows = [
        (
            fill(LIT, "#555"),
            format!(
                "faces the light: {lit} of {n} triangles, numbered 1–{last}{}",
                if next <= last {
                    format!("; {next}–{last} are on the far side, drawn below")
                } else {
                    String::new()
                }
            ),
        ),
        (
            fill(AWAY, "#555"),
            format!("faces away: {} triangles", n - lit),
        ),
        (
            fill(SIL, "none"),
            format!(
                "silhouette edge: {} edges, each between a triangle that faces the light and \
                 one that faces away; dashed where the cube hides it",
                sil.len()
            ),
        ),
        (
            stroke("#a80", 1.0, "3,3"),
            "grazing rays: from the light past each silhouette vertex".into(),
        ),
    ];
    let y = legend(&mut s, 460.0, 90.0, &rows);
    let note = "The silhouette is a closed loop around the light-facing triangles: extruded \
                away from the light, it becomes the sides of the shadow volume.";
    let y = s.para((40.0, 470.0_f64.max(y + 14.0)), 12.0, "start", 400.0, note);
    s.h = y.max(far.at.1 + far.size.1 + 10.0);
    s.finish()
}

#[cfg(test)]
mod tests {
    use super::super::independent::{
        cube_triangles, faces_point, near, point_light, points, scene, silhouette,
    };
    use super::*;
    use crate::diagrams::svg::tests::{elements, number, texts};

    /// Is `p` inside the triangle `t` (page coordinates)?
    fn in_triangle(t: &[P; 3], p: P) -> bool {
        let side = |a: P, b: P| (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        let s = [side(t[0], t[1]), side(t[1], t[2]), side(t[2], t[0])];
        s.iter().all(|v| *v > 0.0) || s.iter().all(|v| *v < 0.0)
    }

    /// In both drawings of the cube, the red edges are the cube's edges
    /// between a triangle that faces the light and one that does not,
    /// found from the scene's mesh and light alone; every triangle is
    /// drawn in one of the two, yellow exactly when it faces the light;
    /// each light-facing triangle carries one number, 1 to their count,
    /// inside it; the legend counts the triangles and the edges.
    #[test]
    fn red_edges_lie_between_lit_and_unlit_faces() {
        let scene = scene();
        let c = Caster::from_scene(&scene).unwrap();
        let svg = super::silhouette(&c);
        let tris = cube_triangles(&scene);
        let light = point_light(&scene);
        let lit: Vec<bool> = tris.iter().map(|t| faces_point(t, light)).collect();
        let want = silhouette(&tris, &lit);
        let lines = elements(&svg, "line");
        let red: Vec<(P, P)> = lines
            .iter()
            .filter(|l| l["stroke"] == SIL)
            .map(|l| {
                let end = |x: &str, y: &str| (number(l, x), number(l, y));
                (end("x1", "y1"), end("x2", "y2"))
            })
            .collect();
        assert_eq!(red.len(), 2 * want.len(), "red edges drawn: {red:?}");
        let polygons = elements(&svg, "polygon");
        let labels = texts(&svg);
        let mut numbered: Vec<usize> = Vec::new();
        let mut drawn = vec![false; tris.len()];
        for v in [View::near(&c), View::far(&c)] {
            let at = layout(&c, &v);
            for (a, b) in &want {
                let (a, b) = (at(*a), at(*b));
                let found = red
                    .iter()
                    .any(|&(p, q)| (near(p, a) && near(q, b)) || (near(p, b) && near(q, a)));
                assert!(
                    found,
                    "silhouette edge {a:?}-{b:?} is not drawn red: {red:?}"
                );
            }
            for (i, (t, &l)) in tris.iter().zip(&lit).enumerate() {
                let corners = t.map(&at);
                let face = polygons.iter().find(|e| {
                    let pts = points(&e["points"]);
                    pts.len() == 3 && corners.iter().all(|c| pts.iter().any(|p| near(*p, *c)))
                });
                let Some(face) = face else { continue };
                drawn[i] = true;
                assert_eq!(face["fill"] == LIT, l, "triangle {corners:?}: facing {l}");
                let inside: Vec<&(f64, f64, String)> = labels
                    .iter()
                    .filter(|t| t.2.parse::<usize>().is_ok())
                    .filter(|t| in_triangle(&corners, (t.0, t.1 - 5.0)))
                    .collect();
                if l {
                    assert_eq!(inside.len(), 1, "triangle {corners:?}: numbers {inside:?}");
                    numbered.push(inside[0].2.parse().unwrap());
                } else {
                    assert!(
                        inside.is_empty(),
                        "a number on an unlit triangle: {inside:?}"
                    );
                }
            }
        }
        assert!(
            drawn.iter().all(|d| *d),
            "a triangle is drawn in neither view"
        );
        numbered.sort();
        let n_lit = lit.iter().filter(|l| **l).count();
        assert_eq!(numbered, (1..=n_lit).collect::<Vec<_>>());
        let words: Vec<String> = labels.into_iter().map(|t| t.2).collect();
        let words = words.join(" ");
        for count in [
            format!("{n_lit} of {} triangles", tris.len()),
            format!("{} edges", want.len()),
        ] {
            assert!(words.contains(&count), "the legend lacks {count:?}");
        }
    }
}
