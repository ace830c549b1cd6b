//! What the generator keeps of a run (`book/src/generated/<lesson>/<run>.json`)
//! and the markdown tables made from it. The chapters include the tables;
//! `tests/generated.rs` re-runs the lessons and compares the error columns
//! and counters with these records, and the tables with their records.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// A median with its spread (an interquartile range, see [`Stat::of_runs`]), in milliseconds.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct Stat {
    pub median: f64,
    pub q25: f64,
    pub q75: f64,
}

impl Stat {
    /// The median and interquartile range of pooled samples.
    pub fn of(samples: &[f64]) -> Stat {
        Stat {
            median: common::measure::timing::quantile(samples, 0.5),
            q25: common::measure::timing::quantile(samples, 0.25),
            q75: common::measure::timing::quantile(samples, 0.75),
        }
    }

    /// The spread of a time measured in several runs (one sample list a
    /// run): the median of all samples; from the lower of their first
    /// quartile and the lowest run's own median, to the higher of their
    /// third quartile and the highest run's median. A run that went
    /// faster or slower as a whole widens the spread instead of hiding
    /// in the pooled frames.
    pub fn of_runs(runs: &[&[f64]]) -> Stat {
        let all: Vec<f64> = runs.iter().flat_map(|r| r.iter().copied()).collect();
        let pooled = Stat::of(&all);
        let medians: Vec<f64> = runs
            .iter()
            .filter(|r| !r.is_empty())
            .map(|r| common::measure::timing::quantile(r, 0.5))
            .collect();
        let lo = medians.iter().copied().fold(pooled.q25, f64::min);
        let hi = medians.iter().copied().fold(pooled.q75, f64::max);
        Stat {
            median: pooled.median,
            q25: lo,
            q75: hi,
        }
    }

    /// Two times differ measurably only when their spreads do not overlap.
    pub fn differs_from(&self, other: &Stat) -> bool {
        self.q75 < other.q25 || other.q75 < self.q25
    }
}

/// GPU total and per-pass times (`frame` and `cpu_total` among them),
/// pooled over the repeats.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Timing {
    pub total: Stat,
    pub passes: BTreeMap<String, Stat>,
    /// Why the times cannot be quoted (the protocol's base-pass check
    /// failed in a repeat), or absent when they can.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unstable: Option<String>,
    /// Runs left out of the pool because the check failed in them (the
    /// other runs' frames make the figures).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub left_out: Option<String>,
}

impl Timing {
    /// The frame cost (`frame`: wall clock, start to GPU completion); the
    /// GPU total in records older than the key.
    pub fn frame(&self) -> &Stat {
        self.passes.get(FRAME).unwrap_or(&self.total)
    }

    /// The CPU's time per frame (`cpu_total`), when recorded.
    pub fn cpu(&self) -> Option<&Stat> {
        self.passes.get(CPU_TOTAL)
    }

    /// Whether the times can be quoted.
    pub fn stable(&self) -> bool {
        self.unstable.is_none()
    }
}

use common::measure::timing::{CPU_TOTAL, FRAME};

/// One variant: its error against the reference, counters and times.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct VariantRecord {
    pub name: String,
    pub receiver_pixels: u64,
    pub misclassified_pct: f64,
    pub false_shadow_pct: f64,
    pub false_lit_pct: f64,
    pub mean_abs: f64,
    pub coverage_mismatch_pct: f64,
    pub counters: BTreeMap<String, u64>,
    pub timing: Option<Timing>,
    /// Shimmer over the scene's `[camera_path]` (lesson 09), when it has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_path: Option<CameraPathRecord>,
    /// The error per class of pixels (lesson 09: per cascade), when the
    /// lesson gives classes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub classes: Vec<ClassRecord>,
}

/// Shimmer over a camera path (lesson 09): the report's own figures,
/// kept as they are (see `common::scene::camera_path`).
pub type CameraPathRecord = common::measure::report::CameraPathReport;

impl ClassRecord {
    /// What the book keeps of a report's per-class errors.
    pub fn of(v: &common::measure::report::VariantReport) -> Vec<ClassRecord> {
        v.classes
            .iter()
            .flatten()
            .map(|c| ClassRecord {
                name: c.name.clone(),
                pixels: c.pixels,
                misclassified_pct: c.misclassified_pct,
                false_shadow_pct: c.false_shadow_pct,
                false_lit_pct: c.false_lit_pct,
            })
            .collect()
    }
}

