//! What a shadow-map lookup and a shadow map cost, against what their work
//! alone should cost on the same adapter: the floor under each variant's
//! lit pass and the model of its map passes, for every lesson that looks
//! up a shadow map (01, 02, 03, 04, 09 and 10; the volume lessons 05 to 08
//! have no lookups) and every set the book holds
//! (`generated/lesson_NN/tap_floor.md`, on each lesson's record page).
//!
//! **The floor.** The rate comes from the same set's run of lesson 03:
//! its grids (`pcf_1x1` … `pcf_7x7`) differ only in their comparisons a
//! pixel (1 to 49, neighbouring texels), so a straight line through their
//! lighting passes' medians gives the milliseconds a frame that one more
//! comparison a pixel costs. A variant's floor is its comparisons a pixel
//! times that slope: what its taps alone cost at the best rate the adapter
//! showed, over the no-shadow lit pass. The rest of its measured cost is
//! not taps (the lookup's setup, which the line's intercept shows, the
//! blocker search's arithmetic, a wider footprint's cache misses), and no
//! arrangement of the same taps takes the floor away: only fewer taps do.
//!
//! **The map passes** are set against [`crate::pass_model`]'s model of the
//! set, fitted on its own runs.
//!
//! A variant more than [`OVER`] times its floor or its model is listed
//! under the tables with the reason [`crate::why`] gives for it; the
//! generator fails on one with no reason, and on a reason that no longer
//! explains a listed variant. This file measures; [`crate::tap_floor`]
//! writes the page.

use crate::origins::{changed, gpu, origin};
use crate::pass_model::{self, PassModel};
use crate::plots::{line_fit, Line};
use crate::record::{Record, Stat, Timing, VariantRecord};
use crate::why::{On, Pass};
use common::measure::counters::{
    BLOCKER_SEARCH_TAPS, FILTER_TAPS, FILTER_TAPS_PER_PIXEL, PROBED_PIXELS, SHADOW_FRAGMENTS,
};

/// The lessons that look up a shadow map.
pub const LESSONS: &[&str] = &[
    "lesson_01",
    "lesson_02",
    "lesson_03",
    "lesson_04",
    "lesson_09",
    "lesson_10",
];

/// Lesson 03's grids: the comparisons a pixel, and nothing else, differ.
pub const LADDER: &[&str] = &["pcf_1x1", "pcf_3x3", "pcf_5x5", "pcf_7x7"];

/// A variant over this many times its floor or its model must say why.
pub const OVER: f64 = 1.5;

/// The lighting pass's median and spread, when the times are quotable.
fn lighting(t: Option<&Timing>) -> Option<Stat> {
    let t = t.filter(|t| t.stable())?;
    t.passes.get("lighting").copied()
}

/// The least-squares line of the grids' lighting pass against their
/// comparisons a pixel, from lesson 03's default run; `None` when the run
/// lacks a grid or its times.
pub fn rate(lesson_03: &Record) -> Option<Line> {
    let mut points = Vec::new();
    for name in LADDER {
        let v = lesson_03.variants.iter().find(|v| v.name == *name)?;
        let taps = *v.counters.get(FILTER_TAPS_PER_PIXEL.name)? as f64;
        points.push((taps, lighting(v.timing.as_ref())?.median));
    }
    line_fit(&points)
}

/// An adapter's rate of comparisons, from its run of lesson 03.
#[derive(Debug, Clone, Copy)]
pub struct Rate {
    /// Lighting ms against comparisons a pixel.
    pub line: Line,
    /// Lesson 03's no-shadow lit pass, median ms.
    pub base: f64,
    pub width: u32,
    pub height: u32,
}

impl Rate {
    /// The rate of a set's lesson 03 default run, unless a grid changed
    /// since the set's `commit`.
    pub fn of(records: &[Record], commit: Option<&str>) -> Option<Rate> {
        if commit.is_some_and(|c| LADDER.iter().any(|g| changed(c, "lesson_03", g).is_some())) {
            return None;
        }
        let r03 = records
            .iter()
            .find(|r| r.lesson == "lesson_03" && r.run == "results")?;
        Some(Rate {
            line: rate(r03)?,
            base: lighting(r03.baseline.as_ref())?.median,
            width: r03.width,
            height: r03.height,
        })
    }

    /// Comparisons a second, in billions: every pixel of the frame one
    /// more comparison, over the milliseconds that costs.
    pub fn per_second_g(&self) -> f64 {
        f64::from(self.width) * f64::from(self.height) / self.line.slope / 1e6
    }

    /// Where the line meets no comparison, over the no-shadow lit pass:
    /// the grids' lookup before its first comparison.
    pub fn setup(&self) -> f64 {
        self.line.intercept - self.base
    }
}

