//! What every column of a generated table means, written under the table
//! where it is read. The standard columns and every timed pass are defined
//! here once (every counter a lesson reports is defined with its legend in
//! `common::measure::counters`), in the order the tables
//! show them (what a technique gets wrong, then what it does, in the order
//! the frame does it, then what it costs). A table whose writer has columns
//! of its own passes their definitions with [`legend_with`].
//!
//! `tests/book_legends.rs` reads every generated table and fails when a
//! column has no entry in the legend under it.

use anyhow::{bail, Result};
use common::measure::counters::{self, Counter};

/// The standard columns of a run's tables.
const STANDARD: &[(&str, &str)] = &[
    ("variant", "the lesson's variant (its `--variant` name); each chapter's variants listing says what it changes"),
    ("scene", "the scene file the row was run on"),
    ("misclassified %", "the receiver pixels classified differently from the exact reference (lit where V ≥ ½), in % of the receiver pixels of every light"),
    ("false shadow %", "the receiver pixels shadowed here but lit in the reference (acne, over-long shadows), in % of the receiver pixels"),
    ("false lit %", "the receiver pixels lit here but shadowed in the reference (light leaks, Peter Panning), in % of the receiver pixels"),
    ("mean \\|ΔV\\| %", "the mean of |V − V_ref| over the receiver pixels, in %: it sees partial visibility (a penumbra, a blend) that misclassified % rounds away"),
    ("penumbra \\|ΔV\\| %", "a light with a size (a soft shadow): the mean of |V − V_ref| over the receiver pixels in the exact reference's penumbra (0 < V_ref < 1), in %: how far the penumbra's shade is from the visible fraction of the emitter; — where the variant reports none"),
    ("bleeding %", "a light with a size: of the receiver pixels in the exact reference's umbra (V_ref = 0, the emitter wholly hidden), the share the variant lights above V = 0.1, in %; near the umbra's rim this is mostly a blur's spill, light through a blocker (the variance maps' bleeding) is the classes table's leak %; 0 where the scene has no umbra"),
    ("frame ms", "the frame's wall-clock cost, from the start of recording to the GPU's completion: median [spread: the frames' interquartile range, widened to hold each run's median]"),
    ("GPU ms", "the GPU's time for the whole frame, from its timestamps: median [spread: the frames' interquartile range, widened to hold each run's median]"),
    ("CPU ms", "the CPU's time to record and submit the frame, waits for the GPU left out: median [spread: the frames' interquartile range, widened to hold each run's median]"),
    ("shadows cost (frame, vs no shadows)", "the frame's median over the no-shadow baseline's, when their spreads do not overlap (× the ratio); else no measurable difference"),
    ("vs the fastest", "the frame's median over the fastest variant's, when their spreads do not overlap; else no measurable difference"),
];

/// The timed passes of a frame (the passes tables' columns, `` `name` ms ``).
pub const PASSES: &[(&str, &str)] = &[
    (
        "base",
        "the base pass: the scene's depth and colour, with no shadow",
    ),
    (
        "shadow",
        "the shadow-map passes: every map, face and cascade",
    ),
    (
        "extrude",
        "the compute pass that finds silhouettes and writes the volumes",
    ),
    (
        "volume",
        "the shadow-volume pass into the stencil (and the bounds marks)",
    ),
    (
        "moments",
        "the compute pass that turns the depth map into moments (a variance map) and blurs them along x",
    ),
    (
        "blur",
        "the compute pass that blurs the moments again, along y",
    ),
    (
        "min_max",
        "the compute passes that build the map's min/max mip chain, one a level (`pcss_min_max`)",
    ),
    ("lighting", "the lit passes, one per light"),
    (
        "cpu_silhouette",
        "CPU time finding silhouettes and building the volumes",
    ),
    (
        "cpu_bounds",
        "CPU time computing the lights' range-sphere bounds",
    ),
    (
        "cpu_camera",
        "CPU time fitting a variant's own camera and uploading it",
    ),
    (
        "cpu_fit",
        "CPU time fitting the cascades to the view and uploading them",
    ),
    (
        "cpu_cull",
        "CPU time choosing, per cascade, the casters that can shadow its receivers and their scissor rectangles",
    ),
    (
        "cpu_record",
        "CPU time recording the frame's passes (wgpu's encoders)",
    ),
    ("cpu_total", "the CPU's time to record and submit the frame"),
    (
        "frame",
        "the frame's wall-clock cost, start of recording to GPU completion",
    ),
];

/// The rank of a counter in [`counters::ALL`] (unknown ones last, by name).
pub fn counter_rank(name: &str) -> (usize, String) {
    let i = counters::ALL.iter().position(|c| c.name == name);
    (i.unwrap_or(usize::MAX), name.to_string())
}

/// The rank of a pass in [`PASSES`].
pub fn pass_rank(name: &str) -> (usize, String) {
    let i = PASSES.iter().position(|(n, _)| *n == name);
    (i.unwrap_or(usize::MAX), name.to_string())
}

/// The definition of a standard column, a counter (`` `name` ``) or a
/// pass (`` `name` ms ``).
fn definition(column: &str) -> Option<String> {
    if let Some((_, d)) = STANDARD.iter().find(|(n, _)| *n == column) {
        return Some(d.to_string());
    }
    let code = column.strip_prefix('`')?;
    if let Some(name) = code.strip_suffix("` ms") {
        return PASSES
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, d)| format!("{d}: median [spread], ms"));
    }
    let name = code.strip_suffix('`')?;
    Counter::named(name).map(|c| c.legend.to_string())
}

/// The legend of a table whose writer defines its own columns (`own`),
/// the others taken from the standard ones. A column defined nowhere gets
/// an empty entry, which `tests/book_legends.rs` reports.
pub fn legend_own(columns: &[String], own: &[(&str, &str)]) -> String {
    details(&definitions(columns, own))
}

/// The legend of a table with `columns`: every column defined, in order.
pub fn legend(columns: &[String]) -> Result<String> {
    legend_with(columns, &[])
}

/// The legend, with the definitions of a table's own columns (`own`) taking
/// precedence over the standard ones.
pub fn legend_with(columns: &[String], own: &[(&str, &str)]) -> Result<String> {
    let defined = definitions(columns, own);
    if let Some((c, _)) = defined.iter().find(|(_, d)| d.is_none()) {
        bail!("the column {c:?} has no definition: add it to book/generate/legend.rs");
    }
    Ok(details(&defined))
}

/// Each column with its definition: the table's own (`own`) first, then
/// the standard one; `None` where neither defines it.
fn definitions<'a>(
    columns: &'a [String],
    own: &[(&str, &str)],
) -> Vec<(&'a String, Option<String>)> {
    let own_definition = |c: &String| own.iter().find(|(n, _)| *n == c.as_str());
    (columns.iter())
        .map(|c| {
            let d = own_definition(c).map(|(_, d)| d.to_string());
            (c, d.or_else(|| definition(c)))
        })
        .collect()
}

/// The legend block: one `- column: definition` line a column (empty
/// where it has none), folded under "What each column means".
fn details(defined: &[(&String, Option<String>)]) -> String {
    let mut s = String::from("\n<details><summary>What each column means</summary>\n\n");
    for (c, d) in defined {
        let d = d.as_deref().unwrap_or_default();
        s += &format!("- {c}: {d}\n");
    }
    s += "\n</details>\n";
    s
}
