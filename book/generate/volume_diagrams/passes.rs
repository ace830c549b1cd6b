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
                "writes the ambient term and the object id".into(),
                "no blending".into(),
            ],
        ),
        (
            "#fff6dc",
            vec![
                "2. volume pass".into(),
                "per light".into(),
                format!("draws the volumes: {parts}"),
                "cull none: both faces count".into(),
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
                "writes the light's visibility".into(),
            ],
        ),
    ];
    let title = "Lesson 05's passes: what each tests and writes";
    let w = 860.0;
    let mut s = Svg::new(w, 0.0, title);
    let cols = [
        (20.0, 165.0),
        (185.0, 160.0),
        (345.0, 340.0),
        (685.0, 155.0),
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
    let note = "The stencil cells and the volume's parts are read from the lesson's code \
        (Counting::zpass, lit_stencil, CasterDraw::zpass); the depth and colour cells are as \
        SceneGpu and the volume pipelines set them. The volume pass loads pass 1's depth and \
        never writes it, so every light's volumes are tested against the same surfaces.";
    s.h = s.para((20.0, y + 24.0), 12.0, "start", w - 40.0, note);
    s.finish()
}
