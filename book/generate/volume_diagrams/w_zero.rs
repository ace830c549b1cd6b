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
            for t in [1.0, 3.0, 9.0] {
                if let Some(p) = px(rel(v + t * away(v))) {
                    s.circle(fit.at(p), 2.5, &fill(SIL, "none"));
                }
            }
        }
        let (v, _, inf) = ends[0];
        s.circle(fit.at(inf), 6.0, &fill("#9467bd", "#222"));
        let heading = ["(a) point light p", "(b) directional light d"][k];
        s.text((x0, 62.0), 14.0, "start", heading);
        let at_px = format!("→ pixel ({:.0}, {:.0})", inf.0, inf.1);
        let lines = match light {
            LightDir::Point(_) => vec![
                format!("p = {}, light 0", v3(c.light)),
                format!("v = {}, w = 1 (a silhouette vertex)", v3(v)),
                format!(
                    "(v − p, 0) = ({}, 0)",
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
         silhouette vertex v pushed away from the light; the dots are v + t·(direction) for \
         t = 1, 3, 9, closing in on the purple point, the projection of the w = 0 point: where \
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
