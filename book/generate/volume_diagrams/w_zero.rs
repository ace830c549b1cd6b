//! Picture (e), the extrusion to w = 0 (`volume_w_zero.svg`): the far ends
//! of the volume at infinity, where the projection still puts them on the
//! screen.

use anyhow::{Context, Result};
use common::glam::{DVec3, DVec4};
use common::scene::camera::camera_matrices;
use common::scene::{LightKind, Scene};
use workbook::lesson_05::silhouette::{face_facing, silhouette_edges_for, LightDir};

use super::caster::Caster;
use super::draw::{pixel, v3, Fit, AWAY, LIT, SIL};
use crate::diagrams::svg::{fill, stroke, Svg, P};

const W0_SIZE: (u32, u32) = (640, 360);

pub(super) fn w_zero(scene: &Scene, c: &Caster) -> Result<String> {
    let title = "Extrusion to w = 0: homogeneous points at infinity on lesson 05's screen";
    let (pw, left) = (370.0, 20.0);
    let mut s = Svg::new(2.0 * pw + 3.0 * left, 0.0, title);
    let (w, h) = W0_SIZE;
    let o = scene.origin();
    let vp = camera_matrices(scene, w, h).view_proj.as_dmat4();
    let px = |p: DVec4| pixel(vp, w as f64, h as f64, p);
    let rel = |p: DVec3| (p - o).extend(1.0);
    let dir = scene.lights.iter().find_map(|l| match l.kind {
        LightKind::Directional { direction } => Some(direction),
        _ => None,
    });
    let dir = dir.context("lesson_05.toml: no directional light")?;
    let mut bottom: f64 = 0.0;
    for (k, light) in [
        LightDir::Point(c.light.as_vec3()),
        LightDir::Directional(dir.as_vec3()),
    ]
    .into_iter()
    .enumerate()
    {
        let facing = face_facing(&c.adj, light);
        let mut verts: Vec<u32> = silhouette_edges_for(&c.adj, &facing)
            .iter()
            .map(|e| e.a)
            .collect();
        verts.sort_unstable();
        verts.dedup();
        // Where each silhouette vertex goes: its direction away from the light, w = 0.
        let away = |v: DVec3| match light {
            LightDir::Point(_) => v - c.light,
            LightDir::Directional(_) => dir,
        };
        let mut pts = vec![(0.0, 0.0), (w as f64, h as f64)];
        let mut ends = Vec::new();
        for &i in &verts {
            let v = c.pos(i);
            let inf = px(away(v).extend(0.0)).context("a vanishing point behind the eye")?;
            let near = px(rel(v)).context("the cube behind the eye")?;
            pts.extend([inf, near]);
            ends.push((v, near, inf));
        }
        let x0 = left + k as f64 * (pw + left);
        let fit = Fit::new(&pts, (x0, 80.0), (pw, 240.0));
        let (a, b) = (fit.at((0.0, 0.0)), fit.at((w as f64, h as f64)));
        s.rect(a, (b.0 - a.0, b.1 - a.1), &fill("#f4f7fb", "#222"));
        for (f, t) in c.adj.triangles.iter().enumerate() {
            let tri: Option<Vec<P>> = t
                .iter()
                .map(|&i| px(rel(c.pos(i))).map(|p| fit.at(p)))
                .collect();
            let colour = if facing[f] { LIT } else { AWAY };
            s.poly(
                &tri.context("the cube behind the eye")?,
                true,
                &fill(colour, "#666"),
            );
        }
        for &(v, near, inf) in &ends {
            s.line(fit.at(near), fit.at(inf), &stroke(SIL, 1.2, "5,3"));
            for k in [1.0, 3.0, 9.0] {
                if let Some(p) = px(rel(v + k * away(v))) {
                    s.circle(fit.at(p), 2.5, &fill(SIL, "none"));
                }
            }
        }
        let (v, _, inf) = ends[0];
        s.circle(fit.at(inf), 6.0, &fill("#9467bd", "#222"));
        let heading = ["(a) point light L", "(b) directional light d"][k];
        s.text((x0, 62.0), 14.0, "start", heading);
        let at_px = format!("→ pixel ({:.0}, {:.0})", inf.0, inf.1);
        let lines = match light {
            LightDir::Point(_) => vec![
                format!("L = {}, light 0", v3(c.light)),
                format!("v = {}, w = 1 (a silhouette vertex)", v3(v)),
                format!(
                    "(v − L, 0) = ({}, 0)",
                    &v3(v - c.light)[1..v3(v - c.light).len() - 1]
                ),
                format!("{at_px}: v's own vanishing point"),
            ],
            LightDir::Directional(_) => vec![
                format!("d = {}, light 1", v3(dir)),
                format!("(d, 0) = ({}, 0)", &v3(dir)[1..v3(dir).len() - 1]),
                format!("{at_px}: every extruded vertex"),
                format!("lands here ({} silhouette vertices)", verts.len()),
            ],
        };
        let mut y = 80.0 + 240.0 + 24.0;
        for l in &lines {
            y = s.para((x0, y), 12.0, "start", pw, l);
        }
        bottom = bottom.max(y);
    }
    let note = format!(
        "The {w}×{h} screen of the scene's camera (light blue) with the cube. Dashed red: each \
         silhouette vertex v pushed away from the light; the dots are v + k·(direction) for \
         k = 1, 3, 9, closing in on the purple point, the projection of the w = 0 point: where \
         that direction vanishes on screen. The rasteriser draws the volume's far vertices \
         there, with no finite length to choose and nothing for a far plane to clip."
    );
    s.h = s.para(
        (left, bottom + 10.0),
        12.0,
        "start",
        s.w - 2.0 * left,
        &note,
    );
    Ok(s.finish())
}

