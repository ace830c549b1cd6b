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
