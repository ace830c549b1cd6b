//! What the taps cost: each adapter's rate of shadow-map comparisons, and
//! the floor it puts under every filter of lessons 03 and 10 (chapters 03
//! and 10, `generated/lesson_NN/tap_floor.md`).
//!
//! The rate comes from the same run of the book as the figures it is set
//! against: lesson 03's grids (`pcf_1x1` … `pcf_7x7`) differ only in their
//! comparisons a pixel (1 to 49, neighbouring texels), so a straight line
//! through their lighting passes' medians gives the milliseconds a frame
//! that one more comparison a pixel costs. A variant's floor is its
//! comparisons a pixel times that slope: what its taps alone cost at the
//! best rate the adapter showed, over the no-shadow lit pass. The rest of
//! its measured cost is not taps (the lookup's setup, the blocker search's
//! arithmetic, a wider footprint's cache misses), and no arrangement of the
//! same taps takes the floor away: only fewer taps do.

use crate::legend::legend_own;
use crate::origins::{changed, changes_note, origin};
use crate::plots::{line_fit, Line};
use crate::record::{Record, VariantRecord};
use crate::table::{header, ms, row};

/// The file each chapter includes, under `generated/<lesson>/`.
pub const TABLE: &str = "tap_floor.md";

/// The lessons whose chapters show their floors.
pub const LESSONS: &[&str] = &["lesson_03", "lesson_10"];

/// Lesson 03's grids: the comparisons a pixel, and nothing else, differ.
const LADDER: &[&str] = &["pcf_1x1", "pcf_3x3", "pcf_5x5", "pcf_7x7"];

/// The resolution the choosing chapter holds a technique to half a
/// millisecond at.
const FULL_HD: (u32, u32) = (1920, 1080);
const HALF_MS: f64 = 0.5;

/// The lighting pass's median, when the variant's times are quotable.
fn lighting(t: Option<&crate::record::Timing>) -> Option<f64> {
    let t = t?;
    if !t.stable() {
        return None;
    }
    t.passes.get("lighting").map(|s| s.median)
}

/// The least-squares line of the grids' lighting pass against their
/// comparisons a pixel, from lesson 03's default run; `None` when the run
/// lacks a grid or its times.
pub fn rate(lesson_03: &Record) -> Option<Line> {
    let mut points = Vec::new();
    for name in LADDER {
        let v = lesson_03.variants.iter().find(|v| v.name == *name)?;
        let taps = *v.counters.get("filter_taps_per_pixel")? as f64;
        points.push((taps, lighting(v.timing.as_ref())?));
    }
    line_fit(&points)
}

/// A variant's comparisons a pixel: the mean where the lesson counts each
/// pixel's path (`filter_taps` over `probed_pixels`, lesson 03's adaptive
/// filter), else the blocker search's and the filter's taps. The second
/// value says whether that is the most a pixel takes rather than what
/// pixels took (an adaptive path the lesson does not count).
pub fn taps(v: &VariantRecord) -> Option<(f64, bool)> {
    let c = &v.counters;
    if let (Some(&all), Some(&pixels)) = (c.get("filter_taps"), c.get("probed_pixels")) {
        return (pixels > 0).then(|| (all as f64 / pixels as f64, false));
    }
    let filter = *c.get("filter_taps_per_pixel")?;
    let search = c.get("blocker_search_taps").copied().unwrap_or(0);
    let at_most = v.name.ends_with("_adaptive");
    Some(((filter + search) as f64, at_most))
}