/// The error over one class of pixels (one cascade).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct ClassRecord {
    pub name: String,
    pub pixels: u64,
    pub misclassified_pct: f64,
    pub false_shadow_pct: f64,
    pub false_lit_pct: f64,
}

/// One run of one lesson (timed runs pool several processes).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Record {
    pub lesson: String,
    pub run: String,
    /// The scene file, or `default`.
    pub scene: String,
    pub title: String,
    pub adapter: String,
    pub backend: String,
    pub width: u32,
    pub height: u32,
    /// Processes and timed frames per process (0 frames: untimed).
    pub repeats: u32,
    pub frames: u32,
    pub timing_source: String,
    /// The protocol's least warm-up per timed block (`--warm-up-ms`);
    /// absent in untimed runs and in records older than the protocol.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warm_up_ms: Option<f64>,
    pub variants: Vec<VariantRecord>,
    pub baseline: Option<Timing>,
}

/// Pools the samples of every key over the runs' timing maps (one map a
/// run): each key's [`Stat::of_runs`].
pub fn pool(maps: &[&BTreeMap<String, Vec<f64>>]) -> Option<Timing> {
    let mut keys: Vec<&String> = maps.iter().flat_map(|m| m.keys()).collect();
    keys.sort();
    keys.dedup();
    let stat = |k: &str| {
        let runs: Vec<&[f64]> = maps
            .iter()
            .filter_map(|m| m.get(k))
            .map(Vec::as_slice)
            .collect();
        Stat::of_runs(&runs)
    };
    maps.iter().find(|m| m.contains_key("total"))?;
    let passes = keys
        .iter()
        .filter(|k| k.as_str() != "total")
        .map(|k| (k.to_string(), stat(k)))
        .collect();
    Some(Timing {
        total: stat("total"),
        passes,
        unstable: None,
        left_out: None,
    })
}

/// Where a report's times came from, in words.
pub fn timing_source(report: &common::measure::report::Report) -> String {
    match report.variants.first().map(|v| v.timing_source) {
        Some(common::measure::timing::TimingSource::GpuTimestamps) => "GPU timestamps".into(),
        Some(common::measure::timing::TimingSource::CpuWall) => "CPU wall clock per pass".into(),
        None => String::new(),
    }
}

/// An error percentage as the tables print it.
pub fn pct(x: f64) -> String {
    format!("{x:.3}")
}

/// A count with thin-space thousands separators: `7 336 928`.
pub fn count(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push('\u{2009}');
        }
        out.push(c);
    }
    out
}

