//! The adapter a snapshot was recorded on: its first line
//! ([`adapter_line`]), the adapters of the committed snapshots
//! ([`recorded_adapters`]), and [`AS_ELSEWHERE`], which compares as
//! another adapter would.

use crate::paths::root;

/// The line that names the adapter a text was recorded on
/// (`adapter: llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)`): [`adapter_line`].
pub const ADAPTER_PREFIX: &str = "adapter: ";

/// The first line of a snapshot: the adapter and backend of the run.
pub fn adapter_line(report: &serde_json::Value) -> String {
    let a = &report["adapter"];
    format!(
        "{ADAPTER_PREFIX}{} ({})\n",
        a["name"].as_str().unwrap_or("?"),
        a["backend"].as_str().unwrap_or("?")
    )
}

/// Set (to anything), the comparison is the one another adapter gets,
/// even on the snapshot's own: `.ci/snapshot-mutations` shows with it that
/// a broken technique fails the bounds, not only the exact comparison.
pub const AS_ELSEWHERE: &str = "WORKBOOK_SNAPSHOT_AS_ELSEWHERE";

/// The adapter lines (without their newline) of the committed snapshots,
/// `tests/snapshots/*.snap`: the adapters they were recorded on.
pub fn recorded_adapters() -> std::collections::BTreeSet<String> {
    let dir = root().join("tests/snapshots");
    let entries = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .flatten();
    entries
        .filter(|e| e.path().extension().is_some_and(|x| x == "snap"))
        .filter_map(|e| std::fs::read_to_string(e.path()).ok())
        .filter_map(|t| adapter_of(&t).map(str::to_string))
        .collect()
}

/// The adapter line of a text, if it has one.
pub(super) fn adapter_of(text: &str) -> Option<&str> {
    text.lines().find(|l| l.starts_with(ADAPTER_PREFIX))
}