#[cfg(test)]
mod tests {
    use common::glam::DMat4;

    use super::super::independent::{
        cube_triangles, direction, faces_point, point_light, scene, silhouette,
    };
    use super::*;
    use crate::diagrams::svg::tests::{elements, number, texts};

    /// A world point through the scene's camera, to pixels of the
    /// `W0_SIZE` screen (y down).
    fn to_pixel(vp: DMat4, p: DVec3) -> P {
        let c = vp * p.extend(1.0);
        let (w, h) = (W0_SIZE.0 as f64, W0_SIZE.1 as f64);
        ((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h)
    }

    fn close(a: P, b: P, tol: f64) -> bool {
        (a.0 - b.0).abs() < tol && (a.1 - b.1).abs() < tol
    }

    /// What the purple points stand for: the projection of a point at
    /// infinity is where the projections of ever farther finite points go.
    /// Each silhouette vertex v (found here from the mesh and the light)
    /// is pushed a million times its distance along its way from the light
    /// (v − L, or d), with w = 1, and projected: the dashed line drawn
    /// from v ends there, the purple point of each panel is one of those
    /// ends (every vertex's, for the directional light), the pixel written
    /// under it is its pixel, and the dots drawn for k = 1, 3, 9 lie on
    /// the dashed line, each closer to its end than the one before.
    #[test]
    fn purple_points_are_where_farther_and_farther_points_project() {
        let scene = scene();
        let c = Caster::from_scene(&scene).unwrap();
        let svg = w_zero(&scene, &c).unwrap();
        let vp = camera_matrices(&scene, W0_SIZE.0, W0_SIZE.1)
            .view_proj
            .as_dmat4();
        let o = scene.origin();
        let px = |p: DVec3| to_pixel(vp, p - o);
        let tris = cube_triangles(&scene);
        let (light, dir) = (point_light(&scene), direction(&scene));
        let screens: Vec<_> = elements(&svg, "rect")
            .into_iter()
            .filter(|r| r["fill"] == "#f4f7fb")
            .collect();
        assert_eq!(screens.len(), 2, "two panels");
        let words: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
        let words = words.join(" ");
        let lines = elements(&svg, "line");
        let circles = elements(&svg, "circle");
        for (k, screen) in screens.iter().enumerate() {
            // The panel's page from the screen's pixels, read off its rectangle.
            let (x, y) = (number(screen, "x"), number(screen, "y"));
            let sx = number(screen, "width") / W0_SIZE.0 as f64;
            let sy = number(screen, "height") / W0_SIZE.1 as f64;
            let page = |p: P| (x + p.0 * sx, y + p.1 * sy);
            let in_panel = |px: f64| (px < 400.0) == (k == 0);
            let lit: Vec<bool> = match k {
                0 => tris.iter().map(|t| faces_point(t, light)).collect(),
                _ => tris
                    .iter()
                    .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).dot(-dir) > 0.0)
                    .collect(),
            };
            let mut verts: Vec<DVec3> = Vec::new();
            for (a, b) in silhouette(&tris, &lit) {
                for v in [a, b] {
                    if !verts.iter().any(|w| w.distance(v) < 1e-6) {
                        verts.push(v);
                    }
                }
            }
            let away = |v: DVec3| if k == 0 { v - light } else { dir };
            let ends: Vec<(P, P)> = verts
                .iter()
                .map(|&v| (page(px(v)), page(px(v + 1e6 * away(v)))))
                .collect();
            let dashed: Vec<(P, P)> = lines
                .iter()
                .filter(|l| l["stroke"] == SIL && in_panel(number(l, "x1")))
                .map(|l| {
                    (
                        (number(l, "x1"), number(l, "y1")),
                        (number(l, "x2"), number(l, "y2")),
                    )
                })
                .collect();
            assert_eq!(
                dashed.len(),
                ends.len(),
                "panel {k}: one dashed line a silhouette vertex"
            );
            for &(near, far) in &ends {
                let line = dashed.iter().find(|(a, _)| close(*a, near, 0.05));
                let line = line.unwrap_or_else(|| panic!("panel {k}: no line from {near:?}"));
                assert!(
                    close(line.1, far, 0.3),
                    "panel {k}: the line from {near:?} ends at {:?}, not {far:?}",
                    line.1
                );
                // The dots on this line: on it, closing in on its end.
                let d = (far.0 - near.0, far.1 - near.1);
                let len = d.0.hypot(d.1);
                let mut along: Vec<f64> = circles
                    .iter()
                    .filter(|e| e["fill"] == SIL && in_panel(number(e, "cx")))
                    .map(|e| (number(e, "cx") - near.0, number(e, "cy") - near.1))
                    .filter(|q| (q.0 * d.1 - q.1 * d.0).abs() / len < 0.05)
                    .map(|q| (q.0 * d.0 + q.1 * d.1) / len)
                    .collect();
                along.sort_by(f64::total_cmp);
                assert!(
                    along.len() >= 3 && along.iter().all(|s| *s > 0.0 && *s < len),
                    "panel {k}: dots {along:?} of {len}"
                );
            }
            let purple = circles
                .iter()
                .find(|e| e["fill"] == "#9467bd" && in_panel(number(e, "cx")))
                .expect("a purple point");
            let at = (number(purple, "cx"), number(purple, "cy"));
            let end = ends.iter().find(|(_, far)| close(*far, at, 0.3));
            let (_, far) = end
                .unwrap_or_else(|| panic!("panel {k}: the purple point {at:?} is no vertex's end"));
            let pixel = ((far.0 - x) / sx, (far.1 - y) / sy);
            let written = format!("→ pixel ({:.0}, {:.0})", pixel.0, pixel.1);
            assert!(
                words.contains(&written),
                "panel {k}: {written:?} is not written"
            );
        }
    }
}
