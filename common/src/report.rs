//! `report.json` (INTERFACES.md) and the terminal table.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::metrics::{ClassError, ErrorStats, COVERAGE_WARN_PCT};
use crate::timing::TimingSource;

#[derive(Serialize, Deserialize, Clone, Debug)]
pub struct AdapterReport {
    pub name: String,
    pub backend: String,
    /// The scene's depth-stencil format, as wgpu names it
    /// (`"Depth32FloatStencil8"`; empty in reports older than the field).
    #[serde(default)]
    pub depth_format: String,
    /// What that format stores on this adapter, as measured
    /// ([`crate::depth_probe`]): `"unorm24"`, `"float32"` (or `"unknown"`).
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
    /// The scene's `[camera_path]` measured (absent without one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_path: Option<CameraPathReport>,
    /// The error per pixel class, when the lesson has classes
    /// ([`crate::lesson::Lesson::pixel_classes`]; absent otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub classes: Option<Vec<ClassError>>,
}

/// A variant along the scene's camera path ([`crate::camera_path::Shimmer`]).
/// The flip percentages are of the pixels that are receivers in both
/// frames of a pair, over every pair and light.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct CameraPathReport {
    pub frames: u32,
    /// World-locked: the receivers whose shadow flips when only the fit
    /// moves to the next frame's camera and the view stays
    /// ([`crate::camera_path`]). The reference cannot flip there.
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
    pub timing_spread_ms: BTreeMap<String, [f64; 2]>,
    pub timing_samples_ms: BTreeMap<String, Vec<f64>>,
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
    }
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
            .max(7);
        // A shimmer column only when some variant walked a camera path.
        let shimmer = self.variants.iter().any(|v| v.camera_path.is_some());
        let (head, rule) = match shimmer {
            true => (" | shimmer %", "-|----------"),
            false => ("", ""),
        };
        s += &format!(
            "{:<w$} | misclassified % | false shadow | false lit |       ms{head}\n",
            "variant"
        );
        s += &format!(
            "{}-|-----------------|--------------|-----------|---------{rule}\n",
            "-".repeat(w)
        );
        for v in &self.variants {
            let ms = v.timing_ms.get("total").copied().unwrap_or(f64::NAN);
            s += &format!(
                "{:<w$} | {:>15.3} | {:>12.3} | {:>9.3} | {:>8.3}",
                v.name,
                v.error.misclassified_pct,
                v.error.false_shadow_pct,
                v.error.false_lit_pct,
                ms
            );
            if shimmer {
                match &v.camera_path {
                    Some(p) => s += &format!(" | {:>9.3}", p.shimmer_pct),
                    None => s += &format!(" | {:>9}", "-"),
                }
            }
            s += "\n";
        }
        s
    }
}
