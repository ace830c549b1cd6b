//! The choosing chapter's second volume table: lesson 05's three routes
//! measured elsewhere, on an NVIDIA H100 (`book/measured/h100-631f993/`,
//! whose README gives the commit and the commands). Until a GPU set of
//! records is committed (`workbook book --adapter any`), this is what the
//! chapter cites for the routes' order on a GPU.

use std::path::Path;

use anyhow::{Context, Result};
use common::measure::report::Report;

use crate::table::{count, header, row};

/// The measured reports, relative to the repository's root.
pub const DIR: &str = "book/measured/h100-631f993";

/// Each report: its file, the scene in words, the caster's triangles.
const SCENES: &[(&str, &str, u64)] = &[
    ("torus_64.json", "torus 64×32", 64 * 32 * 2),
    ("torus_256.json", "torus 256×128", 256 * 128 * 2),
    ("lesson_05_holed.json", "`lesson_05_holed`", 50_400),
    ("lesson_05_dense.json", "`lesson_05_dense`", 98_304),
    ("torus_512.json", "torus 512×512", 512 * 512 * 2),
    ("torus_1024.json", "torus 1024×512", 1024 * 512 * 2),
];

const ROUTES: [&str; 3] = ["zpass_cpu", "zpass_quads", "zpass_compute"];

/// The table: per scene and route, the GPU total, the base pass (the same
/// work in every route: where it is slower, the GPU's clock had fallen),
/// the CPU's silhouette, and GPU + CPU, a floor under the frame's cost.
pub fn table(root: &Path) -> Result<String> {
    let mut s = String::new();
    let mut head_done = false;
    for (file, scene, triangles) in SCENES {
        let path = root.join(DIR).join(file);
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let r: Report = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a report", path.display()))?;
        if !head_done {
            s += &format!(
                "*{} · {}×{} · measured elsewhere with the protocol of commit `631f993` (2 warm-up frames; median of the frames of one process): `{DIR}/README.md` gives the commands · GPU ms from timestamps, CPU ms from the CPU's clock*\n\n",
                crate::record::adapter_label(&r.adapter.name, &r.adapter.backend),
                r.width,
                r.height
            );
            s += &header(&HEAD.map(String::from));
            head_done = true;
        }
        let fastest = ROUTES
            .iter()
            .filter_map(|&n| r.variants.iter().find(|v| v.name == n))
            .map(|v| cost(&v.timing_ms))
            .fold(f64::INFINITY, f64::min);
        for name in ROUTES {
            let Some(v) = r.variants.iter().find(|v| v.name == name) else {
                continue;
            };
            let t = &v.timing_ms;
            let get = |k: &str| t.get(k).map_or("—".to_string(), |x| format!("{x:.2}"));
            let c = cost(t);
            let mark = if c == fastest { " (least)" } else { "" };
            s += &row(&[
                scene.to_string(),
                count(*triangles),
                format!("`{name}`"),
                get("total"),
                get("base"),
                get("cpu_silhouette"),
                format!("{c:.2}{mark}"),
            ]);
        }
    }
    s += &crate::legend::legend_own(&HEAD.map(String::from), LEGEND);
    Ok(s)
}

/// The table's columns.
const HEAD: [&str; 7] = [
    "scene",
    "caster triangles",
    "route",
    "GPU ms",
    "base pass ms",
    "CPU silhouette ms",
    "GPU + CPU ms",
];

/// What they mean.
const LEGEND: &[(&str, &str)] = &[
    ("scene", "the scene: a floor and a generated torus of major × minor segments, or one of lesson 05's scene files"),
    ("caster triangles", "the caster's triangles (the torus: two a quad)"),
    ("route", "lesson 05's variant, how the volumes are built: `zpass_cpu` finds the silhouettes on the CPU every frame; `zpass_quads` sends a degenerate quad for every edge, built once, and extrudes it in the vertex shader; `zpass_compute` finds silhouettes and writes the sides in a compute pass, drawn indirectly"),
    ("GPU ms", "the GPU's time for the whole frame, first timestamp to last: median of the process's frames, ms"),
    ("base pass ms", "the base pass's GPU time (the scene's depth and colour, no shadow): the same work in every route, so where it is slower the GPU's clock had fallen; median, ms"),
    ("CPU silhouette ms", "the CPU's time finding silhouettes and building the volumes: median, ms; — for the routes that do it on the GPU"),
    ("GPU + CPU ms", "GPU ms + CPU silhouette ms: a floor under the frame's cost when the two do not overlap; (least): the lowest of the routes on that scene"),
];

/// GPU total plus the CPU's silhouette: what a frame costs at least when
/// the two do not overlap.
fn cost(t: &std::collections::BTreeMap<String, f64>) -> f64 {
    t.get("total").copied().unwrap_or(f64::NAN) + t.get("cpu_silhouette").copied().unwrap_or(0.0)
}

/// Writes `choosing/volumes_gpu.md`.
pub fn write(root: &Path, generated: &Path) -> Result<()> {
    let path = generated.join("choosing/volumes_gpu.md");
    std::fs::write(&path, table(root)?).with_context(|| format!("cannot write {}", path.display()))
}