fn ms(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

/// `18.2 [17.9–18.6]`: a median and its spread.
pub fn stat(s: &Stat) -> String {
    format!("{} [{}–{}]", ms(s.median), ms(s.q25), ms(s.q75))
}

impl Record {
    /// `lesson_05/results`: the manifest's run id.
    pub fn id(&self) -> String {
        format!("{}/{}", self.lesson, self.run)
    }

    /// The line above every table: adapter, resolution, scene, protocol.
    pub fn header(&self) -> String {
        let scene = if self.scene == "default" {
            format!("the default scene (`scenes/{}.toml`)", self.lesson)
        } else {
            format!("`{}` ({})", self.scene, self.title)
        };
        let timing = if self.frames == 0 {
            "error and counters only (untimed)".to_string()
        } else {
            let warm_up = match self.warm_up_ms {
                Some(ms) => format!(
                    "each variant warmed up (≥ {ms:.0} ms, until its frame times settle) and timed back to back with the no-shadow baseline between"
                ),
                None => "after 2 warm-up frames".to_string(),
            };
            format!(
                "times: median of {} runs × {} frames, {warm_up}, [spread: the frames' interquartile range, widened to hold each run's median], {}",
                self.repeats,
                self.frames,
                self.timing_source.replace('_', " ")
            )
        };
        format!(
            "*{}, {} · {}×{} · {} · {}*",
            self.adapter, self.backend, self.width, self.height, scene, timing
        )
    }

    /// Counter names that any variant reports, in a stable order.
    fn counter_keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = self
            .variants
            .iter()
            .flat_map(|v| v.counters.keys().cloned())
            .collect();
        keys.sort();
        keys.dedup();
        keys
    }

    /// The error columns and counters of one variant: the cells the drift
    /// test compares.
    pub fn measured_cells(&self, v: &VariantRecord, with_mean_abs: bool) -> Vec<String> {
        let mut cells = vec![
            format!("`{}`", v.name),
            pct(v.misclassified_pct),
            pct(v.false_shadow_pct),
            pct(v.false_lit_pct),
        ];
        if with_mean_abs {
            cells.push(pct(100.0 * v.mean_abs));
        }
        for k in self.counter_keys() {
            cells.push(v.counters.get(&k).map_or("—".into(), |&n| count(n)));
        }
        cells
    }

    /// The run's main table: one row a variant (and the no-shadow
    /// baseline, for timed runs).
    pub fn table(&self, with_mean_abs: bool) -> String {
        let mut head = vec![
            "variant".to_string(),
            "misclassified %".into(),
            "false shadow %".into(),
            "false lit %".into(),
        ];
        if with_mean_abs {
            head.push("mean \\|ΔV\\| %".into());
        }
        head.extend(self.counter_keys().iter().map(|k| format!("`{k}`")));
        let timed = self.frames > 0;
        if timed {
            head.extend([
                "frame ms".to_string(),
                "GPU ms".into(),
                "CPU ms".into(),
                "shadows cost (frame, vs no shadows)".into(),
                "vs the fastest".into(),
            ]);
        }
        let stable = |t: &&Timing| t.stable();
        let fastest = self
            .variants
            .iter()
            .filter_map(|v| {
                v.timing
                    .as_ref()
                    .filter(stable)
                    .map(|t| (v.name.clone(), t.frame()))
            })
            .min_by(|a, b| a.1.median.total_cmp(&b.1.median));
        let baseline = self.baseline.as_ref().filter(stable);
        let mut s = format!("{}\n\n", self.header());
        s += &row(&head);
        s += &row(&vec!["---".to_string(); head.len()]);
        if let (true, Some(base)) = (timed, &self.baseline) {
            let n = head.len() - 6;
            let mut cells = vec!["no shadows (baseline)".to_string()];
            cells.extend(vec!["—".to_string(); n]);
            cells.extend(time_cells(base));
            cells.extend(["—".into(), "—".into()]);
            s += &row(&cells);
        }
        for v in &self.variants {
            let mut cells = self.measured_cells(v, with_mean_abs);
            if let Some(t) = v.timing.as_ref().filter(|_| timed) {
                cells.extend(time_cells(t));
                let frame = t.frame();
                cells.push(match baseline {
                    _ if !t.stable() => "—".into(),
                    Some(b) if frame.differs_from(b.frame()) => format!(
                        "{:+.1} ms (×{:.2})",
                        frame.median - b.frame().median,
                        frame.median / b.frame().median
                    ),
                    Some(_) => "no measurable difference".into(),
                    None => "—".into(),
                });
                cells.push(match &fastest {
                    _ if !t.stable() => "—".into(),
                    Some((name, _)) if *name == v.name => "fastest".into(),
                    Some((name, f)) if frame.differs_from(f) => {
                        format!("{:+.1} ms", frame.median - f.median)
                    }
                    Some((name, _)) => format!("no measurable difference from `{name}`"),
                    None => "—".into(),
                });
            }
            s += &row(&cells);
        }
        if let Some(note) = self.unstable_note() {
            s += &format!("\n{note}\n");
        }
        s
    }

    /// The lines under a table whose protocol check failed somewhere:
    /// the cells not quoted, and the runs left out of the others.
    pub fn unstable_note(&self) -> Option<String> {
        let named = |f: fn(&Timing) -> Option<&String>| -> Vec<String> {
            let mut out: Vec<String> = self
                .variants
                .iter()
                .filter_map(|v| Some(format!("`{}`: {}", v.name, f(v.timing.as_ref()?)?)))
                .collect();
            if let Some(u) = self.baseline.as_ref().and_then(f) {
                out.push(format!("baseline: {u}"));
            }
            out
        };
        let unstable = named(|t| t.unstable.as_ref());
        let left_out = named(|t| t.left_out.as_ref());
        let mut lines = Vec::new();
        if !unstable.is_empty() {
            lines.push(format!(
                "*Unstable: the base pass, the same work in every block, took a different time in these blocks than in the baseline's, in every run, so their times are not quoted ({}).*",
                unstable.join("; ")
            ));
        }
        if !left_out.is_empty() {
            lines.push(format!(
                "*Left out: in these runs the base pass ran at another speed than the baseline's (more than 2× off), so their frames are left out and the other runs' make the figures ({}).*",
                left_out.join("; ")
            ));
        }
        (!lines.is_empty()).then(|| lines.join("\n\n"))
    }

    /// Per-pass times of a timed run: median [spread].
    pub fn passes_table(&self) -> String {
        let mut keys: Vec<String> = self
            .variants
            .iter()
            .filter_map(|v| v.timing.as_ref())
            .flat_map(|t| t.passes.keys().cloned())
            .collect();
        keys.sort();
        keys.dedup();
        let mut head = vec!["variant".to_string()];
        head.extend(keys.iter().map(|k| format!("`{k}` ms")));
        let mut s = format!("{}\n\n", self.header());
        s += &row(&head);
        s += &row(&vec!["---".to_string(); head.len()]);
        let mut line = |name: String, t: &Timing| {
            let mut cells = vec![name];
            for k in &keys {
                cells.push(t.passes.get(k).map_or("—".into(), stat));
            }
            s += &row(&cells);
        };
        if let Some(b) = &self.baseline {
            line("no shadows (baseline)".into(), b);
        }
        for v in &self.variants {
            if let Some(t) = &v.timing {
                line(format!("`{}`", v.name), t);
            }
        }
        s
    }
}

