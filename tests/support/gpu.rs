//! The adapter the tests run on ([`test_adapter`], [`test_gpu`]), what
//! happens without one ([`gpu_required`]), and whether a snapshot's run
//! measures its figures' bounds there ([`measure_bounds`]).

use crate::tolerance;

/// Called when a lesson found no adapter. A GPU test without a GPU proves
/// nothing, so by default the test FAILS here, with the line that says
/// what to install. Only with `WORKBOOK_ALLOW_NO_GPU=1` does it return
/// `false`, and the caller skips with a loud `SKIPPED` line.
pub fn gpu_required() -> bool {
    if std::env::var("WORKBOOK_ALLOW_NO_GPU").is_ok_and(|v| v == "1") {
        return false;
    }
    panic!(
        "no GPU adapter found: on Linux without a GPU driver, install Mesa's software \
         rasterisers (`apt-get install -y mesa-vulkan-drivers libgl1-mesa-dri libegl1`); \
         Windows (DX12, Vulkan) and macOS (Metal) use their GPU; \
         WORKBOOK_ALLOW_NO_GPU=1 skips the GPU tests instead, and then they prove nothing"
    );
}

/// The adapter the tests run the lessons on: `any` (your GPU, else a
/// software rasteriser), unless `WORKBOOK_ADAPTER` says otherwise. CI pins
/// `software` (lavapipe/llvmpipe) for determinism; the snapshots hold on
/// either, within the tolerances of [`crate::tolerance`].
pub fn test_adapter() -> String {
    std::env::var("WORKBOOK_ADAPTER")
        .ok()
        .filter(|v| !v.trim().is_empty())
        .unwrap_or_else(|| "any".into())
}

/// A device on [`test_adapter`], for the tests that drive the GPU
/// themselves; `None` (the test returns, having said `SKIPPED`) only where
/// [`gpu_required`] allows it.
pub fn test_gpu() -> Option<common::gpu::Gpu> {
    match common::gpu::Gpu::new(None, Some(&test_adapter()), None) {
        Ok(gpu) => Some(gpu),
        Err(e) if !gpu_required() => {
            eprintln!("SKIPPED: {e}");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

/// Whether a snapshot's run measures its figures' bounds (`--fragile`):
/// only on an adapter the committed snapshots were recorded on (their
/// first line, `adapter: NAME (BACKEND)`: CI's lavapipe on Vulkan). There
/// the new text must equal the committed one, bounds and all, so the run
/// measures them again. On any other adapter (llvmpipe on GL, a
/// student's GPU) a figure may move by the committed run's bound and the
/// new run's own bound is never read (`tolerance::compare`: a broken
/// technique cannot widen its own tolerance), so the run leaves out the
/// moved draws, most of a snapshot's time: lesson 08's default scene at
/// 320×180 took 11.6 s without them, 52.7 s with them (lavapipe,
/// 2026-12-04). The adapter is recognised by that line alone (its name as
/// the driver gives it, and the backend). `WORKBOOK_FRAGILE=1` in the
/// tests' environment measures them on any adapter (printed there, never
/// compared); any other value leaves the rule as it is.
pub fn measure_bounds() -> bool {
    use std::sync::OnceLock;
    static HERE: OnceLock<bool> = OnceLock::new();
    *HERE.get_or_init(|| {
        let forced = std::env::var("WORKBOOK_FRAGILE").map(|v| v.trim().to_ascii_lowercase());
        if forced.is_ok_and(|v| v == "1" || v == "true") {
            return true;
        }
        // No adapter: measure, and let the run fail the way it must.
        let Ok(gpu) = common::gpu::Gpu::new(None, Some(&test_adapter()), None) else {
            return true;
        };
        let here = format!(
            "{}{} ({})",
            tolerance::ADAPTER_PREFIX,
            gpu.adapter_name(),
            gpu.backend_name()
        );
        tolerance::recorded_adapters().contains(&here)
    })
}