/// One adapter's part: its rate and, per variant, the lighting pass over
/// the no-shadow one against the floor of its taps. `commit`: the set's,
/// whose variants changed since are left out and named.
fn part(lesson: &str, records: &[Record], heading: &str, commit: Option<&str>) -> Option<String> {
    let r03 = records
        .iter()
        .find(|r| r.lesson == "lesson_03" && r.run == "results")?;
    let run = records
        .iter()
        .find(|r| r.lesson == lesson && r.run == "results")?;
    // A grid changed since the set's commit: no rate from it.
    if commit.is_some_and(|c| LADDER.iter().any(|g| changed(c, "lesson_03", g).is_some())) {
        return None;
    }
    let rate = rate(r03)?;
    let base = lighting(run.baseline.as_ref())?;
    let pixels = f64::from(run.width) * f64::from(run.height);
    let full_hd = f64::from(FULL_HD.0) * f64::from(FULL_HD.1) / pixels;
    let mut s = format!(
        "{heading}: each comparison a pixel costs the grids' lighting pass {} µs a frame at {}×{} (a line through `{}` … `{}`, r² {:.3}), {:.1} G comparisons a second.\n\n",
        ms(rate.slope * 1000.0),
        r03.width,
        r03.height,
        LADDER[0],
        LADDER[LADDER.len() - 1],
        rate.r2,
        f64::from(r03.width) * f64::from(r03.height) / rate.slope / 1e6,
    );
    let columns = [
        "variant".to_string(),
        "comparisons a pixel".into(),
        "lighting pass over the no-shadow one (ms)".into(),
        "floor, comparisons × the rate (ms)".into(),
        "floor's share".into(),
        format!("floor at {}×{} (ms)", FULL_HD.0, FULL_HD.1),
    ];
    s += &header(&columns);
    let mut left_out = Vec::new();
    // Whether the floor at 1920×1080 alone is over half a millisecond.
    let (mut over_half, mut under_half) = (Vec::new(), Vec::new());
    for v in &run.variants {
        if commit.is_some_and(|c| changed(c, lesson, &v.name).is_some()) {
            left_out.push(v.name.as_str());
            continue;
        }
        let (Some((n, at_most)), Some(lit)) = (taps(v), lighting(v.timing.as_ref())) else {
            continue;
        };
        let over = lit - base;
        let floor = n * rate.slope;
        let share = if over > 0.0 {
            format!("{:.0} %", 100.0 * floor / over)
        } else {
            "—".into()
        };
        let (n, floor_cell, hd_cell) = if at_most {
            (
                format!("≤ {n:.0}"),
                format!("≤ {}", fine_ms(floor)),
                format!("≤ {}", fine_ms(floor * full_hd)),
            )
        } else {
            (
                if n.fract() == 0.0 {
                    format!("{n:.0}")
                } else {
                    format!("{n:.2}")
                },
                fine_ms(floor),
                fine_ms(floor * full_hd),
            )
        };
        let share = if at_most { "—".into() } else { share };
        let named = format!("`{}`", v.name);
        match (floor * full_hd > HALF_MS, at_most) {
            (true, false) => over_half.push(named),
            (false, _) => under_half.push(named),
            (true, true) => {}
        }
        s += &row(&[
            format!("`{}`", v.name),
            n,
            fine_ms(over),
            floor_cell,
            share,
            hd_cell,
        ]);
    }
    s += &legend_own(
        &columns,
        &[
            ("variant", "the lesson's variant (its `--variant` name)"),
            ("comparisons a pixel", "depth comparisons the lit pass makes at a pixel: the blocker search's taps plus the filter's (`blocker_search_taps` + `filter_taps_per_pixel`), or, where the lesson counts each pixel's path, their mean over the probed pixels (`filter_taps` / `probed_pixels`); ≤: the most a pixel takes, where the lesson does not count the paths"),
            ("lighting pass over the no-shadow one (ms)", "the variant's `lighting` pass, median, less the no-shadow frame's (the passes table): what the shadow lookup adds to the lit pass"),
            ("floor, comparisons × the rate (ms)", "the comparisons a pixel times the rate above: what the comparisons alone cost at the best rate the adapter showed"),
            ("floor's share", "the floor over the measured lookup cost: near 100 %, the variant is its comparisons; over 100 %, its comparison is cheaper than a grid's (a hardware 2×2 compare)"),
            (&columns[5], "the floor times the pixels of 1920×1080 over this run's: the comparisons grow with the pixels (an extrapolation, not a run at that size)"),
        ],
    );
    let list = |names: &[String]| match names {
        [] => "none".to_string(),
        _ => names.join(", "),
    };
    s += &format!(
        "\nTheir comparisons alone at {}×{}, at this rate: over half a millisecond in {}; under it in {}.\n",
        FULL_HD.0,
        FULL_HD.1,
        list(&over_half),
        list(&under_half)
    );
    if let Some(c) = commit {
        s += &changes_note(c, lesson, &left_out, false, None);
    }
    Some(s)
}

/// A time in milliseconds, to the microsecond under 1 ms (a GPU's lit
/// pass at 640×360 is a tenth of one).
fn fine_ms(x: f64) -> String {
    if x.abs() < 1.0 {
        format!("{x:.3}")
    } else {
        ms(x)
    }
}

/// Writes every [`LESSONS`]' [`TABLE`].
pub fn write_all(
    generated: &std::path::Path,
    main: &[Record],
    sets: &[(String, Vec<Record>)],
) -> anyhow::Result<()> {
    use anyhow::Context as _;
    for lesson in LESSONS {
        let path = generated.join(lesson).join(TABLE);
        std::fs::write(&path, table(lesson, main, sets))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

/// `lesson`'s `tap_floor.md`: lavapipe's records, then each other set
/// that holds lesson 03's and this lesson's default runs.
pub fn table(lesson: &str, main: &[Record], sets: &[(String, Vec<Record>)]) -> String {
    let mut parts = Vec::new();
    let name_of = |records: &[Record]| {
        records
            .iter()
            .find(|r| r.lesson == lesson)
            .map_or_else(|| "?".to_string(), |r| r.adapter_label())
    };
    if let Some(p) = part(lesson, main, &format!("**{}**", name_of(main)), None) {
        parts.push(p);
    }
    for (set, records) in sets {
        let o = origin(set);
        let heading = match o {
            Some(o) => format!(
                "**{}, the code of commit `{}`** (measured {})",
                name_of(records),
                o.commit,
                o.measured
            ),
            None => format!("**{}**", name_of(records)),
        };
        if let Some(p) = part(lesson, records, &heading, o.map(|o| o.commit)) {
            parts.push(p);
        }
    }
    let mut s = String::from(
        "*The lighting pass's medians of each adapter's default run (640×360), less the no-shadow lit pass's; the floor is the variant's comparisons a pixel times that adapter's rate, and at 1920×1080 it is scaled by the pixels (the comparisons grow with the pixels; not a run at that size)*\n\n",
    );
    s += &parts.join("\n");
    if !s.ends_with('\n') {
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_line_is_fitted_exactly() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/book/src/generated/lesson_03/results.json"
        ))
        .expect("lesson 03's record");
        let mut r: Record = serde_json::from_str(&text).expect("a record");
        // Lighting = 2 ms + 0.5 ms a comparison, exactly.
        for v in &mut r.variants {
            if let (Some(t), Some(&n)) = (&mut v.timing, v.counters.get("filter_taps_per_pixel")) {
                t.passes.get_mut("lighting").expect("lighting").median = 2.0 + 0.5 * n as f64;
            }
        }
        let rate = rate(&r).expect("a rate");
        assert!((rate.slope - 0.5).abs() < 1e-12, "{rate:?}");
        assert!((rate.intercept - 2.0).abs() < 1e-12, "{rate:?}");
        assert!((rate.r2 - 1.0).abs() < 1e-12, "{rate:?}");
    }
}
