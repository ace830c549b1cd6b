//! The page of a lesson's floors (`generated/lesson_NN/tap_floor.md`, on
//! its record page): for every set the book holds, the rate and the model
//! ([`crate::taps`], [`crate::pass_model`]), what its GPU is
//! ([`crate::gpus`]), one table of every variant's lit pass against its
//! floor and its map passes against the model, and under the tables the
//! variants over [`crate::taps::OVER`] with their reasons ([`crate::why`]).

use crate::gpus;
use crate::legend::legend_own;
use crate::origins::{changes_note, origin};
use crate::over_floor;
use crate::pass_model::{self, Alone, PassModel};
use crate::record::Record;
use crate::table::{header, ms, row};
use crate::taps::{adapters, overs, rows, times, Adapter, Over, Rate, LADDER, LESSONS};

/// The file each lesson's record page includes, under `generated/<lesson>/`.
pub const TABLE: &str = "tap_floor.md";

/// The resolution the choosing chapter holds a technique to half a
/// millisecond at.
const FULL_HD: (u32, u32) = (1920, 1080);
const HALF_MS: f64 = 0.5;

/// A time in milliseconds, to the microsecond under 1 ms (a GPU's lit
/// pass at 640×360 is a tenth of one).
pub fn fine_ms(x: f64) -> String {
    let s = if x.abs() < 1.0 {
        format!("{x:.3}")
    } else {
        ms(x)
    };
    // The book's minus sign.
    s.replacen('-', "−", 1)
}

/// One set's part of a lesson's table; `None` when the set has no default
/// run of the lesson.
fn part(lesson: &str, a: &Adapter, sets: &[(String, Vec<Record>)]) -> Option<String> {
    let (rate, model) = (a.rate(), a.model());
    let (rows, left_out) = rows(lesson, a, rate.as_ref(), model.as_ref())?;
    let run = a
        .records
        .iter()
        .find(|r| r.lesson == lesson && r.run == "results")?;
    let label = run.adapter_label();
    let mut s = match a.set.and_then(origin) {
        Some(o) => format!(
            "**{label}, the code of commit `{}`** (measured {})",
            o.commit, o.measured
        ),
        None => format!("**{label}**"),
    };
    s += &lead(a, rate.as_ref(), model.as_ref());
    let pixels = f64::from(run.width) * f64::from(run.height);
    let full_hd = f64::from(FULL_HD.0) * f64::from(FULL_HD.1) / pixels;
    let note = match a.set {
        Some(set) => gpus::set_note(set, sets),
        None => Some("lavapipe: Mesa's software rasteriser, the lessons' GPU work run on this machine's CPU cores".into()),
    };
    s += &format!(
        "*{label} · {}×{}, the default scene · the lighting pass's median less the no-shadow lit pass's, against the comparisons × the rate; the map passes' median against the model{}*\n\n",
        run.width,
        run.height,
        note.map_or(String::new(), |n| format!(" · {n}"))
    );
    let columns = [
        "variant".to_string(),
        "comparisons a pixel".into(),
        "lighting pass over the no-shadow one (ms)".into(),
        "floor, comparisons × the rate (ms)".into(),
        "measured / floor".into(),
        format!("floor at {}×{} (ms)", FULL_HD.0, FULL_HD.1),
        "map passes (ms)".into(),
        "model (ms)".into(),
        "measured / model".into(),
    ];
    s += &header(&columns);
    // Whether the floor at 1920×1080 alone is over half a millisecond.
    let (mut over_half, mut under_half) = (Vec::new(), Vec::new());
    let dash = || "—".to_string();
    for r in &rows {
        let named = format!("`{}`", r.variant);
        let at_most = r.at_most();
        let le = if at_most { "≤ " } else { "" };
        if let Some(f) = r.floor {
            match (f * full_hd > HALF_MS, at_most) {
                (true, false) => over_half.push(named.clone()),
                (false, _) => under_half.push(named.clone()),
                (true, true) => {}
            }
        }
        let n = r.comparisons.map_or_else(dash, |(n, _)| {
            if n.fract() == 0.0 {
                format!("{le}{n:.0}")
            } else {
                format!("{le}{n:.2}")
            }
        });
        let ratio = r.lit_ratio().map_or_else(dash, |x| {
            format!("{}{}", if at_most { "≥ " } else { "" }, times(x))
        });
        s += &row(&[
            named,
            n,
            r.lit_over().map_or_else(dash, fine_ms),
            r.floor.map_or_else(dash, |f| format!("{le}{}", fine_ms(f))),
            ratio,
            r.floor
                .map_or_else(dash, |f| format!("{le}{}", fine_ms(f * full_hd))),
            r.map.map_or_else(dash, fine_ms),
            r.model.map_or_else(dash, fine_ms),
            r.map_ratio().map_or_else(dash, times),
        ]);
    }
    s += &legend_own(&columns, &legend());
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
    if let Some(c) = a.commit() {
        let names: Vec<&str> = left_out.iter().map(String::as_str).collect();
        s += &changes_note(c, lesson, &names, false, None);
    }
    Some(s)
}

