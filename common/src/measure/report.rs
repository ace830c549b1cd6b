//! `report.json` (its fields: the book's appendix "Interfaces",
//! `book/src/appendix/interfaces.md`) and the terminal table.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::measure::timing::{TimingSource, CPU_TOTAL, FRAME, TOTAL};
use crate::reference::metrics::{
    ClassError, ErrorStats, SoftError, BLEEDING_THRESHOLD, COVERAGE_WARN_PCT, RIM_PX,
};

#[derive(Serialize, Deserialize, Clone, Debug)]
pub struct AdapterReport {
    pub name: String,
    pub backend: String,
    /// The scene's depth-stencil format, as wgpu names it
    /// (`"Depth32FloatStencil8"`; empty in reports older than the field).
    #[serde(default)]
    pub depth_format: String,
    /// What that format stores on this adapter, as measured
    /// ([`crate::gpu::depth_probe`]): `"unorm24"`, `"float32"` (or `"unknown"`).
    #[serde(default)]
    pub depth_storage: String,
}

#[derive(Serialize, Deserialize, Clone, Debug)]
pub struct VariantReport {
    pub name: String,
    /// All lights together (pixel counts summed over lights).
    pub error: ErrorStats,
    /// One entry per light, in scene order.
    pub error_per_light: Vec<ErrorStats>,
    /// Median milliseconds: `total`, one key per pass, `cpu_*` for CPU work.
    pub timing_ms: BTreeMap<String, f64>,
    /// The interquartile range `[q25, q75]` of each `timing_ms` key.
    #[serde(default)]
    pub timing_spread_ms: BTreeMap<String, [f64; 2]>,
    /// Every timed frame's milliseconds, key by key (the generator pools
    /// them over repeated runs).
    #[serde(default)]
    pub timing_samples_ms: BTreeMap<String, Vec<f64>>,
    pub timing_source: TimingSource,
    pub counters: BTreeMap<String, u64>,
    /// The values of the variant's knobs it ran with (`--knob`; absent for
    /// a variant with none).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub knobs: BTreeMap<String, f64>,
    /// The scene's `[camera_path]` measured (absent without one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_path: Option<CameraPathReport>,
    /// The error per pixel class, when the lesson has classes
    /// ([`crate::run::instruments::Instruments::pixel_classes`]; absent otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub classes: Option<Vec<ClassError>>,
    /// How the variant's timed block went ([`crate::measure::protocol`]);
    /// absent in reports older than the protocol.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timing_check: Option<TimingCheck>,
    /// The receivers a rasteriser could flip, and how far each error figure
    /// can move by them (`--fragile`; absent otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fragile: Option<crate::reference::fragile::Fragile>,
}

impl VariantReport {
    /// Whether the times can be quoted: no check (an older report) or a
    /// stable one.
    pub fn timing_stable(&self) -> bool {
        self.timing_check.as_ref().is_none_or(|c| c.stable)
    }
}

/// One timed block's warm-up and its base-pass check.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct TimingCheck {
    /// Untimed frames and their wall-clock milliseconds before timing.
    pub warm_up_frames: u32,
    pub warm_up_ms: f64,
    /// Whether the frame times settled in the warm-up (else it gave up).
    pub settled: bool,
    /// The block's median base-pass time (ms; `None` without a base pass).
    pub base_ms: Option<f64>,
    /// Whether that agrees with the run's reference (see
    /// [`TimingProtocolReport`]): the GPU ran at the same speed.
    pub stable: bool,
}

/// The protocol a run was timed with and its verdict.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct TimingProtocolReport {
    /// `--warm-up-ms`: each block's least warm-up (the first block's: 3×).
    pub warm_up_min_ms: f64,
    /// The timed blocks in the order they ran (`baseline` between variants).
    pub order: Vec<String>,
    /// The median base-pass time of the baseline blocks; a block whose
    /// own is more than `base_ratio_limit` times off it either way, and
    /// further than `base_tolerance_ms` from it, is unstable.
    pub base_reference_ms: Option<f64>,
    pub base_ratio_limit: f64,
    pub base_tolerance_ms: f64,
    /// Every block stable.
    pub stable: bool,
}

