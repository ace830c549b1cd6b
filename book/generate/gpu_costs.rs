//! The choosing chapter's GPU cost table: each lesson's recommended
//! variants on an NVIDIA H100 with its clock held (one variant per process,
//! 300 frames; `book/measured/h100-631f993/clock_held.txt`, whose README
//! gives the commit and the commands), against the half millisecond over
//! the no-shadow frame a shadow technique should cost on such a GPU.
//! A row whose variant is not its lesson's most accurate (the families
//! table's) says why in its own cell; the generator fails on a row with no
//! reason ([`NOT_THE_MOST_ACCURATE`]).

use std::path::Path;

use anyhow::{bail, Context, Result};

use crate::record::Record;
use crate::table::{pct, row};
use crate::volumes_gpu::DIR;

/// What a shadow technique may cost over the no-shadow frame on a GPU like
/// the H100 at 1920×1080.
pub const BUDGET_MS: f64 = 0.5;

/// Why a row measures another variant than its lesson's most accurate:
/// `(lesson, variant, why)`.
const NOT_THE_MOST_ACCURATE: &[(&str, &str, &str)] = &[
    ("04", "depth_1024", "hardware depth: an ordinary depth-only shadow pass, where `linear_2048` runs a fragment shader over six 2048² faces ([lesson 04](lesson_04.md))"),
    ("05", "zpass_compute", "the compute route, which tests the edges on the GPU: the route a GPU favours as the casters grow ([three ways to build the volumes](#three-ways-to-build-the-volumes))"),
    ("06", "zfail_selective", "z-fail only for the casters whose volume may hold the eye, z-pass for the rest: fewer draws than `zfail_cpu` ([lesson 06](lesson_06.md))"),
    ("07", "infinite", "the other cure for the far plane: the far plane at infinity, no depth clamp ([lesson 07](lesson_07.md))"),
    ("08", "bounds_scissor", "the decision table's pick: the bounds cut each light's fill to its range ([lesson 08](lesson_08.md#counting-the-work))"),
    ("09", "k4", "the decision table's pick: the snapped sphere does not shimmer, where `k4_aabb`'s box follows the camera and does ([lesson 09](lesson_09.md#shimmer-along-a-camera-path))"),
];

/// The cell that says why a row's variant is measured: the lesson's most
/// accurate, or as accurate as it, or less accurate, and then why.
fn why(records: &[Record], lesson: &str, variant: &str) -> Result<String> {
    let Some(r) = crate::choosing::default_of(records, &format!("lesson_{lesson}")) else {
        bail!("no default record of lesson {lesson}");
    };
    let Some(best) = crate::choosing::most_accurate(r) else {
        bail!("lesson {lesson}'s record has no variants");
    };
    if best.name == variant {
        return Ok("the most accurate (the families table's)".into());
    }
    let Some(v) = r.variants.iter().find(|v| v.name == variant) else {
        bail!("lesson {lesson} has no variant `{variant}`");
    };
    let Some((_, _, reason)) = NOT_THE_MOST_ACCURATE
        .iter()
        .find(|(l, n, _)| *l == lesson && *n == variant)
    else {
        bail!(
            "gpu_costs: lesson {lesson}'s `{variant}` is not its most accurate (`{}`): give the \
             reason in NOT_THE_MOST_ACCURATE",
            best.name
        );
    };
    let accuracy = if v.error_pct() == best.error_pct() {
        format!(
            "as accurate as `{}` (the families table names the first of equals)",
            best.name
        )
    } else {
        format!(
            "`{}` is more accurate ({} % against {} %)",
            best.name,
            pct(best.error_pct()),
            pct(v.error_pct())
        )
    };
    Ok(format!("{accuracy}; {reason}"))
}

/// One line of `clock_held.txt`.
struct Line {
    lesson: String,
    variant: String,
    total: f64,
    baseline: f64,
    cost: f64,
    clock: String,
}

fn parse(text: &str) -> Result<Vec<Line>> {
    let mut out = Vec::new();
    for (i, l) in text.lines().enumerate().skip(1) {
        let cells: Vec<&str> = l.split('|').map(str::trim).collect();
        if cells.len() != 8 {
            bail!(
                "clock_held.txt line {}: {} cells, not 8",
                i + 1,
                cells.len()
            );
        }
        let (lesson, variant) = cells[0]
            .split_once(' ')
            .with_context(|| format!("clock_held.txt line {}: no variant", i + 1))?;
        let num = |k: usize| -> Result<f64> {
            cells[k]
                .trim_start_matches('+')
                .parse()
                .with_context(|| format!("clock_held.txt line {}: cell {k}", i + 1))
        };
        out.push(Line {
            lesson: lesson.into(),
            variant: variant.into(),
            total: num(1)?,
            baseline: num(3)?,
            cost: num(5)?,
            clock: cells[7].into(),
        });
    }
    Ok(out)
}

/// The table.
pub fn table(root: &Path, records: &[Record]) -> Result<String> {
    let path = root.join(DIR).join("clock_held.txt");
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let mut s = format!(
        "*NVIDIA H100 80GB HBM3, Vulkan · 1920×1080 · the default scenes · commit `631f993` (before the lit passes were compiled per variant, lesson 08's cull and lit-pass scissor) · one variant per process, median of 300 frames, the GPU kept busy: `{DIR}/README.md` · GPU ms from timestamps*\n\n"
    );
    let head = [
        "lesson".to_string(),
        "variant".into(),
        "GPU ms".into(),
        "no shadows, GPU ms".into(),
        "shadows cost".into(),
        format!("within {BUDGET_MS} ms?"),
        "SM clock, MHz (min, max)".into(),
        "why this variant".into(),
    ];
    s += &row(&head);
    s += &row(&vec!["---".to_string(); head.len()]);
    for l in parse(&text)? {
        s += &row(&[
            l.lesson.clone(),
            format!("`{}`", l.variant),
            format!("{:.2}", l.total),
            format!("{:.2}", l.baseline),
            format!("{:+.2} ms", l.cost),
            if l.cost <= BUDGET_MS { "yes" } else { "no" }.into(),
            l.clock.clone(),
            why(records, &l.lesson, &l.variant)?,
        ]);
    }
    let within = format!(
        "yes where the shadows cost at most {BUDGET_MS} ms over the no-shadow frame, what a shadow technique may cost on such a GPU at 1920×1080; else no"
    );
    let own = [
        ("lesson", "the lesson, on its default scene"),
        ("variant", "the lesson's variant, alone in its process: its most accurate (the families table's), or another where the last column says why"),
        ("GPU ms", "the GPU's time for the whole frame, first timestamp to last: median of the process's 300 frames, ms"),
        ("no shadows, GPU ms", "the same for the lesson's no-shadow baseline (the scene drawn without shadows), ms"),
        ("shadows cost", "GPU ms − no shadows, GPU ms: what the shadows add to the frame, ms"),
        (head[5].as_str(), within.as_str()),
        ("SM clock, MHz (min, max)", "the lowest and highest clock of the GPU's streaming multiprocessors seen during the run, MHz: a minimum below the maximum means the clock fell (the times are then less sure)"),
        ("why this variant", "whether the variant is the lesson's most accurate on today's records (the families table's) and, where it is not, why the row measures it"),
    ];
    s += &crate::legend::legend_own(&head, &own);
    Ok(s)
}

/// Writes `choosing/gpu_costs.md`.
pub fn write(root: &Path, generated: &Path, records: &[Record]) -> Result<()> {
    let path = generated.join("choosing/gpu_costs.md");
    std::fs::write(&path, table(root, records)?)
        .with_context(|| format!("cannot write {}", path.display()))
}
