//! The GPU cost table (`choosing/gpu_costs.md`): one row a lesson's
//! recommended variant, its costs and verdict, and why the row measures it
//! where it is not the lesson's most accurate ([`NOT_THE_MOST_ACCURATE`]).

use anyhow::{bail, Result};

use super::costs::{rows, Cost, FullHd, Verdict};
use super::{BUDGET_MS, ORIGIN};
use crate::origins::changes_note;
use crate::record::Record;
use crate::table::{header, pct, row, stat};

/// Why a row measures another variant than its lesson's most accurate:
/// `(lesson, variant, why)`.
const NOT_THE_MOST_ACCURATE: &[(&str, &str, &str)] = &[
    ("04", "depth_1024", "hardware depth: an ordinary depth-only shadow pass, where `linear_2048` runs a fragment shader over six 2048² faces ([lesson 04](lesson_04.md))"),
    ("05", "zpass_compute", "the compute route, which tests the edges on the GPU: the route a GPU favours as the casters grow ([three ways to build the volumes](#three-ways-to-build-the-volumes))"),
    ("06", "zfail_selective", "z-fail only for the casters whose volume may hold the eye, z-pass for the rest: fewer draws than `zfail_cpu` ([lesson 06](lesson_06.md))"),
    ("07", "infinite", "the other cure for the far plane: the far plane at infinity, no depth clamp ([lesson 07](lesson_07.md))"),
    ("08", "bounds_scissor", "the decision table's pick: the bounds cut each light's fill to its range ([lesson 08](lesson_08.md#counting-the-work))"),
    ("08", "cull_bounds_scissor", "`bounds_scissor` with the cull: a caster whose bounding sphere misses the light's range casts no volume ([lesson 08](lesson_08.md#counting-the-work))"),
    ("09", "k4", "the decision table's pick: the snapped sphere does not shimmer, where `k4_aabb`'s box follows the camera and does ([lesson 09](lesson_09.md#shimmer-along-a-camera-path))"),
    ("10", "pcss", "the GPU sets ran before `pcss_min_max` (issue 50), PCSS itself on a map without the ground, its chain answering where the taps would agree ([lesson 10](lesson_10.md))"),
    ("10", "hard_pcf", "lesson 03's rotated 16-tap Poisson disk, no light size: the hard shadow's edge, filtered ([lesson 10](lesson_10.md))"),
    ("10", "pcf_wide_16", "PCSS's 16 filter taps on a fixed 8-texel disk, one width everywhere: what PCSS's blocker search sizes per pixel ([lesson 10](lesson_10.md))"),
    ("10", "pcf_wide_32", "32 taps on the same disk, as many as PCSS's search and filter together ([lesson 10](lesson_10.md))"),
    ("10", "vsm", "a variance map blurred 9×9 texels: one filtered lookup a pixel ([lesson 10](lesson_10.md))"),
    ("10", "vsm_bleed_cut", "`vsm` with the cut against light bleeding ([lesson 10](lesson_10.md))"),
    ("10", "evsm", "an exponential variance map (EVSM4): `vsm`'s lookup on warped depths, the lower bound of two warps ([lesson 10](lesson_10.md))"),
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

/// The table's caption: the GPU, the runs, the protocol, and what the
/// GPU is (`note`, [`crate::gpus::set_note`]).
fn caption(full: &FullHd, note: Option<&str>) -> String {
    let Some(r) = full.reports.first() else {
        return String::new();
    };
    let warm = r.timing_protocol.as_ref().map_or(String::new(), |p| {
        format!(
            " (≥ {:.0} ms, until its frame times settle)",
            p.warm_up_min_ms
        )
    });
    format!(
        "*{}, {} · {}×{} · the default scenes · the code of commit `{}` (measured {}) · each lesson alone, its variants warmed up{warm} and timed, {} frames each, between blocks of the no-shadow frame · GPU ms from timestamps: median [spread: the frames' interquartile range]{}*\n\n",
        r.adapter.name,
        r.adapter.backend,
        r.width,
        r.height,
        ORIGIN.commit,
        ORIGIN.measured,
        r.frames,
        note.map_or(String::new(), |n| format!(" · what this GPU is: {n}"))
    )
}

fn verdict_cell(c: Option<Cost>) -> String {
    match c.map(|c| c.verdict()) {
        Some(Verdict::Within) => "yes".into(),
        Some(Verdict::Over) => "no".into(),
        Some(Verdict::OnTheLine) => "on the line".into(),
        None => "—".into(),
    }
}

/// The table.
pub fn table(full: &FullHd, records: &[Record], note: Option<&str>) -> Result<String> {
    let mut s = caption(full, note);
    let head = [
        "lesson".to_string(),
        "variant".into(),
        "GPU ms".into(),
        "no shadows, GPU ms".into(),
        "shadows cost, GPU".into(),
        format!("within {BUDGET_MS} ms?"),
        "shadows cost, frame".into(),
        "CPU ms".into(),
        "why this variant".into(),
    ];
    s += &header(&head);
    let mut notes = String::new();
    for r in &full.reports {
        let (rows, left_out) = rows(r);
        for x in &rows {
            let unstable = || "unstable".to_string();
            s += &row(&[
                format!("[{}]({}.md)", x.lesson, r.lesson),
                format!("`{}`", x.variant.name),
                x.gpu.as_ref().map_or_else(unstable, stat),
                x.base_gpu.as_ref().map_or_else(unstable, stat),
                x.gpu_cost.map_or_else(unstable, |c| c.cell()),
                verdict_cell(x.gpu_cost),
                x.frame_cost.map_or_else(unstable, |c| c.cell()),
                x.cpu.as_ref().map_or("—".into(), stat),
                why(records, &x.lesson, &x.variant.name)?,
            ]);
        }
        let whose = format!("lesson {}'s", &r.lesson[7..]);
        // Times only: what the errors are measured against does not matter.
        notes += &changes_note(ORIGIN.commit, &r.lesson, &left_out, false, Some(&whose));
    }
    let within = format!(
        "`yes` where the shadows' GPU cost is at most {BUDGET_MS} ms even at the high end of its spread (the variant's third quartile less the no-shadow frame's first), what a shadow technique may cost on such a GPU at 1920×1080; `no` where it is over {BUDGET_MS} ms even at the low end; `on the line` where {BUDGET_MS} ms lies within its spread"
    );
    let own = [
        ("lesson", "the lesson, on its default scene, linked to its chapter"),
        ("variant", "the lesson's variant: its most accurate (the families table's), or another where the last column says why"),
        ("GPU ms", "the GPU's time for the whole frame, first timestamp to last: median [spread], ms"),
        ("no shadows, GPU ms", "the same for the lesson's no-shadow baseline (the scene drawn without shadows), timed in the blocks between the variants: median [spread], ms"),
        ("shadows cost, GPU", "GPU ms − no shadows, GPU ms (medians): what the shadows add to the GPU's frame; no measurable difference where the two spreads overlap"),
        (head[5].as_str(), within.as_str()),
        ("shadows cost, frame", "the same for the frame's wall clock, from the start of recording to the GPU's completion, which counts the CPU's work (a silhouette found on the CPU, culling, recording): frame ms − the no-shadow frame's (medians); no measurable difference where the two spreads overlap"),
        ("CPU ms", "the CPU's time to record and submit the frame, waits for the GPU left out (`cpu_total`): median [spread], ms"),
        ("why this variant", "whether the variant is the lesson's most accurate on today's records (the families table's) and, where it is not, why the row measures it"),
    ];
    s += &crate::legend::legend_own(&head, &own);
    s += &notes;
    Ok(s)
}