/// A variant along the scene's camera path ([`crate::scene::camera_path::Shimmer`]).
/// The flip percentages are of the pixels that are receivers in both
/// frames of a pair, over every pair and light.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct CameraPathReport {
    pub frames: u32,
    /// World-locked: the receivers whose shadow flips when only the fit
    /// moves to the next frame's camera and the view stays
    /// ([`crate::scene::camera_path`]). The reference cannot flip there.
    pub shimmer_pct: f64,
    /// Screen-space: between consecutive frames, the technique flips
    /// lit/shadowed and the reference does not (edges sweeping past count).
    pub screen_mismatch_pct: f64,
    /// The reference flips (the shadow really moves across the pixel).
    pub reference_flip_pct: f64,
    /// The technique flips, rightly or not.
    pub technique_flip_pct: f64,
    /// Each frame's misclassified % (all lights), in path order.
    pub misclassified_pct_per_frame: Vec<f64>,
}

/// The same frame with the visibility test removed: the base pass and one
/// unshadowed lit pass per light. What the shadows cost is a variant's
/// time minus this.
#[derive(Serialize, Deserialize, Clone, Debug)]
pub struct BaselineReport {
    pub timing_ms: BTreeMap<String, f64>,
    #[serde(default)]
    pub timing_spread_ms: BTreeMap<String, [f64; 2]>,
    #[serde(default)]
    pub timing_samples_ms: BTreeMap<String, Vec<f64>>,
    /// Each baseline block (the protocol times one between every two
    /// variants); empty in older reports.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub blocks: Vec<TimingCheck>,
}

impl BaselineReport {
    /// Whether the baseline's times can be quoted: some block was stable
    /// (its frames are those of the stable blocks), or an older report.
    pub fn stable(&self) -> bool {
        self.blocks.is_empty() || self.blocks.iter().any(|b| b.stable)
    }
}

#[derive(Serialize, Deserialize, Clone, Debug)]
pub struct Report {
    pub lesson: String,
    pub adapter: AdapterReport,
    pub width: u32,
    pub height: u32,
    pub scene: String,
    pub reference_ms: f64,
    pub frames: u32,
    pub variants: Vec<VariantReport>,
    /// The no-shadow baseline, timed like the variants.
    #[serde(default)]
    pub baseline: Option<BaselineReport>,
    /// The timing protocol and its verdict (absent in older reports).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timing_protocol: Option<TimingProtocolReport>,
}

/// Sums per-light statistics into one (weighted by receiver pixels).
pub fn combine(per_light: &[ErrorStats]) -> ErrorStats {
    let n: u64 = per_light.iter().map(|s| s.receiver_pixels).sum();
    let interior: u64 = per_light.iter().map(|s| s.interior_receiver_pixels).sum();
    let w = |f: fn(&ErrorStats) -> f64| -> f64 {
        if n == 0 {
            0.0
        } else {
            per_light
                .iter()
                .map(|s| f(s) * s.receiver_pixels as f64)
                .sum::<f64>()
                / n as f64
        }
    };
    ErrorStats {
        receiver_pixels: n,
        misclassified_pct: w(|s| s.misclassified_pct),
        false_shadow_pct: w(|s| s.false_shadow_pct),
        false_lit_pct: w(|s| s.false_lit_pct),
        mean_abs: w(|s| s.mean_abs),
        // Coverage does not depend on the light: every entry has the same.
        coverage_mismatch_pct: per_light
            .iter()
            .map(|s| s.coverage_mismatch_pct)
            .fold(0.0, f64::max),
        interior_receiver_pixels: interior,
        interior_misclassified_pct: if interior == 0 {
            0.0
        } else {
            per_light
                .iter()
                .map(|s| s.interior_misclassified_pct * s.interior_receiver_pixels as f64)
                .sum::<f64>()
                / interior as f64
        },
        soft: combine_soft(per_light),
    }
}