/// A timing's frame, GPU and CPU cells; `unstable` for the first two
/// when the protocol's check failed (CPU time does not follow the GPU's
/// clock).
pub fn time_cells(t: &Timing) -> [String; 3] {
    let clocked = |x: &Stat| {
        if t.stable() {
            stat(x)
        } else {
            "unstable".into()
        }
    };
    [
        clocked(t.frame()),
        clocked(&t.total),
        t.cpu().map_or("—".into(), stat),
    ]
}

/// A markdown table row.
pub fn row(cells: &[String]) -> String {
    format!("| {} |\n", cells.join(" | "))
}

/// A lesson's extreme cases side by side: one row a run, one column a
/// variant, misclassified % in the cells.
pub fn scenes_table(records: &[&Record]) -> String {
    let Some(first) = records.first() else {
        return String::new();
    };
    let mut names: Vec<String> = Vec::new();
    for r in records {
        for v in &r.variants {
            if !names.contains(&v.name) {
                names.push(v.name.clone());
            }
        }
    }
    let mut s = format!(
        "*{}, {} · {}×{} · misclassified % of receiver pixels*\n\n",
        first.adapter, first.backend, first.width, first.height
    );
    let mut head = vec!["scene".to_string()];
    head.extend(names.iter().map(|n| format!("`{n}`")));
    s += &row(&head);
    s += &row(&vec!["---".to_string(); head.len()]);
    for r in records {
        let mut cells = vec![format!("{} (`{}`)", r.title, r.scene)];
        for n in &names {
            cells.push(
                r.variants
                    .iter()
                    .find(|v| &v.name == n)
                    .map_or("—".into(), |v| pct(v.misclassified_pct)),
            );
        }
        s += &row(&cells);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_off_as_a_whole_widens_the_spread() {
        // Three runs whose frames agree within each run: the pooled
        // quartiles alone would hide the slow third run.
        let runs: [&[f64]; 3] = [
            &[10.0, 10.1, 10.2],
            &[10.0, 10.1, 10.1],
            &[13.0, 13.1, 13.2],
        ];
        let s = Stat::of_runs(&runs);
        let all: Vec<f64> = runs.iter().flat_map(|r| r.iter().copied()).collect();
        let pooled = Stat::of(&all);
        assert_eq!(s.median, pooled.median);
        assert!(pooled.q75 < 13.1 && s.q75 == 13.1, "{pooled:?} {s:?}");
        assert_eq!(s.q25, pooled.q25);
        // Runs that agree leave the interquartile range as it is.
        let same: [&[f64]; 2] = [&[1.0, 2.0, 3.0], &[1.0, 2.0, 3.0]];
        assert_eq!(
            Stat::of_runs(&same),
            Stat::of(&[1.0, 2.0, 3.0, 1.0, 2.0, 3.0])
        );
    }
}
