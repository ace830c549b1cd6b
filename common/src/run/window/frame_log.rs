//! A window's `--window-log`: one JSON line a frame (its time and cost,
//! the view it shows, the error figure with the view it was computed
//! for), which a web page also hands to its scripts.

use std::io::Write;

use anyhow::{Context, Result};

use super::live::Level;
use super::overlay::ShownError;
use super::App;
use crate::run::instruments::Instruments;

impl<L: Instruments> App<L> {
    /// One `--window-log` line: the frame's time and cost, the view it
    /// shows, and the error figure with the view it was computed for.
    pub(super) fn write_log(
        &mut self,
        shown: &Option<ShownError>,
        overlay: Option<[f32; 4]>,
    ) -> Result<()> {
        #[cfg(not(target_arch = "wasm32"))]
        if self.log.is_none() {
            return Ok(());
        }
        let s = &self.state;
        let answer = s.answer.as_ref().map(|a| {
            serde_json::json!({
                "scene_gen": a.stamp.scene_gen,
                "image_gen": a.stamp.image_gen,
                "level": match a.level { Level::Coarse => "coarse", Level::Full => "full" },
                "worker_ms": a.ms,
                "misclassified_pct": a.error.misclassified_pct,
                "false_shadow_pct": a.error.false_shadow_pct,
                "false_lit_pct": a.error.false_lit_pct,
                // An area light's: the error inside the penumbra.
                "penumbra_mean_abs": a.error.soft.as_ref().map(|x| x.penumbra_mean_abs),
                "light_bleeding_pct": a.error.soft.as_ref().map(|x| x.light_bleeding_pct),
            })
        });
        let line = serde_json::json!({
            "frame": self.frames,
            "width": self.running.as_ref().map(|r| r.targets.width),
            "height": self.running.as_ref().map(|r| r.targets.height),
            "t_s": self.started.elapsed().as_secs_f64(),
            "variant": s.variants[s.current],
            "scene_gen": s.stamp.scene_gen,
            "image_gen": s.stamp.image_gen,
            "cost_ms": s.cost.ms,
            // The GPU's total and passes over the last frames timed:
            // [q25, median, q75] ms; in a page, how late they were read.
            "gpu_ms": gpu_spreads(&s.cost),
            // The lesson's counters for the variant shown, as the report's.
            "counters": self.running.as_ref().map(|r| r.lesson.counters(self.variants[s.current])),
            "gpu_frames": s.cost.gpu.len(),
            "gpu_read_late": s.cost.late.map(|(late, _)| late),
            "timestamp_quantum_ns": s.cost.late.map(|(_, q)| q),
            "fps": s.cost.fps,
            "error": answer,
            "error_current": shown.as_ref().is_some_and(|e| !e.stale),
            "adapter": self.adapter_line,
            "rss_kb": rss_kb(),
            "overlay_px": overlay,
        });
        // A page shows the line to its scripts (the web check reads it).
        #[cfg(target_arch = "wasm32")]
        self.page.publish(&line);
        let Some(log) = self.log.as_mut() else {
            return Ok(());
        };
        writeln!(log, "{line}").context("--window-log: cannot write")
    }
}

/// Every GPU key's `[q25, median, q75]` over the frames the overlay keeps.
fn gpu_spreads(cost: &super::overlay::Cost) -> serde_json::Value {
    let keys = cost.gpu.back().into_iter().flat_map(|f| f.keys());
    let spreads = keys.filter_map(|k| Some((k.clone(), cost.gpu_spread(k)?.to_vec())));
    serde_json::json!(spreads.collect::<std::collections::BTreeMap<_, _>>())
}

/// This process's resident memory (Linux), for the log.
fn rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find_map(|l| l.strip_prefix("VmRSS:"))?;
    line.trim().trim_end_matches("kB").trim().parse().ok()
}