/// A variant's comparisons a pixel: the mean where the lesson counts each
/// pixel's path (`filter_taps` over `probed_pixels`, lesson 03's adaptive
/// filter), else the blocker search's and the filter's taps. The second
/// value says whether that is the most a pixel takes rather than what
/// pixels took (an adaptive path the lesson does not count).
pub fn taps(v: &VariantRecord) -> Option<(f64, bool)> {
    let c = &v.counters;
    if let (Some(&all), Some(&pixels)) = (c.get(FILTER_TAPS.name), c.get(PROBED_PIXELS.name)) {
        return (pixels > 0).then(|| (all as f64 / pixels as f64, false));
    }
    let filter = *c.get(FILTER_TAPS_PER_PIXEL.name)?;
    let search = c.get(BLOCKER_SEARCH_TAPS.name).copied().unwrap_or(0);
    let at_most = v.name.ends_with("_adaptive");
    Some(((filter + search) as f64, at_most))
}

/// One variant of one set: its lit pass against its floor, its map passes
/// against the model.
#[derive(Debug, Clone)]
pub struct Row {
    pub variant: String,
    /// Comparisons a pixel, and whether that is the most a pixel takes.
    pub comparisons: Option<(f64, bool)>,
    pub lit: Option<Stat>,
    /// The run's no-shadow lit pass.
    pub base: Option<Stat>,
    /// Comparisons × the rate, ms.
    pub floor: Option<f64>,
    /// The map passes' median, ms.
    pub map: Option<f64>,
    /// The model's time for the variant's map, ms.
    pub model: Option<f64>,
}

impl Row {
    /// The lit pass over the no-shadow one, ms (medians).
    pub fn lit_over(&self) -> Option<f64> {
        Some(self.lit?.median - self.base?.median)
    }

    /// Measured over floor, when the lit pass is measurably slower than
    /// the no-shadow one (their spreads do not overlap); a lower bound
    /// where the comparisons are the most a pixel takes.
    pub fn lit_ratio(&self) -> Option<f64> {
        let (lit, base, floor) = (self.lit?, self.base?, self.floor?);
        (lit.differs_from(&base) && lit.median > base.median && floor > 0.0)
            .then(|| (lit.median - base.median) / floor)
    }

    /// Measured over model, for the map passes.
    pub fn map_ratio(&self) -> Option<f64> {
        let model = self.model.filter(|m| *m > 0.0)?;
        Some(self.map? / model)
    }

    /// Whether the comparisons are the most a pixel takes.
    pub fn at_most(&self) -> bool {
        self.comparisons.is_some_and(|c| c.1)
    }
}

/// One set as the tables show it: the book's own (`set: None`) or another.
pub struct Adapter<'a> {
    /// The set's folder name, `None` for the book's own.
    pub set: Option<&'a str>,
    pub records: &'a [Record],
}

impl Adapter<'_> {
    /// The commit the set ran, when it is another adapter's.
    pub fn commit(&self) -> Option<&'static str> {
        self.set.and_then(origin).map(|o| o.commit)
    }

    /// Which reasons apply to it.
    pub fn on(&self) -> On {
        if self.set.is_none() {
            On::Lavapipe
        } else {
            On::Gpu
        }
    }

    /// Its short name in the list of reasons: `lavapipe`, `the H100`.
    pub fn short(&self) -> String {
        match self.set.and_then(gpu) {
            None if self.set.is_none() => "lavapipe".into(),
            Some(g) => format!("the {g:?}"),
            None => self
                .records
                .first()
                .map_or("?".into(), |r| r.adapter_label()),
        }
    }

    pub fn rate(&self) -> Option<Rate> {
        Rate::of(self.records, self.commit())
    }

    pub fn model(&self) -> Option<PassModel> {
        pass_model::fit(&pass_model::points(self.records, self.commit()))
    }
}

/// A lesson's rows on one set, less the variants changed since the set's
/// commit (returned by name); `None` when the set has no default run of
/// the lesson.
pub fn rows(
    lesson: &str,
    a: &Adapter,
    rate: Option<&Rate>,
    model: Option<&PassModel>,
) -> Option<(Vec<Row>, Vec<String>)> {
    let run = a
        .records
        .iter()
        .find(|r| r.lesson == lesson && r.run == "results")?;
    let base = lighting(run.baseline.as_ref());
    let mut rows = Vec::new();
    let mut left_out = Vec::new();
    for v in &run.variants {
        if a.commit()
            .is_some_and(|c| changed(c, lesson, &v.name).is_some())
        {
            left_out.push(v.name.clone());
            continue;
        }
        let comparisons = taps(v);
        let texels = pass_model::map_texels(lesson, v);
        let fragments = v.counters.get(SHADOW_FRAGMENTS.name).map(|&f| f as f64);
        rows.push(Row {
            variant: v.name.clone(),
            comparisons,
            lit: lighting(v.timing.as_ref()),
            base,
            floor: comparisons.zip(rate).map(|((n, _), r)| n * r.line.slope),
            map: pass_model::map_ms(v.timing.as_ref()),
            model: texels.zip(model).and_then(|(t, m)| m.predict(t, fragments)),
        });
    }
    Some((rows, left_out))
}

/// A variant over [`OVER`] times its floor or its model on one set.
#[derive(Debug, Clone)]
pub struct Over {
    pub lesson: String,
    pub variant: String,
    pub pass: Pass,
    pub on: On,
    /// The set's short name ([`Adapter::short`]).
    pub adapter: String,
    pub ratio: f64,
    /// The ratio is a lower bound (the comparisons are the most a pixel takes).
    pub at_least: bool,
}

