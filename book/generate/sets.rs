//! Records made on other adapters: `workbook book --adapter NAME` (or
//! `--backend gl`) measures every run of the manifest there and writes the
//! records and tables under `book/src/generated/sets/<adapter>-<backend>/`,
//! leaving the book's own set (lavapipe, Vulkan) as it is. Each chapter
//! then shows the other sets' tables beside lavapipe's
//! (`generated/<lesson>/results_other_adapters.md`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use crate::manifest::{self, RUNS};
use crate::record::Record;

/// The folder of the other sets, under `book/src/generated/`.
pub const SETS_DIR: &str = "sets";

/// Whether `--adapter` and `--backend` make the book's own set.
pub fn is_main(adapter: &str, backend: &str) -> bool {
    adapter == manifest::ADAPTER && backend == manifest::BACKEND
}

/// A set's folder name: the adapter's name and the backend, in lower case,
/// runs of other characters made one `-`
/// (`NVIDIA H100 80GB HBM3`, `Vulkan` → `nvidia-h100-80gb-hbm3-vulkan`).
pub fn slug(adapter: &str, backend: &str) -> String {
    let mut s = String::new();
    for c in format!("{adapter} {backend}").chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_matches('-').to_string()
}

/// The folder a set's records go to.
pub fn set_dir(generated: &Path, adapter: &str, backend: &str) -> PathBuf {
    generated.join(SETS_DIR).join(slug(adapter, backend))
}

/// Every committed other set: its folder name and the records it has.
pub fn load_sets(generated: &Path) -> Result<Vec<(String, Vec<Record>)>> {
    let dir = generated.join(SETS_DIR);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Ok(Vec::new());
    };
    let mut names: Vec<String> = entries
        .flatten()
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    let mut sets = Vec::new();
    for name in names {
        let mut records = Vec::new();
        for r in RUNS {
            let path = dir
                .join(&name)
                .join(r.lesson)
                .join(format!("{}.json", r.name));
            if let Ok(text) = std::fs::read_to_string(&path) {
                let rec: Record = serde_json::from_str(&text)
                    .with_context(|| format!("{}: not a record", path.display()))?;
                records.push(rec);
            }
        }
        sets.push((name, records));
    }
    Ok(sets)
}

/// Each lesson's `results_other_adapters.md`: the default run's table of
/// every other set, or how to make one.
pub fn write_other_adapters(generated: &Path, sets: &[(String, Vec<Record>)]) -> Result<()> {
    let mut lessons: Vec<&str> = RUNS.iter().map(|r| r.lesson).collect();
    lessons.dedup();
    for lesson in lessons {
        let mean_abs = manifest::MEAN_ABS_LESSONS.contains(&lesson);
        let tables: Vec<String> = sets
            .iter()
            .filter_map(|(_, records)| {
                records
                    .iter()
                    .find(|r| r.lesson == lesson && r.run == "results")
            })
            .map(|r| {
                Ok(format!(
                    "**{} ({})**\n\n{}",
                    r.adapter,
                    r.backend,
                    r.table(mean_abs)?
                ))
            })
            .collect::<Result<_>>()?;
        let text = if tables.is_empty() && !sets.is_empty() {
            let names: Vec<&str> = sets.iter().map(|(n, _)| n.as_str()).collect();
            format!(
                "*The committed sets of other adapters ({}) have no run of this lesson.*\n",
                names.join(", ")
            )
        } else if tables.is_empty() {
            format!(
                "*Only lavapipe's records are committed. On a GPU, `cargo run --release --bin workbook -- book --adapter any` measures every run there and writes its set to `book/src/generated/{SETS_DIR}/<adapter>-<backend>/`; its table then appears here, beside lavapipe's.*\n"
            )
        } else {
            tables.join("\n")
        };
        let path = generated.join(lesson).join("results_other_adapters.md");
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_names_come_from_the_adapter_and_backend() {
        assert_eq!(
            slug("NVIDIA H100 80GB HBM3", "Vulkan"),
            "nvidia-h100-80gb-hbm3-vulkan"
        );
        assert_eq!(
            slug("llvmpipe (LLVM 15.0.6, 256 bits)", "Gl"),
            "llvmpipe-llvm-15-0-6-256-bits-gl"
        );
        assert!(is_main("software", "vulkan"));
        assert!(!is_main("software", "gl") && !is_main("any", "vulkan"));
    }
}