/// The part's lead after its bold adapter: the rate and the model.
fn lead(a: &Adapter, rate: Option<&Rate>, model: Option<&PassModel>) -> String {
    let mut s = match rate {
        Some(r) => format!(
            ": each comparison a pixel costs lesson 03's grids' lighting pass {} µs a frame at {}×{} (a line through `{}` … `{}`, r² {:.3}), {:.1} G comparisons a second; where the line meets no comparison it is {} ms over the no-shadow lit pass, the grids' lookup before its first comparison, which no floor counts",
            ms(r.line.slope * 1000.0),
            r.width,
            r.height,
            LADDER[0],
            LADDER[LADDER.len() - 1],
            r.line.r2,
            r.per_second_g(),
            fine_ms(r.setup()),
        ),
        None => ": no rate (the set's lesson 03 grids are missing, unquotable or changed since its commit), so no floor".into(),
    };
    s += &match model {
        Some(m) => {
            let alone = match m.alone {
                None => "",
                Some(Alone::Together) => "; the texels alone, since over these runs the fragments move with the texels and no cost per fragment is told apart",
                Some(Alone::Negative) => "; the texels alone, since with the fragments too the fit gave a negative cost per fragment",
            };
            format!(
                ". The model of its map passes: {}, least squares on the relative error over the {} variants of {} that count their map's texels and fragments (measured / model {} to {} over them){alone}.\n\n",
                m.formula(),
                m.points,
                {
                    let ls = pass_model::point_lessons(a.records, a.commit());
                    let word = if ls.contains(',') { "lessons" } else { "lesson" };
                    format!("{word} {ls}")
                },
                times(m.spread.0),
                times(m.spread.1),
            )
        }
        None => ". No model of its map passes: no variant of the set counts its map's texels and fragments.\n\n".into(),
    };
    s
}

/// The columns' meanings.
fn legend() -> Vec<(&'static str, &'static str)> {
    vec![
        ("variant", "the lesson's variant (its `--variant` name)"),
        ("comparisons a pixel", "depth comparisons the lit pass makes at a pixel: the blocker search's taps plus the filter's (`blocker_search_taps` + `filter_taps_per_pixel`), or, where the lesson counts each pixel's path, their mean over the probed pixels (`filter_taps` / `probed_pixels`); ≤: the most a pixel takes, where the lesson does not count the paths; a variance map's one filtered read of its moments counts as one"),
        ("lighting pass over the no-shadow one (ms)", "the variant's `lighting` pass, median, less the no-shadow frame's (the passes table): what the shadow lookup adds to the lit pass"),
        ("floor, comparisons × the rate (ms)", "the comparisons a pixel times the rate above: what the comparisons alone cost at the best rate the adapter showed"),
        ("measured / floor", "the lit pass over the no-shadow one, divided by the floor: near 1×, the variant is its comparisons; under 1×, its comparison is cheaper than a grid's (a hardware 2×2 compare); ≥: a lower bound, where the floor counts the most a pixel takes; — where the lit pass is not measurably slower than the no-shadow one (their spreads overlap)"),
        ("floor at 1920×1080 (ms)", "the floor times the pixels of 1920×1080 over this run's: the comparisons grow with the pixels (an extrapolation, not a run at that size)"),
        ("map passes (ms)", "the passes that build the variant's map, medians: its `shadow` pass, plus a variance map's `moments` and `blur` passes, or the min/max chain's `min_max`"),
        ("model (ms)", "what the set's model above gives for the variant's map: its texels (the map's size² × its cascades or cube faces drawn) and, where the model has a cost per fragment, its `shadow_fragments`; — where the variant does not count what the model needs"),
        ("measured / model", "the map passes over the model: near 1×, the map costs what its texels and fragments cost on this adapter; over it, something else (another pass, a fragment shader the depth-only pass does not have)"),
    ]
}

/// `lesson`'s `tap_floor.md`: each set's part (lavapipe's first), the
/// sets without a run of the lesson, and the variants over [`crate::taps::OVER`] with
/// their reasons.
pub fn table(lesson: &str, main: &[Record], sets: &[(String, Vec<Record>)]) -> String {
    let all = adapters(main, sets);
    let mut parts = Vec::new();
    let mut without = Vec::new();
    for a in &all {
        match part(lesson, a, sets) {
            Some(p) => parts.push(p),
            None => without.push(a.records.first().map_or("?".into(), |r| r.adapter_label())),
        }
    }
    let mut s = parts.join("\n");
    if !without.is_empty() {
        s += &format!(
            "\nNo run of this lesson in the sets of {}.\n",
            without.join("; ")
        );
    }
    s += &over_floor::list(&overs(lesson, &all));
    s
}

/// Writes every [`LESSONS`]' [`TABLE`]; fails when a variant over [`crate::taps::OVER`]
/// has no reason, or a reason explains no listed variant ([`over_floor::check`]).
pub fn write_all(
    generated: &std::path::Path,
    main: &[Record],
    sets: &[(String, Vec<Record>)],
) -> anyhow::Result<()> {
    use anyhow::Context as _;
    let all = adapters(main, sets);
    let overs: Vec<Over> = LESSONS.iter().flat_map(|l| overs(l, &all)).collect();
    over_floor::check(&overs)?;
    for lesson in LESSONS {
        let path = generated.join(lesson).join(TABLE);
        std::fs::write(&path, table(lesson, main, sets))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_lesson_with_lookups_has_its_table_and_every_set_its_part() {
        let (main, sets) = crate::taps::tests::committed();
        for lesson in LESSONS {
            let t = table(lesson, &main, &sets);
            assert!(t.contains("**lavapipe"), "{lesson}: no lavapipe part");
            for (name, records) in &sets {
                let holds = records
                    .iter()
                    .any(|r| r.lesson == *lesson && r.run == "results");
                let label = records[0].adapter_label();
                assert_eq!(
                    t.contains(&format!("**{label}, the code of commit")),
                    holds,
                    "{lesson}: {name}'s part"
                );
            }
        }
    }
}
