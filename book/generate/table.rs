//! The markdown tables made from the records ([`crate::record`]): a run's
//! results and passes tables, a lesson's extreme cases side by side, and
//! the cells every generated table shares (percentages, counts, times with
//! their spread). The chapters include them; `tests/generated.rs` checks
//! each committed table against its record.

use anyhow::Result;

use crate::legend::legend;
use crate::record::{Record, Stat, Timing, VariantRecord};

/// The soft-shadow columns (lesson 10), defined in [`crate::legend`].
pub const PENUMBRA: &str = "penumbra \\|ΔV\\| %";
pub const BLEEDING: &str = "bleeding %";

/// Where the timing protocol is told, from a page of the book.
pub const PROTOCOL: &str = "using.md#how-times-are-measured";

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

/// A time in milliseconds at the tables' precision.
pub fn ms(x: f64) -> String {
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
            // The protocol is told once, where the link goes; the line
            // keeps what a reader needs to weigh the cells.
            let warm_up = match self.warm_up_ms {
                Some(ms) => format!("each variant warmed up ≥ {ms:.0} ms"),
                None => "after 2 warm-up frames".to_string(),
            };
            format!(
                "times: median [spread] of {} runs × {} frames, {warm_up}, {} ([the protocol]({PROTOCOL}))",
                self.repeats,
                self.frames,
                self.timing_source.replace('_', " ")
            )
        };
        format!(
            "*{} · {}×{} · {} · {}*",
            self.adapter_label(),
            self.width,
            self.height,
            scene,
            timing
        )
    }

    /// Counter names that any variant reports, in a stable order.
    fn counter_keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = self
            .variants
            .iter()
            .flat_map(|v| v.counters.keys().cloned())
            .collect();
        keys.sort_by_key(|k| crate::legend::counter_rank(k));
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
        if self.soft() {
            let (penumbra, bleeding) = match &v.soft {
                Some(e) => (pct(100.0 * e.penumbra_mean_abs), pct(e.light_bleeding_pct)),
                None => ("—".into(), "—".into()),
            };
            cells.extend([penumbra, bleeding]);
        }
        for k in self.counter_keys() {
            cells.push(v.counters.get(&k).map_or("—".into(), |&n| count(n)));
        }
        cells
    }

    /// The run's main table: one row a variant (and the no-shadow
    /// baseline, for timed runs).
    pub fn table(&self, with_mean_abs: bool) -> Result<String> {
        let mut head = vec![
            "variant".to_string(),
            "misclassified %".into(),
            "false shadow %".into(),
            "false lit %".into(),
        ];
        if with_mean_abs {
            head.push("mean \\|ΔV\\| %".into());
        }
        if self.soft() {
            head.extend([PENUMBRA.to_string(), BLEEDING.into()]);
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
        s += &header(&head);
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
        s += &legend(&head)?;
        if let Some(note) = self.unstable_note() {
            s += &format!("\n{note}\n");
        }
        Ok(s)
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
    pub fn passes_table(&self) -> Result<String> {
        let mut keys: Vec<String> = self
            .variants
            .iter()
            .filter_map(|v| v.timing.as_ref())
            .flat_map(|t| t.passes.keys().cloned())
            .collect();
        keys.sort_by_key(|k| crate::legend::pass_rank(k));
        keys.dedup();
        let mut head = vec!["variant".to_string()];
        head.extend(keys.iter().map(|k| format!("`{k}` ms")));
        let mut s = format!("{}\n\n", self.header());
        s += &header(&head);
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
        s += &legend(&head)?;
        Ok(s)
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

/// A table's header: its columns' row and the `---` row under it.
pub fn header(columns: &[String]) -> String {
    row(columns) + &row(&vec!["---".to_string(); columns.len()])
}

/// What a scenes table's cells show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cell {
    /// Misclassified % of the receivers (a hard shadow's error).
    Misclassified,
    /// Mean |ΔV| over the reference's penumbra, in % (a soft shadow's).
    Penumbra,
    /// Light bleeding, % of the reference's umbra.
    Bleeding,
}

impl Cell {
    /// The cells a lesson's scenes table shows: its records' own error.
    pub fn error_of(records: &[&Record]) -> Cell {
        match records.iter().any(|r| r.soft()) {
            true => Cell::Penumbra,
            false => Cell::Misclassified,
        }
    }

    fn value(self, v: &VariantRecord) -> Option<f64> {
        match self {
            Cell::Misclassified => Some(v.misclassified_pct),
            Cell::Penumbra => v.soft.as_ref().map(|s| 100.0 * s.penumbra_mean_abs),
            Cell::Bleeding => v.soft.as_ref().map(|s| s.light_bleeding_pct),
        }
    }

    /// The caption's words for the cells.
    fn caption(self) -> &'static str {
        match self {
            Cell::Misclassified => "misclassified % of receiver pixels",
            Cell::Penumbra => "mean |ΔV| over the reference's penumbra (0 < V < 1), in %",
            Cell::Bleeding => "light bleeding: % of the reference's umbra (V = 0) lit above 0.1",
        }
    }

    /// The legend's words for a variant's cell.
    fn legend(self) -> &'static str {
        match self {
            Cell::Misclassified => "misclassified % on the row's scene",
            Cell::Penumbra => "mean |V − V_ref| over the reference's penumbra (receivers with 0 < V_ref < 1) on the row's scene, in %",
            Cell::Bleeding => "light bleeding on the row's scene: of the receivers in the reference's umbra (V_ref = 0), the % it lights above 0.1; 0 where the scene has no umbra",
        }
    }
}

