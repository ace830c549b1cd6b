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

#[cfg(test)]
mod tests {

    use super::super::svg::tests::{elements, is, number, texts};
    use super::*;

    /// "+X", "−Z", … as a unit vector.
    fn axis(s: &str) -> DVec3 {
        let sign = if s.starts_with('−') { -1.0 } else { 1.0 };
        let e = match s.chars().last() {
            Some('X') => DVec3::X,
            Some('Y') => DVec3::Y,
            Some('Z') => DVec3::Z,
            _ => panic!("{s:?} is no axis"),
        };
        sign * e
    }

    /// The cube-map rule of WebGPU (as Vulkan's and Direct3D's): the
    /// direction's major axis chooses the layer (+X −X +Y −Y +Z −Z), and
    /// the texel's (s, t) in [0, 1]² follow the layer's table row.
    fn sample(r: DVec3) -> (usize, f64, f64) {
        let a = r.abs();
        let (layer, sc, tc, ma) = if a.x >= a.y && a.x >= a.z {
            if r.x > 0.0 {
                (0, -r.z, -r.y, a.x)
            } else {
                (1, r.z, -r.y, a.x)
            }
        } else if a.y >= a.z {
            if r.y > 0.0 {
                (2, r.x, r.z, a.y)
            } else {
                (3, r.x, -r.z, a.y)
            }
        } else if r.z > 0.0 {
            (4, r.x, -r.y, a.z)
        } else {
            (5, -r.x, -r.y, a.z)
        };
        (layer, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0))
    }

    /// Each cell drawn: its face's index, forward axis, and texel axes u
    /// (column, right) and v (row, down), read off the picture. Every
    /// direction through the cell, forward + a u + b v for |a|, |b| < 1,
    /// has the drawn forward as its major axis, so the sampler reads the
    /// drawn layer there, at s = (1 + a)/2, t = (1 + b)/2: the drawn u and
    /// v are the texel directions.
    #[test]
    fn each_drawn_direction_selects_the_drawn_face_and_texel() {
        let svg = cube_faces().unwrap();
        let words = texts(&svg);
        let cells: Vec<_> = (elements(&svg, "rect").into_iter())
            .filter(|r| is(r, "fill", "#eef3fb"))
            .collect();
        assert_eq!(cells.len(), 6);
        let mut layers = Vec::new();
        for cell in &cells {
            let (x, y) = (number(cell, "x"), number(cell, "y"));
            let (w, h) = (number(cell, "width"), number(cell, "height"));
            let inside: Vec<&str> = (words.iter())
                .filter(|t| (x..x + w).contains(&t.0) && (y..y + h).contains(&t.1))
                .map(|t| t.2.as_str())
                .collect();
            let find = |key: &str| {
                let t = inside.iter().find(|t| t.starts_with(key));
                t.unwrap_or_else(|| panic!("{key:?} in {inside:?}"))[key.len()..].to_string()
            };
            let (index, name) = find("face ")
                .split_once(": ")
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .unwrap();
            let layer: usize = index.parse().unwrap();
            let (forward, u, v) = (axis(&name), axis(&find("u → ")), axis(&find("v ↓ ")));
            let vector = find("forward ").replace('−', "-");
            let xyz: Vec<f64> = (vector.trim_matches(|c| c == '(' || c == ')').split(", "))
                .map(|c| c.parse().unwrap())
                .collect();
            assert_eq!(DVec3::new(xyz[0], xyz[1], xyz[2]), forward, "face {layer}");
            for i in 0..=8 {
                for j in 0..=8 {
                    let (a, b) = (-0.96 + 0.24 * i as f64, -0.96 + 0.24 * j as f64);
                    let (got, s, t) = sample(forward + a * u + b * v);
                    assert_eq!(
                        got, layer,
                        "face {layer} ({name}): a {a}, b {b} selects {got}"
                    );
                    let want = (0.5 * (1.0 + a), 0.5 * (1.0 + b));
                    assert!(
                        (s - want.0).abs() < 1e-12 && (t - want.1).abs() < 1e-12,
                        "face {layer} ({name}): u {u}, v {v} drawn, but at a {a}, b {b} the \
                         sampler reads s {s}, t {t}"
                    );
                }
            }
            layers.push(layer);
        }
        layers.sort();
        assert_eq!(layers, [0, 1, 2, 3, 4, 5]);
    }

    /// The cross the diagram lays out is the lesson's (`cross.rs`'s
    /// shader: `if cell.y == R && cell.x == C { layer = L; }`).
    #[test]
    fn cross_is_the_lessons() {
        let root = &crate::repo_root();
        let src = std::fs::read_to_string(root.join("lessons/lesson_04/cross.rs")).unwrap();
        let mut found = 0;
        for line in src.lines().map(str::trim) {
            let Some(rest) = line.strip_prefix("if cell.y == ") else {
                continue;
            };
            let Some((row, rest)) = rest.split_once(" && cell.x == ") else {
                continue;
            };
            let Some((col, rest)) = rest.split_once(" { layer = ") else {
                continue;
            };
            let layer: usize = rest.trim_end_matches("; }").parse().unwrap();
            let forward = CUBE_FACES[layer].0;
            let cell = CROSS.iter().find(|c| c.0 == forward).unwrap();
            assert_eq!(
                (cell.1, cell.2),
                (col.parse().unwrap(), row.parse().unwrap()),
                "layer {layer}"
            );
            found += 1;
        }
        assert_eq!(found, 6);
    }
}