/// Every variant of `lesson` over [`OVER`], set by set.
pub fn overs(lesson: &str, adapters: &[Adapter]) -> Vec<Over> {
    let mut out = Vec::new();
    for a in adapters {
        let (rate, model) = (a.rate(), a.model());
        let Some((rows, _)) = rows(lesson, a, rate.as_ref(), model.as_ref()) else {
            continue;
        };
        for r in rows {
            let passes = [
                (Pass::Lighting, r.lit_ratio(), r.at_most()),
                (Pass::Map, r.map_ratio(), false),
            ];
            for (pass, ratio, at_least) in passes {
                if let Some(ratio) = ratio.filter(|x| *x > OVER) {
                    out.push(Over {
                        lesson: lesson.into(),
                        variant: r.variant.clone(),
                        pass,
                        on: a.on(),
                        adapter: a.short(),
                        ratio,
                        at_least,
                    });
                }
            }
        }
    }
    out
}

/// A ratio as the tables print it: `5.45×`, `52×` (two places under 10,
/// so that one just under [`OVER`] does not print as it).
pub fn times(x: f64) -> String {
    if x >= 9.995 {
        format!("{x:.0}×")
    } else {
        format!("{x:.2}×")
    }
}

/// [`OVER`] as the text writes it, `1.5×`.
pub fn over() -> String {
    format!("{OVER}×")
}

/// Every set as [`Adapter`]s: the book's own first.
pub fn adapters<'a>(main: &'a [Record], sets: &'a [(String, Vec<Record>)]) -> Vec<Adapter<'a>> {
    let mut out = vec![Adapter {
        set: None,
        records: main,
    }];
    out.extend(sets.iter().map(|(name, records)| Adapter {
        set: Some(name.as_str()),
        records,
    }));
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The committed records of the book's own set and the other sets.
    pub(crate) fn committed() -> (Vec<Record>, Vec<(String, Vec<Record>)>) {
        let generated = crate::repo_root().join("book/src/generated");
        let main = crate::manifest::RUNS
            .iter()
            .map(|r| {
                let path = generated.join(r.lesson).join(format!("{}.json", r.name));
                let text = std::fs::read_to_string(&path).expect("a record");
                serde_json::from_str(&text).expect("a record")
            })
            .collect();
        let sets = crate::origins::load_sets(&generated).expect("the sets");
        (main, sets)
    }

    fn lesson_03() -> Record {
        let path = crate::repo_root().join("book/src/generated/lesson_03/results.json");
        let text = std::fs::read_to_string(path).expect("lesson 03's record");
        serde_json::from_str(&text).expect("a record")
    }

    #[test]
    fn a_straight_line_is_fitted_exactly() {
        let mut r = lesson_03();
        // Lighting = 2 ms + 0.5 ms a comparison, exactly.
        for v in &mut r.variants {
            if let (Some(t), Some(&n)) = (&mut v.timing, v.counters.get(FILTER_TAPS_PER_PIXEL.name))
            {
                t.passes.get_mut("lighting").expect("lighting").median = 2.0 + 0.5 * n as f64;
            }
        }
        let rate = rate(&r).expect("a rate");
        assert!((rate.slope - 0.5).abs() < 1e-12, "{rate:?}");
        assert!((rate.intercept - 2.0).abs() < 1e-12, "{rate:?}");
        assert!((rate.r2 - 1.0).abs() < 1e-12, "{rate:?}");
    }

    #[test]
    fn a_variant_is_over_only_where_its_excess_is_measured() {
        let stat = |m: f64, lo: f64, hi: f64| Stat {
            median: m,
            q25: lo,
            q75: hi,
        };
        let mut r = Row {
            variant: "v".into(),
            comparisons: Some((4.0, false)),
            lit: Some(stat(14.0, 13.0, 15.0)),
            base: Some(stat(2.0, 1.5, 2.5)),
            floor: Some(4.0),
            map: Some(3.0),
            model: Some(1.0),
        };
        // 12 ms over the no-shadow pass against a 4 ms floor: 3×.
        assert_eq!(r.lit_ratio(), Some(3.0));
        assert_eq!(r.map_ratio(), Some(3.0));
        // The same medians, spreads that overlap: not measured, no ratio.
        r.base = Some(stat(2.0, 1.0, 13.5));
        assert_eq!(r.lit_ratio(), None);
        // Faster than the no-shadow pass: no ratio either.
        r.base = Some(stat(20.0, 19.0, 21.0));
        assert_eq!(r.lit_ratio(), None);
    }

    #[test]
    fn the_volume_lessons_look_nothing_up() {
        let (main, _) = committed();
        for lesson in ["lesson_05", "lesson_06", "lesson_07", "lesson_08"] {
            assert!(!LESSONS.contains(&lesson));
            let run = main
                .iter()
                .find(|r| r.lesson == lesson && r.run == "results")
                .expect("a default run");
            assert!(run.variants.iter().all(|v| taps(v).is_none()), "{lesson}");
        }
    }
}