/// The soft figures of the lights that have them, pooled like [`combine`]'s:
/// every pixel count summed, every mean and share weighted by its own
/// count (the penumbra's by penumbra pixels, the umbra's by umbra pixels,
/// the leak's by deep-umbra pixels, the width error by contour pixels over
/// the lights that have one; `None` if none has).
fn combine_soft(per_light: &[ErrorStats]) -> Option<SoftError> {
    let soft: Vec<&SoftError> = per_light.iter().filter_map(|s| s.soft.as_ref()).collect();
    if soft.is_empty() {
        return None;
    }
    let total = |by: fn(&SoftError) -> u64| soft.iter().map(|s| by(s)).sum::<u64>();
    let mean = |f: fn(&SoftError) -> f64, by: fn(&SoftError) -> u64| {
        let n = total(by);
        soft.iter().map(|s| f(s) * by(s) as f64).sum::<f64>() / n.max(1) as f64
    };
    let widths: Vec<(f64, u64)> = (soft.iter())
        .filter_map(|s| Some((s.penumbra_width_error_px?, s.contour_pixels)))
        .collect();
    let width_pixels: u64 = widths.iter().map(|&(_, n)| n).sum();
    Some(SoftError {
        penumbra_pixels: total(|s| s.penumbra_pixels),
        penumbra_mean_abs: mean(|s| s.penumbra_mean_abs, |s| s.penumbra_pixels),
        umbra_pixels: total(|s| s.umbra_pixels),
        umbra_misclassified_pct: mean(|s| s.umbra_misclassified_pct, |s| s.umbra_pixels),
        light_bleeding_pct: mean(|s| s.light_bleeding_pct, |s| s.umbra_pixels),
        umbra_mean_abs: mean(|s| s.umbra_mean_abs, |s| s.umbra_pixels),
        lit_pixels: total(|s| s.lit_pixels),
        lit_mean_abs: mean(|s| s.lit_mean_abs, |s| s.lit_pixels),
        deep_umbra_pixels: total(|s| s.deep_umbra_pixels),
        leak_mean_abs: mean(|s| s.leak_mean_abs, |s| s.deep_umbra_pixels),
        leak_pct: mean(|s| s.leak_pct, |s| s.deep_umbra_pixels),
        spill_pixels: total(|s| s.spill_pixels),
        spill_mean_abs: mean(|s| s.spill_mean_abs, |s| s.spill_pixels),
        horizon_clipped_pixels: total(|s| s.horizon_clipped_pixels),
        horizon_clipped_mean_abs: mean(
            |s| s.horizon_clipped_mean_abs,
            |s| s.horizon_clipped_pixels,
        ),
        contour_pixels: total(|s| s.contour_pixels),
        penumbra_width_error_px: (!widths.is_empty()).then(|| {
            let sum: f64 = widths.iter().map(|&(e, n)| e * n as f64).sum();
            sum / width_pixels.max(1) as f64
        }),
    })
}

impl Report {
    /// One warning line when a variant's GPU image and the reference see
    /// different surfaces on more than [`COVERAGE_WARN_PCT`] % of the covered
    /// pixels (the worst variant is named), else `None`.
    pub fn coverage_warning(&self) -> Option<String> {
        let bad: Vec<&VariantReport> = self
            .variants
            .iter()
            .filter(|v| v.error.coverage_mismatch_pct > COVERAGE_WARN_PCT)
            .collect();
        // The first of the worst, in report order.
        let worst = bad.iter().copied().reduce(|w, v| {
            if v.error.coverage_mismatch_pct > w.error.coverage_mismatch_pct {
                v
            } else {
                w
            }
        })?;
        let others = match bad.len() - 1 {
            0 => String::new(),
            n => format!(" and {n} other variant(s)"),
        };
        Some(format!(
            "warning: {}: the GPU and the reference see different surfaces on {:.1} % of the covered pixels ({}{others}); the error figures leave those pixels out, so they hide part of the image (compare {}_visibility_l0.png with reference_visibility_l0.png)",
            self.lesson, worst.error.coverage_mismatch_pct, worst.name, worst.name
        ))
    }

    /// One line naming the blocks whose base pass strayed (their times are
    /// printed as `unstable`), or `None` when every block was stable.
    pub fn unstable_line(&self) -> Option<String> {
        let p = self.timing_protocol.as_ref().filter(|p| !p.stable)?;
        let mut bad: Vec<String> = self
            .variants
            .iter()
            .filter_map(|v| {
                let c = v.timing_check.as_ref().filter(|c| !c.stable)?;
                Some(match c.base_ms {
                    Some(ms) => format!("{} {ms:.3} ms", v.name),
                    None => format!("{} (no base pass)", v.name),
                })
            })
            .collect();
        let baseline = self.baseline.iter().flat_map(|b| &b.blocks);
        let n = baseline.filter(|c| !c.stable).count();
        if n > 0 {
            let kept = self.baseline.as_ref().is_some_and(|b| b.stable());
            let fate = if kept {
                "left out of the baseline"
            } else {
                "all of them"
            };
            bad.push(format!("{n} baseline block(s), {fate}"));
        }
        Some(format!(
            "unstable: the base pass, the same work in every block, took {} against {:.3} ms in the baseline (more than {}× off); the GPU's speed changed during the run (its clock?), so those times are not quoted. Re-run, or time one variant alone (--variant NAME --frames 300)",
            bad.join(", "),
            p.base_reference_ms.unwrap_or(f64::NAN),
            p.base_ratio_limit
        ))
    }

