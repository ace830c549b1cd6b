//! Picture (d), the stencil counts (`volume_stencil_counts.svg`): lesson 05's
//! z-pass stencil value over a frame of its scene, cell by cell, from its
//! own counting rule.

use anyhow::Result;
use common::glam::Vec3;
use common::reference::bvh::Bvh;
use common::reference::primary_ray;
use common::scene::camera::camera_matrices;
use common::scene::mesh::face_normal;
use common::scene::{LightKind, Scene};
use workbook::lesson_05::silhouette::{casts_two_sided, LightDir};
use workbook::lesson_05::stencil::segment_crosses;

use crate::diagrams::svg::{fill, Svg, INK};

const COLS: u32 = 96;
const ROWS: u32 = 54;
const CELL: f64 = 3.9;
const COUNT_COLOURS: [&str; 5] = ["#f2f2f2", "#9ecae1", "#4292c6", "#08519c", "#08306b"];

/// Lesson 05's z-pass stencil value at the surface each cell's ray hits:
/// the number of light-facing caster triangles between the point and the
/// light, each one's own volume holding the point (as `max_volume_overlap`
/// counts it). `None` where the ray hits nothing.
fn stencil_grid(scene: &Scene, light: usize) -> Result<Vec<Option<u32>>> {
    let tris = scene.world_triangles();
    let bvh = Bvh::try_build(tris.iter().map(|(t, _)| *t).collect())?;
    let o = scene.origin();
    let l = match scene.lights[light].kind {
        LightKind::Directional { direction } => LightDir::Directional(direction.as_vec3()),
        LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
            LightDir::Point((position - o).as_vec3())
        }
    };
    let two: Vec<bool> = scene
        .objects
        .iter()
        .map(|o| casts_two_sided(&o.mesh))
        .collect();
    let lit: Vec<[Vec3; 3]> = tris
        .iter()
        .filter(|(_, i)| scene.objects[*i as usize].casts_shadow)
        .filter(|(t, i)| {
            let n = face_normal(t[0], t[1], t[2]);
            let towards = match l {
                LightDir::Point(p) => n.dot(p - t[0]),
                LightDir::Directional(d) => n.dot(-d),
            };
            towards > 0.0 || (two[*i as usize] && towards < 0.0)
        })
        .map(|(t, _)| *t)
        .collect();
    let inv = camera_matrices(scene, COLS, ROWS)
        .view_proj
        .as_dmat4()
        .inverse();
    let mut out = Vec::new();
    for j in 0..ROWS {
        for i in 0..COLS {
            let (org, d) = primary_ray(inv, i, j, COLS, ROWS);
            let Some(hit) = bvh.closest_hit(org, d, f32::INFINITY) else {
                out.push(None);
                continue;
            };
            let p = org + d * hit.t;
            let (to, t_max) = match l {
                LightDir::Point(lp) => ((lp - p).normalize(), (lp - p).length()),
                LightDir::Directional(dir) => (-dir.normalize(), f32::INFINITY),
            };
            out.push(Some(
                lit.iter()
                    .filter(|t| segment_crosses(p, to, t_max, t))
                    .count() as u32,
            ));
        }
    }
    Ok(out)
}

