//! Chapter 04's cube faces (`cube_faces.svg`): the six faces as lesson 04's
//! cross writes them, each face's texel directions from its real
//! view-projection, checked to meet at every shared edge.

use anyhow::{bail, Context, Result};
use common::glam::DVec3;
use workbook::lesson_04::faces::{face_view_proj, CUBE_FACES};

use super::svg::{fill, vec_text, Svg};

/// Lesson 04's cross (`cross.rs`): +Y above; −X +Z +X −Z; −Y below, as
/// (forward axis, column, row).
const CROSS: [(DVec3, usize, usize); 6] = [
    (DVec3::Y, 1, 0),
    (DVec3::NEG_X, 0, 1),
    (DVec3::Z, 1, 1),
    (DVec3::X, 2, 1),
    (DVec3::NEG_Z, 3, 1),
    (DVec3::NEG_Y, 1, 2),
];

fn axis_name(v: DVec3) -> String {
    let (i, c) = (0..3)
        .map(|i| (i, v[i]))
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .unwrap_or((0, 0.0));
    format!("{}{}", if c < 0.0 { "−" } else { "+" }, ["X", "Y", "Z"][i])
}

/// A face's texel directions from its real view-projection: u = the axis
/// that moves right in the window, v = the one that moves down.
fn face_uv(face: usize) -> Result<(DVec3, DVec3)> {
    let m = face_view_proj(DVec3::ZERO, face, 0.1, 10.0).as_dmat4();
    let axes = [DVec3::X, DVec3::Y, DVec3::Z].map(|e| [e, -e]).concat();
    let ndc = |e: DVec3| m.project_point3(CUBE_FACES[face].0 + 0.5 * e);
    let u = axes
        .iter()
        .find(|&&e| ndc(e).x > 0.4)
        .context("no u axis")?;
    let v = axes
        .iter()
        .find(|&&e| ndc(e).y < -0.4)
        .context("no v axis")?;
    Ok((*u, *v))
}

pub(super) fn cube_faces() -> Result<String> {
    let (cell, left, top) = (165.0, 30.0, 50.0);
    let title = "The six cube faces as lesson 04's cross writes them (CUBE_FACES)";
    let mut s = Svg::new(left * 2.0 + 4.0 * cell, 0.0, title);
    let mut placed = Vec::new();
    for (face, &(forward, up)) in CUBE_FACES.iter().enumerate() {
        let cross = CROSS.iter().find(|c| c.0 == forward);
        let &(_, col, row) = cross.context("face missing from the cross")?;
        let (u, v) = face_uv(face)?;
        placed.push((col, row, forward, u, v));
        let (x, y) = (left + col as f64 * cell, top + row as f64 * cell);
        s.rect((x, y), (cell, cell), &fill("#eef3fb", "#222"));
        let name = format!("face {face}: {}", axis_name(forward));
        s.text((x + cell / 2.0, y + 28.0), 17.0, "middle", &name);
        let lines = [
            format!("forward {}", vec_text(forward)),
            format!("up {}", vec_text(up)),
        ];
        s.texts((x + cell / 2.0, y + 52.0), 12.0, "middle", &lines);
        s.arrow((x + 40.0, y + 148.0), (x + 135.0, y + 148.0), "#1f5fbf");
        let u = format!("u → {}", axis_name(u));
        s.text((x + 88.0, y + 140.0), 13.0, "middle", &u);
        s.arrow((x + 16.0, y + 84.0), (x + 16.0, y + 150.0), "#d62728");
        let v = format!("v ↓ {}", axis_name(v));
        s.text((x + 24.0, y + 104.0), 13.0, "start", &v);
    }
    // Neighbouring cells must share their edge: the diagram checks itself.
    for &(c1, r1, f1, u1, v1) in &placed {
        for &(c2, r2, f2, u2, v2) in &placed {
            let right = c2 == c1 + 1 && r2 == r1 && (f1 + u1 != f2 - u2 || v1 != v2);
            let below = r2 == r1 + 1 && c2 == c1 && (f1 + v1 != f2 - v2 || u1 != u2);
            if right || below {
                let (a, b) = (axis_name(f1), axis_name(f2));
                bail!("cube cross: {a} and {b} do not share an edge");
            }
        }
    }
    let notes =
        "Index = the layer wgpu reads for that face. u, v: the texel column (right) and row \
        (down) directions of each face's view-projection (face_view_proj), checked to match at \
        every shared edge. The empty cells are black in the lesson's PNG.";
    let width = s.w - 2.0 * left;
    s.h = s.para((left, top + 3.0 * cell + 30.0), 13.0, "start", width, notes);
    Ok(s.finish())
}
