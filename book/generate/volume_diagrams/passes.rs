//! Lesson 05's three passes in a frame (`volume_passes.svg`): one row a
//! pass, with the depth, stencil and colour state each sets.

use workbook::lesson_05::stencil::{lit_stencil, Counting};
use workbook::lesson_05::volumes::CasterDraw;

use crate::diagrams::svg::{fill, stroke, Svg};

/// One pass's row: its background, then its cells (pass, depth, stencil,
/// colour), each a list of lines.
type PassRow = (
    &'static str,
    Vec<String>,
    Vec<String>,
    Vec<String>,
    Vec<String>,
);

/// A stencil face's rule, as the pipeline states it.
fn face_rule(f: &wgpu::StencilFaceState) -> String {
    format!(
        "compare {:?}; depth pass {:?}, depth fail {:?}, fail {:?}",
        f.compare, f.pass_op, f.depth_fail_op, f.fail_op
    )
}

/// Lesson 05's three passes in a frame, one row each, with the depth,
/// stencil and colour state each sets. The stencil cells and the parts of
/// the volume drawn are read from the lesson's code (`Counting::zpass`,
/// `lit_stencil`, `CasterDraw::zpass`); the depth and colour cells are
/// typed here, as `SceneGpu::new`, the volume pipelines and
/// `SceneGpu::lit_pipeline` set them inside pipeline creation, which needs
/// a device.
pub(super) fn passes() -> String {
    let counting = Counting::zpass();
    let (zpass, lit) = (counting.zpass, lit_stencil());
    let draw = CasterDraw::zpass(0);
    let parts = match (draw.front_cap, draw.back_cap) {
        (false, false) => "the sides only, no caps",
        (true, false) => "the sides and the front cap",
        (false, true) => "the sides and the back cap",
        (true, true) => "the sides and both caps",
    };
    let both = |st: &wgpu::StencilState| -> Vec<String> {
        if st.front == st.back {
            vec![format!("both faces: {}", face_rule(&st.front))]
        } else {
            vec![
                format!("front faces: {}", face_rule(&st.front)),
                format!("back faces: {}", face_rule(&st.back)),
            ]
        }
    };
    let mask = |st: &wgpu::StencilState| {
        format!(
            "read mask 0x{:02x}, write mask 0x{:02x}",
            st.read_mask, st.write_mask
        )
    };
    let mut volume_stencil = vec!["cleared to 0 (LoadOp::Clear(0))".to_string()];
    volume_stencil.extend(both(&zpass));
    volume_stencil.push(mask(&zpass));
    let mut lit_stencil_cell = both(&lit);
    lit_stencil_cell.push("reference 0: draws where the count is 0".into());
    lit_stencil_cell.push(mask(&lit));
    let rows: [PassRow; 3] = [
        (
            "#eef3fb",
            vec![
                "1. base pass".into(),
                "once a frame".into(),
                "draws every object".into(),
            ],
            vec![
                "test Less".into(),
                "write on: the visible surface's depth".into(),
            ],
            vec!["not used".into()],
            vec![
                "writes the ambient colour: the light every surface gets, shadowed or not".into(),
                "for the measurements: which object covers each pixel".into(),
                "no blending".into(),
            ],
        ),
        (
            "#fff6dc",
            vec![
                "2. volume pass".into(),
                "per light".into(),
                format!("draws the volumes: {parts}"),
                "cull none: front faces (a ray enters) and back faces (it leaves) both count"
                    .into(),
            ],
            vec![
                "test Less against pass 1's depth".into(),
                "write off".into(),
            ],
            volume_stencil,
            vec!["none: no fragment stage, no colour target".into()],
        ),
        (
            "#eaf6ea",
            vec![
                "3. lit pass".into(),
                "per light".into(),
                "draws every object again".into(),
            ],
            vec![
                "test LessEqual: equal to pass 1's depth".into(),
                "write off".into(),
            ],
            lit_stencil_cell,
            vec![
                "adds the light: blend One + One (colour)".into(),
                "for the measurements: 1 into the light's visibility image (0 where the stencil \
                 stops the pass)"
                    .into(),
            ],
        ),
    ];
    let title = "Lesson 05's passes: what each tests and writes";
    let w = 860.0;
    let mut s = Svg::new(w, 0.0, title);
    let cols = [
        (20.0, 165.0),
        (185.0, 150.0),
        (335.0, 305.0),
        (640.0, 200.0),
    ];
    let heads = ["pass", "depth", "stencil", "colour"];
    let mut y = 58.0;
    for (&(x, _), h) in cols.iter().zip(heads) {
        s.text((x + 6.0, y), 13.0, "start", h);
    }
    y += 10.0;
    for (bg, a, b, c, d) in rows {
        // Each cell wrapped to its column; the row as tall as its tallest.
        let cells: Vec<Vec<String>> = [a, b, c, d]
            .iter()
            .zip(cols)
            .map(|(lines, (_, cw))| {
                lines
                    .iter()
                    .flat_map(|l| crate::diagrams::svg::wrap(l, 12.0, cw - 14.0))
                    .collect()
            })
            .collect();
        let rows_h = cells.iter().map(|c| c.len()).max().unwrap_or(1) as f64 * 17.0 + 14.0;
        s.rect((20.0, y), (w - 40.0, rows_h), &fill(bg, "#999"));
        for (cell, &(x, _)) in cells.iter().zip(&cols) {
            s.texts((x + 6.0, y + 20.0), 12.0, "start", cell);
        }
        y += rows_h;
    }
    for &(x, _) in &cols[1..] {
        s.line((x, 68.0), (x, y), &stroke("#999", 1.0, ""));
    }
    let note = "The volume pass loads pass 1's depth and never writes it, so every light's \
        volumes are tested against the same surfaces; the lit pass adds the light only where \
        the volume pass left the stencil at 0.";
    s.h = s.para((20.0, y + 24.0), 12.0, "start", w - 40.0, note);
    s.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagrams::svg::tests::texts;

    /// One stencil face as the figure writes it: compare, depth pass,
    /// depth fail, fail.
    #[derive(Debug, Clone)]
    struct Face {
        compare: String,
        pass: String,
        depth_fail: String,
        fail: String,
    }

    /// The word after `key` in `text` (from `from`), without its comma or
    /// semicolon.
    fn word_after<'a>(text: &'a str, key: &str) -> &'a str {
        let at = text
            .find(key)
            .unwrap_or_else(|| panic!("no {key:?} in {text:?}"))
            + key.len();
        text[at..]
            .split_whitespace()
            .next()
            .unwrap()
            .trim_end_matches([',', ';', ':'])
    }

    /// The rule of `which` faces (`front`, `back`, or `both` for both) in
    /// one pass's text.
    fn face(text: &str, which: &str) -> Face {
        let key = format!("{which} faces: ");
        let at = text
            .find(&key)
            .unwrap_or_else(|| panic!("no {key:?} in {text:?}"));
        let rule = &text[at..];
        Face {
            compare: word_after(rule, "compare ").into(),
            pass: word_after(rule, "depth pass ").into(),
            depth_fail: word_after(rule, "depth fail ").into(),
            fail: word_after(rule, ", fail ").into(),
        }
    }

    fn faces(text: &str) -> (Face, Face) {
        if text.contains("both faces: ") {
            (face(text, "both"), face(text, "both"))
        } else {
            (face(text, "front"), face(text, "back"))
        }
    }

    /// A comparison as wgpu defines it: `new` against what is stored.
    fn compare(f: &str, new: i64, stored: i64) -> bool {
        match f {
            "Never" => false,
            "Less" => new < stored,
            "Equal" => new == stored,
            "LessEqual" => new <= stored,
            "Greater" => new > stored,
            "NotEqual" => new != stored,
            "GreaterEqual" => new >= stored,
            "Always" => true,
            _ => panic!("compare {f:?}"),
        }
    }

    /// A stencil operation on the 8-bit value `s`, reference 0.
    fn apply(op: &str, s: u8) -> u8 {
        match op {
            "Keep" => s,
            "Zero" | "Replace" => 0,
            "Invert" => !s,
            "IncrementClamp" => s.saturating_add(1),
            "DecrementClamp" => s.saturating_sub(1),
            "IncrementWrap" => s.wrapping_add(1),
            "DecrementWrap" => s.wrapping_sub(1),
            _ => panic!("stencil op {op:?}"),
        }
    }

    /// One fragment of a volume face at `depth` over the surface at
    /// `surface`, through the volume pass's depth test and stencil rule.
    fn fragment(rule: &Face, depth_test: &str, depth: i64, surface: i64, s: u8) -> u8 {
        if !compare(&rule.compare, 0, s as i64) {
            return apply(&rule.fail, s);
        }
        if compare(depth_test, depth, surface) {
            apply(&rule.pass, s)
        } else {
            apply(&rule.depth_fail, s)
        }
    }

    /// The states the figure writes make the z-pass count. Read back from
    /// its text (the depth test and stencil rule of the volume pass, the
    /// stencil rule and depth test of the lit pass), they are run on
    /// view rays that start outside every volume: each ray crosses a few
    /// volumes' sides, entering by a face turned to the eye and leaving
    /// by one turned away (or never, to infinity), and ends on a surface.
    /// The lit pass must then draw exactly where the surface point lies in
    /// no volume, counted here from the intervals.
    #[test]
    fn the_states_written_count_the_volumes_in_front_of_the_surface() {
        let svg = passes();
        let words: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
        let all = words.join(" ");
        let volume_at = all.find("2. volume pass").expect("the volume pass");
        let lit_at = all.find("3. lit pass").expect("the lit pass");
        let end = all.find("The stencil cells").unwrap_or(all.len());
        let (volume, lit) = (&all[volume_at..lit_at], &all[lit_at..end]);
        assert!(volume.contains("cleared to 0"), "{volume}");
        assert!(volume.contains("the sides only, no caps"), "{volume}");
        let volume_depth = word_after(volume, "test ");
        let (front, back) = faces(volume);
        let (lit_rule, _) = faces(lit);
        let lit_depth = word_after(lit, "test ");
        assert!(lit.contains("reference 0"), "{lit}");
        // The lit pass draws the surface again, at its own depth.
        assert!(
            compare(lit_depth, 500, 500),
            "the lit pass's depth test {lit_depth}"
        );
        // Random rays, from a fixed seed.
        let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = |n: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % n
        };
        for _ in 0..20_000 {
            // Depths: the surface's even, the faces' odd, so that no face
            // lies on the surface (a tie either way).
            let surface = 2 * (1 + next(500) as i64);
            let volumes = next(6);
            let (mut s, mut holding) = (0u8, 0);
            for _ in 0..volumes {
                let enter = 1 + 2 * next(500) as i64;
                let leave = enter + 2 * (1 + next(300) as i64);
                let leave = (next(4) > 0).then_some(leave); // else to infinity
                holding += i32::from(enter < surface && leave.is_none_or(|l| surface < l));
                s = fragment(&front, volume_depth, enter, surface, s);
                if let Some(l) = leave {
                    s = fragment(&back, volume_depth, l, surface, s);
                }
            }
            let drawn = compare(&lit_rule.compare, 0, s as i64);
            assert_eq!(
                drawn,
                holding == 0,
                "surface {surface}: stencil {s}, in {holding} volumes"
            );
        }
    }
}