/// A lesson's extreme cases side by side: one row a run, one column a
/// variant, `cell` in the cells (misclassified %, or for a soft shadow
/// the penumbra's mean |ΔV| or the bleeding).
pub fn scenes_table(records: &[&Record], cell: Cell) -> Result<String> {
    let Some(first) = records.first() else {
        return Ok(String::new());
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
        "*{} · {}×{} · {}*\n\n",
        first.adapter_label(),
        first.width,
        first.height,
        cell.caption()
    );
    let mut head = vec!["scene".to_string()];
    head.extend(names.iter().map(|n| format!("`{n}`")));
    s += &header(&head);
    for r in records {
        let mut cells = vec![format!("{} (`{}`)", r.title, r.scene)];
        for n in &names {
            cells.push(
                r.variants
                    .iter()
                    .find(|v| &v.name == n)
                    .and_then(|v| cell.value(v))
                    .map_or("—".into(), pct),
            );
        }
        s += &row(&cells);
    }
    let own: Vec<(String, String)> = names
        .iter()
        .map(|n| {
            (
                format!("`{n}`"),
                format!("variant `{n}`'s {}", cell.legend()),
            )
        })
        .collect();
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    s += &crate::legend::legend_with(&head, &own)?;
    Ok(s)
}

/// The soft shadow's figures per class of receiver (lesson 10), each with
/// its pixel count: the umbra, the penumbra and the lit receivers of the
/// reference, the deep umbra's leak, the spill around the penumbra, the
/// receivers below their own horizon, and the penumbra's width error.
const SOFT_CLASS_COLUMNS: &[(&str, &str)] = &[
    ("variant", "the lesson's variant (its `--variant` name)"),
    ("umbra px", "receiver pixels in the reference's umbra (V_ref = 0, the emitter wholly hidden)"),
    ("umbra \\|ΔV\\| %", "the mean of |V − V_ref| over the umbra, in %: light where none arrives"),
    ("penumbra px", "receiver pixels in the reference's penumbra (0 < V_ref < 1)"),
    ("penumbra \\|ΔV\\| %", "the mean of |V − V_ref| over the penumbra, in %"),
    ("lit px", "receiver pixels the reference lights fully (V_ref = 1)"),
    ("lit \\|ΔV\\| %", "the mean of |V − V_ref| over the lit receivers, in %: a blur's spill into the light, acne under a wide kernel"),
    ("deep umbra px", "umbra pixels farther than 3 px (RIM_PX) from every receiver the reference lights at all"),
    ("leak %", "of the deep umbra, the share lit above V = 0.1: light leaking through a blocker (the variance maps' failure), not a blur's spill"),
    ("spill px", "the umbra's rim and the lit fringe: umbra pixels within 3 px of a receiver with V_ref > 0, lit pixels within 3 px of one with V_ref < 1"),
    ("spill \\|ΔV\\| %", "the mean of |V − V_ref| over the spill pixels, in %: a penumbra too wide or misplaced spills there"),
    ("horizon px", "receivers that see part of the emitter below their own tangent plane, counted apart (no shadow map can model them); 0 where the reference flags none"),
    ("width error px", "the mean distance, in pixels, between the reference's and the variant's 10 % and 90 % contours of V: how far the penumbra's edges are from where they belong; — where one image has a contour the other lacks"),
];

impl Record {
    /// The per-class soft table, or `None` for a run without a soft shadow.
    pub fn soft_classes_table(&self) -> Result<Option<String>> {
        if !self.soft() {
            return Ok(None);
        }
        let head: Vec<String> = SOFT_CLASS_COLUMNS
            .iter()
            .map(|(n, _)| n.to_string())
            .collect();
        let mut s = format!("{}\n\n", self.header());
        s += &header(&head);
        for v in &self.variants {
            let Some(e) = &v.soft else { continue };
            let width = e
                .penumbra_width_error_px
                .map_or("—".to_string(), |w| format!("{w:.2}"));
            s += &row(&[
                format!("`{}`", v.name),
                count(e.umbra_pixels),
                pct(100.0 * e.umbra_mean_abs),
                count(e.penumbra_pixels),
                pct(100.0 * e.penumbra_mean_abs),
                count(e.lit_pixels),
                pct(100.0 * e.lit_mean_abs),
                count(e.deep_umbra_pixels),
                pct(e.leak_pct),
                count(e.spill_pixels),
                pct(100.0 * e.spill_mean_abs),
                count(e.horizon_clipped_pixels),
                width,
            ]);
        }
        s += &crate::legend::legend_own(&head, SOFT_CLASS_COLUMNS);
        Ok(Some(s))
    }
}