pub(super) fn stencil_counts(scene: &Scene) -> Result<String> {
    let title = "The stencil after the volume pass: lesson 05's default scene, one count per light";
    let (pw, gap, left) = (COLS as f64 * CELL, 24.0, 28.0);
    let mut s = Svg::new(2.0 * pw + gap + 2.0 * left, 0.0, title);
    let mut tally = vec![0u32; COUNT_COLOURS.len()];
    let mut sky = 0;
    let names = ["light 0 (point)", "light 1 (directional)"];
    for (k, name) in names.iter().enumerate() {
        let grid = stencil_grid(scene, k)?;
        let x0 = left + k as f64 * (pw + gap);
        s.text((x0, 54.0), 13.0, "start", name);
        for j in 0..ROWS {
            // One rectangle per run of equal values along the row.
            let row = &grid[(j * COLS) as usize..((j + 1) * COLS) as usize];
            let mut i = 0;
            while i < row.len() {
                let run = row[i..].iter().take_while(|v| **v == row[i]).count();
                let colour = match row[i] {
                    None => "#fff",
                    Some(c) => COUNT_COLOURS[(c as usize).min(COUNT_COLOURS.len() - 1)],
                };
                let at = (x0 + i as f64 * CELL, 62.0 + j as f64 * CELL);
                let style = format!(r#"fill="{colour}" stroke="none""#);
                s.rect(at, (run as f64 * CELL + 0.3, CELL + 0.3), &style);
                i += run;
            }
        }
        s.rect((x0, 62.0), (pw, ROWS as f64 * CELL), INK);
        for v in &grid {
            match v {
                None => sky += 1,
                Some(c) => tally[(*c as usize).min(COUNT_COLOURS.len() - 1)] += 1,
            }
        }
    }
    let mut y = 62.0 + ROWS as f64 * CELL + 26.0;
    let top = COUNT_COLOURS.len() - 1;
    let mut rows: Vec<(String, String)> = Vec::new();
    for (v, n) in tally.iter().enumerate() {
        if *n == 0 {
            continue;
        }
        let value = if v == top {
            format!("{v} or more")
        } else {
            v.to_string()
        };
        let meaning = match v {
            0 => "outside every volume: lit".to_string(),
            1 => "inside one volume: in shadow".to_string(),
            _ => format!("inside {v} volumes at once: in shadow"),
        };
        rows.push((
            fill(COUNT_COLOURS[v], "#888"),
            format!("{value}: {meaning} ({n} cells)"),
        ));
    }
    rows.push((fill("#fff", "#888"), format!("no surface ({sky} cells)")));
    let half = rows.len().div_ceil(2);
    for (c, chunk) in rows.chunks(half).enumerate() {
        let x = left + c as f64 * (pw + gap);
        for (i, (style, t)) in chunk.iter().enumerate() {
            let yy = y + 18.0 * i as f64;
            s.rect((x, yy - 10.0), (16.0, 11.0), style);
            s.text((x + 24.0, yy), 12.0, "start", t);
        }
    }
    y += 18.0 * half as f64 + 8.0;
    let note = format!(
        "Each cell is one pixel of a {COLS}×{ROWS} frame from the scene's camera: the z-pass \
         count at the surface it sees, computed on the CPU as the number of lit caster triangles \
         between that point and the light (each holds the point in its own volume). The lit \
         pass adds the light only where the count is 0."
    );
    s.h = s.para((left, y), 12.0, "start", s.w - 2.0 * left, &note);
    Ok(s.finish())
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use common::glam::DVec3;

    use super::super::independent::scene;
    use super::*;
    use crate::diagrams::svg::tests::{elements, number};

    /// Where the segment `o + t d`, `1e-4 < t < t_max`, crosses the
    /// triangle (Möller–Trumbore, in `f64`).
    fn crosses(o: DVec3, d: DVec3, t_max: f64, [a, b, c]: [DVec3; 3]) -> bool {
        let (e1, e2) = (b - a, c - a);
        let p = d.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-15 {
            return false;
        }
        let s = o - a;
        let u = s.dot(p) / det;
        let q = s.cross(e1);
        let v = d.dot(q) / det;
        let t = e2.dot(q) / det;
        u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 1e-4 && t < t_max
    }

    /// One caster: its triangles, its bounding sphere, and whether it is
    /// closed (each edge, its vertices welded by position, has two faces).
    struct Solid {
        tris: Vec<[DVec3; 3]>,
        centre: DVec3,
        radius: f64,
        closed: bool,
    }

    fn solids(scene: &Scene) -> Vec<Solid> {
        let mut by_object: BTreeMap<u32, Vec<[DVec3; 3]>> = BTreeMap::new();
        for (t, i) in scene.world_triangles() {
            if scene.objects[i as usize].casts_shadow {
                by_object
                    .entry(i)
                    .or_default()
                    .push(t.map(|p| p.as_dvec3()));
            }
        }
        let key = |p: DVec3| (p * 1e4).round().as_i64vec3().to_array();
        by_object
            .into_values()
            .map(|tris| {
                let mut edges: BTreeMap<_, u32> = BTreeMap::new();
                for t in &tris {
                    for k in 0..3 {
                        let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
                        *edges
                            .entry(if a < b { (a, b) } else { (b, a) })
                            .or_default() += 1;
                    }
                }
                let n = (tris.len() * 3) as f64;
                let centre = tris.iter().flatten().fold(DVec3::ZERO, |s, p| s + *p / n);
                let radius = tris
                    .iter()
                    .flatten()
                    .map(|p| p.distance(centre))
                    .fold(0.0, f64::max);
                Solid {
                    closed: edges.values().all(|&n| n == 2),
                    tris,
                    centre,
                    radius,
                }
            })
            .collect()
    }

    /// How many shadow volumes hold the point `p` for a light at `l` (or
    /// along `dir`): how many times the way from the light to `p` enters a
    /// caster. A closed caster is entered once for each two crossings of
    /// its surface, the last one counted when `p` is on its far side (an
    /// odd count); an open one (a two-sided surface) once for each.
    fn volumes_holding(solids: &[Solid], p: DVec3, light: Result<DVec3, DVec3>) -> u32 {
        let (to, t_max) = match light {
            Ok(l) => ((l - p).normalize(), p.distance(l)),
            Err(dir) => (-dir.normalize(), f64::INFINITY),
        };
        solids
            .iter()
            .map(|s| {
                // The sphere behind the start or beyond the light is missed.
                let along = (s.centre - p).dot(to).clamp(0.0, t_max);
                if (p + to * along).distance(s.centre) > s.radius {
                    return 0;
                }
                let n = s.tris.iter().filter(|t| crosses(p, to, t_max, **t)).count() as u32;
                if s.closed {
                    n.div_ceil(2)
                } else {
                    n
                }
            })
            .sum()
    }

    /// The counts drawn, read back from the cells' rectangles: per panel,
    /// `None` for no surface, else the colour's count (4 for "4 or more").
    fn drawn(svg: &str) -> Vec<Vec<Option<u32>>> {
        let pw = COLS as f64 * CELL;
        let mut out = vec![vec![Some(99); (COLS * ROWS) as usize]; 2];
        for r in elements(svg, "rect") {
            if r.get("stroke").map(String::as_str) != Some("none") {
                continue;
            }
            let (x, y, w) = (number(&r, "x"), number(&r, "y"), number(&r, "width"));
            let k = usize::from(x > 28.0 + pw + 12.0);
            let i = ((x - 28.0 - k as f64 * (pw + 24.0)) / CELL).round() as u32;
            let j = ((y - 62.0) / CELL).round() as u32;
            let run = ((w - 0.3) / CELL).round() as u32;
            let value = match r["fill"].as_str() {
                "#fff" => None,
                c => Some(
                    COUNT_COLOURS
                        .iter()
                        .position(|x| *x == c)
                        .expect("a count's colour") as u32,
                ),
            };
            for c in i..i + run {
                out[k][(j * COLS + c) as usize] = value;
            }
        }
        out
    }

    /// Every cell's colour is the number of shadow volumes holding the
    /// surface point it sees, counted here as the times the segment from
    /// the light to that point enters a caster (its own ray–triangle test
    /// on every caster triangle, not the lesson's lit triangles), for the
    /// point light and for the directional one.
    #[test]
    fn each_cell_is_the_number_of_volumes_holding_its_point() {
        let scene = scene();
        let svg = stencil_counts(&scene).unwrap();
        let got = drawn(&svg);
        let solids = solids(&scene);
        let tris = scene.world_triangles();
        let bvh = Bvh::try_build(tris.iter().map(|(t, _)| *t).collect()).unwrap();
        let inv = camera_matrices(&scene, COLS, ROWS)
            .view_proj
            .as_dmat4()
            .inverse();
        let o = scene.origin();
        let mut shadowed = [0; 2];
        for (k, light) in scene.lights.iter().enumerate() {
            let light = match light.kind {
                LightKind::Directional { direction } => Err(direction),
                LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
                    Ok(position - o)
                }
            };
            let mut wrong = Vec::new();
            for j in 0..ROWS {
                for i in 0..COLS {
                    let (org, d) = primary_ray(inv, i, j, COLS, ROWS);
                    let want = bvh.closest_hit(org, d, f32::INFINITY).map(|hit| {
                        let p = (org + d * hit.t).as_dvec3();
                        volumes_holding(&solids, p, light).min(COUNT_COLOURS.len() as u32 - 1)
                    });
                    shadowed[k] += usize::from(want.is_some_and(|c| c > 0));
                    if got[k][(j * COLS + i) as usize] != want {
                        wrong.push((i, j, got[k][(j * COLS + i) as usize], want));
                    }
                }
            }
            assert!(
                wrong.is_empty(),
                "light {k}: cells (column, row, drawn, counted): {wrong:?}"
            );
        }
        assert!(
            shadowed.iter().all(|&n| n > 100),
            "shadowed cells: {shadowed:?}"
        );
    }
}
