//! What each column of a sweep's tables means: the legends written under
//! its points table and its slopes table.

use super::sweep::{distinct_variants, Sweep};

/// The size axis's column: what the size is, and its symbol in the
/// expected orders.
fn axis_definition(sweep: &Sweep) -> (String, &'static str) {
    match sweep.axis.as_str() {
        "triangles" => (
            "the caster's triangles n, the size the row ran at: a torus of v minor × 2v major segments, two triangles a quad (4·v²), on a floor".into(),
            "n",
        ),
        "shadow map" => (
            "the shadow map's size in texels, s² for a side of s texels: lesson 01's variant `res_<s>`, all sizes in one process".into(),
            "s",
        ),
        "screen" => (
            "the frame's size, width×height in pixels (P = width · height): the default scene rendered at each size".into(),
            "P",
        ),
        "lights" => (
            format!(
                "the number of lights N in the scene, on a circle above lesson 01's floor and casters ({}: see the caption)",
                if sweep.lesson == "lesson_02" {
                    "spot lights, one 1024² shadow map each"
                } else {
                    "point lights"
                }
            ),
            "N",
        ),
        _ => ("the size of the problem the row ran at".into(), "x"),
    }
}

/// The legend of a sweep's points table.
pub(super) fn points_legend(
    sweep: &Sweep,
    head: &[String],
    passes: &[String],
    counters: &[String],
) -> String {
    let frames = sweep.frames;
    let spread = format!("median [interquartile range] of the point's {frames} timed frames, ms");
    let gpu = if sweep.timing_source == "cpu_wall" {
        "the frame's passes, each submitted and timed on its own by the CPU's wall clock, summed"
    } else {
        "the GPU's time for the whole frame, from its first pass's start timestamp to its last pass's end"
    };
    let mut own: Vec<(String, String)> = vec![
        (sweep.axis.clone(), axis_definition(sweep).0),
        (
            "variant".into(),
            format!("{}'s variant the row ran (its `--variant` name)", sweep.lesson.replace('_', " ")),
        ),
        (
            "frame ms".into(),
            format!("the frame's wall-clock cost, from the start of recording to the GPU's completion: {spread}"),
        ),
        ("GPU ms".into(), format!("{gpu}: {spread}")),
        (
            "misclassified %".into(),
            "the receiver pixels classified differently from the exact reference (lit where V ≥ ½), in % of the receiver pixels of every light".into(),
        ),
    ];
    for p in passes {
        let d = crate::legend::PASSES
            .iter()
            .find(|(n, _)| *n == p.as_str())
            .map_or("the pass of that name", |(_, d)| d);
        own.push((
            format!("`{p}` ms"),
            format!("{d}: {spread}; — where the variant has no such pass"),
        ));
    }
    for c in counters {
        let Some(d) = common::measure::counters::Counter::named(c).map(|c| c.legend) else {
            continue;
        };
        own.push((
            format!("`{c}`"),
            format!(
                "{}; in one frame; — where the variant does not report it",
                d.replace(
                    "of those, ",
                    "of the volume fragments that reach the stencil, "
                )
            ),
        ));
    }
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    crate::legend::legend_own(head, &own)
}

/// The legend of a sweep's slopes table.
pub(super) fn slopes_legend(sweep: &Sweep, head: &[String], top: usize) -> String {
    let axis = &sweep.axis;
    let x = axis_definition(sweep).1;
    let multi = distinct_variants(sweep).len() > 1;
    let curve = format!(
        "what is fitted against the {axis} {x}: {}a time's median (GPU ms: the GPU's time for the frame; `` `pass` ms ``: that pass's time), or a counter (`` `name` ``) in one frame",
        if multi {
            "the variant, where the curve is one variant's (none named: every variant's points together); "
        } else {
            ""
        }
    );
    let own = [
        ("curve", curve),
        (
            "expected order",
            format!("how the curve should grow with {x}, from what the algorithm does (O(1): not at all)"),
        ),
        (
            "expected slope",
            "the log-log slope that order means once fixed costs are small: O(1) → 0, O(√n) → 0.5, O(n) → 1, O(s²) → 2".into(),
        ),
        (
            "measured slope (all points)",
            format!("the least-squares slope of log(value) against log({x}) over every point of the curve; — where it is not defined (a value of 0, or a single point)"),
        ),
        (
            head[4].as_str(),
            format!("the same over the curve's largest {top} sizes, where fixed costs weigh least"),
        ),
    ];
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (*a, b.as_str())).collect();
    crate::legend::legend_own(head, &own)
}

/// The legend of a sweep's stops table.
pub(super) fn stops_legend(sweep: &Sweep, head: &[String]) -> String {
    let axis = &sweep.axis;
    let own = [
        (
            "variant".to_string(),
            format!("{}'s variant (its `--variant` name)", sweep.lesson.replace('_', " ")),
        ),
        (
            head[1].clone(),
            format!("the largest size (the {axis} column's) at which the variant ran (— where it ran at none)"),
        ),
        (
            "left out at".into(),
            format!("the smallest size (the {axis} column's) at which the lesson refused to run the variant (— where it ran every size)"),
        ),
        (
            "why".into(),
            "the lesson's own line: the buffer the variant would need there, its size, and the adapter's limit it passes".into(),
        ),
    ];
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    crate::legend::legend_own(head, &own)
}