    /// The terminal table: adapter and reference time, then one row a variant.
    pub fn table(&self) -> String {
        let mut s = String::new();
        s += &format!(
            "{} on {} ({}), {}x{}, scene {}",
            self.lesson,
            self.adapter.name,
            self.adapter.backend,
            self.width,
            self.height,
            self.scene
        );
        if !self.adapter.depth_format.is_empty() {
            let a = &self.adapter;
            s += &format!(", depth {} ({})", a.depth_format, a.depth_storage);
        }
        s += "\n";
        s += &format!("reference (CPU ray cast): {:.1} ms\n", self.reference_ms);
        let src = self.variants.first().map(|v| v.timing_source);
        if src == Some(TimingSource::CpuWall) {
            s += "timing: CPU wall clock per pass (no GPU timestamp queries on this adapter)\n";
        } else {
            s += &format!("timing: GPU timestamps, median of {} frames\n", self.frames);
        }
        let w = self
            .variants
            .iter()
            .map(|v| v.name.len())
            .max()
            .unwrap_or(7)
            .max(21);
        // A shimmer column only when some variant walked a camera path.
        let shimmer = self.variants.iter().any(|v| v.camera_path.is_some());
        let (mut head, mut rule) = match shimmer {
            true => (" | shimmer %".to_string(), "-|----------".to_string()),
            false => (String::new(), String::new()),
        };
        // Soft shadows (an area light): mean |ΔV|, then each class of
        // receiver's count and figures (SOFT_COLUMNS).
        let soft = self.variants.iter().any(|v| v.error.soft.is_some());
        if soft {
            for &(name, width, _) in SOFT_COLUMNS {
                head += &format!(" | {name:>width$}");
                rule += &format!("-|{}", "-".repeat(width + 1));
            }
        }
        s += &format!(
            "{:<w$} | misclassified % | false shadow | false lit | frame ms |   GPU ms |   CPU ms{head}\n",
            "variant"
        );
        s += &format!(
            "{}-|-----------------|--------------|-----------|----------|----------|---------{rule}\n",
            "-".repeat(w)
        );
        let times = |t: &BTreeMap<String, f64>, stable: bool| {
            let get = |k: &str| t.get(k).copied().unwrap_or(f64::NAN);
            let clocked = |x: f64| match stable {
                true => format!("{x:>8.3}"),
                false => format!("{:>8}", "unstable"),
            };
            // CPU time does not depend on the GPU's clock.
            format!(
                "{} | {} | {:>8.3}",
                clocked(get(FRAME)),
                clocked(get(TOTAL)),
                get(CPU_TOTAL)
            )
        };
        if let Some(b) = &self.baseline {
            let blank = format!("{:>15} | {:>12} | {:>9}", "-", "-", "-");
            s += &format!(
                "{:<w$} | {blank} | {}",
                "no shadows (baseline)",
                times(&b.timing_ms, b.stable())
            );
            if shimmer {
                s += &format!(" | {:>9}", "-");
            }
            if soft {
                s += &soft_cells(None);
            }
            s += "\n";
        }
        for v in &self.variants {
            s += &format!(
                "{:<w$} | {:>15.3} | {:>12.3} | {:>9.3} | {}",
                v.name,
                v.error.misclassified_pct,
                v.error.false_shadow_pct,
                v.error.false_lit_pct,
                times(&v.timing_ms, v.timing_stable())
            );
            if shimmer {
                match &v.camera_path {
                    Some(p) => s += &format!(" | {:>9.3}", p.shimmer_pct),
                    None => s += &format!(" | {:>9}", "-"),
                }
            }
            if soft {
                s += &soft_cells(v.error.soft.as_ref().map(|e| (&v.error, e)));
            }
            s += "\n";
        }
        if let Some(line) = self.unstable_line() {
            s += &line;
            s += "\n";
        }
        if soft {
            s += "What each soft column means (|dV|: the mean |V - V_ref| over the pixels counted; n: how many receiver pixels):\n";
            for (name, meaning) in soft_legend() {
                s += &format!("  {name}: {meaning}\n");
            }
        }
        s
    }
}

