//! The scene depth formats the negative controls run in (`--depth-format`):
//! the adapter's default, and `Depth24PlusStencil8` forced, which is a real
//! 24-bit buffer where the driver has D24_UNORM_S8 (lavapipe and llvmpipe
//! do) and 32-bit float where it does not. Each run's report.json says
//! which format the scene used and what it stored (`adapter.depth_format`,
//! `adapter.depth_storage`, measured by `common::gpu::depth_probe`).

#![allow(dead_code)]

/// `--depth-format` values: the default, then 24-bit forced.
pub const DEPTH_FORMATS: [&str; 2] = ["auto", "depth24plus-stencil8"];

/// `["--depth-format", format]`, to append to a lesson's arguments.
pub fn flag(format: &str) -> [&str; 2] {
    ["--depth-format", format]
}

/// The run's scene depth format and storage (`"unorm24"`, `"float32"`, or
/// `"unknown"` where the probe could not tell), checked against what was
/// asked: a forced format is the one used. A criterion that depends on the
/// storage asks for a known one ([`step_near_one`]).
pub fn used(report: &serde_json::Value, asked: &str) -> (String, String) {
    let a = &report["adapter"];
    let format = a["depth_format"].as_str().unwrap_or("").to_string();
    let storage = a["depth_storage"].as_str().unwrap_or("").to_string();
    match asked {
        "depth24plus-stencil8" => assert_eq!(format, "Depth24PlusStencil8"),
        "depth32float-stencil8" => assert_eq!(format, "Depth32FloatStencil8"),
        _ => assert!(format.starts_with("Depth"), "depth_format {format:?}"),
    }
    assert!(
        !storage.is_empty(),
        "{format}: report.json has no depth_storage"
    );
    (format, storage)
}

/// One storage step of depth just below z = 1, where standard depth puts
/// everything beyond a few times the near plane: 1/(2²⁴ − 1) for 24-bit
/// unorm, 2⁻²⁴ for float32 (its spacing in [0.5, 1)). Nearly the same, so
/// standard depth is as coarse there in either format.
pub fn step_near_one(storage: &str) -> f64 {
    match storage {
        "unorm24" => 1.0 / 16_777_215.0,
        "float32" => 2f64.powi(-24),
        other => panic!(
            "the depth probe could not tell what the buffer stores ({other:?}): no criterion"
        ),
    }
}