/// A soft shadow's columns of [`Report::table`]: the name, the width, and
/// the cell of a variant's figures. Every mean has its count before it.
type SoftColumn = (&'static str, usize, fn(&ErrorStats, &SoftError) -> String);
const SOFT_COLUMNS: &[SoftColumn] = &[
    ("mean |dV|", 9, |e, _| format!("{:.4}", e.mean_abs)),
    ("n umbra", 7, |_, s| s.umbra_pixels.to_string()),
    ("umbra |dV|", 10, |_, s| format!("{:.4}", s.umbra_mean_abs)),
    ("n penumbra", 10, |_, s| s.penumbra_pixels.to_string()),
    ("penumbra |dV|", 13, |_, s| {
        format!("{:.4}", s.penumbra_mean_abs)
    }),
    ("n lit", 7, |_, s| s.lit_pixels.to_string()),
    ("lit |dV|", 8, |_, s| format!("{:.4}", s.lit_mean_abs)),
    ("bleeding %", 10, |_, s| {
        format!("{:.3}", s.light_bleeding_pct)
    }),
    ("n deep", 7, |_, s| s.deep_umbra_pixels.to_string()),
    ("leak |dV|", 9, |_, s| format!("{:.4}", s.leak_mean_abs)),
    ("leak %", 7, |_, s| format!("{:.3}", s.leak_pct)),
    ("n spill", 7, |_, s| s.spill_pixels.to_string()),
    ("spill |dV|", 10, |_, s| format!("{:.4}", s.spill_mean_abs)),
    ("n horizon", 9, |_, s| s.horizon_clipped_pixels.to_string()),
    ("horizon |dV|", 12, |_, s| {
        format!("{:.4}", s.horizon_clipped_mean_abs)
    }),
    ("n contour", 9, |_, s| s.contour_pixels.to_string()),
    ("width err px", 12, |_, s| {
        s.penumbra_width_error_px
            .map_or_else(|| "-".to_string(), |d| format!("{d:.2}"))
    }),
];

/// What each of [`SOFT_COLUMNS`] means, printed under a soft run's table
/// (`common::reference::metrics::SoftError` defines each figure).
pub fn soft_legend() -> Vec<(&'static str, String)> {
    let rim = RIM_PX;
    vec![
        ("mean |dV|", "over every receiver of the light: n umbra + n penumbra + n lit + n horizon pixels".into()),
        ("n umbra, umbra |dV|", "the receivers in the exact reference's umbra (V_ref = 0, the emitter wholly hidden)".into()),
        ("n penumbra, penumbra |dV|", "the receivers in its penumbra (0 < V_ref < 1)".into()),
        ("n lit, lit |dV|", "the receivers on its lit side (V_ref = 1): shadow where there is none (a blur's spill, acne)".into()),
        ("bleeding %", format!("of the umbra (n umbra), the share lit above V = {BLEEDING_THRESHOLD}")),
        ("n deep, leak |dV|, leak %", format!("the deep umbra, the umbra receivers more than {rim} px from every receiver with V_ref > 0: mean V there, and the share lit above V = {BLEEDING_THRESHOLD} (light through the blocker)")),
        ("n spill, spill |dV|", format!("the umbra receivers within {rim} px of one with V_ref > 0 and the lit receivers within {rim} px of one with V_ref < 1 (light and shadow spilling out of the penumbra)")),
        ("n horizon, horizon |dV|", "the receivers the reference flags horizon-clipped (part of the emitter below their tangent plane), kept out of every other column; 0 where it flags none".into()),
        ("n contour, width err px", "the pixels of both images' 10 % and 90 % contours (V >= c beside V < c, on one object), and the mean distance in pixels from each to the other image's contour at the same level: 0 when the penumbra lies where the reference's does; - when one image has a contour the other lacks, or neither has one".into()),
    ]
}

/// A variant's soft cells (figures and their count), or `-` in each.
fn soft_cells(figures: Option<(&ErrorStats, &SoftError)>) -> String {
    let mut s = String::new();
    for &(_, width, cell) in SOFT_COLUMNS {
        let text = figures.map_or_else(|| "-".to_string(), |(e, f)| cell(e, f));
        s += &format!(" | {text:>width$}");
    }
    s
}

#[cfg(test)]
#[path = "unit_tests/report.rs"]
mod tests;
