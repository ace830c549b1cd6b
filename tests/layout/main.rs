//! The layout rules of the workbook, checked on the source tree, one
//! module of this test for each:
//!
//! - [`lesson_order`]: a lesson uses an earlier lesson's technique, never
//!   a later one's (`workbook::lesson_MM`, `crate::lesson_MM` or
//!   `shaders/lesson_MM/` with MM > NN, in any file of
//!   `lessons/lesson_NN/`);
//! - [`crates`]: every library and binary of the workspace lies in a crate
//!   that the next two rules check (`CRATES`: common, the lessons, the
//!   grader, the book's generator, the tests' support, the web build);
//! - [`cycles`]: there are no import cycles between the modules of any of
//!   those crates;
//! - [`sizes`]: no source file of those crates is over 500 lines;
//! - [`module_lists`]: `common/src/lib.rs` and each folder's `mod.rs` list
//!   every module they have, in their docs too;
//! - [`single_lesson`]: no module of `common/` serves a single lesson (used
//!   by exactly one lesson folder and by no other module of `common/`);
//! - [`untested_bins`]: no binary built with `test = false` (the lessons',
//!   the generator's) holds a unit test, which would never run.
//!
//! Pure std: the checks read the files as text. Each checker is first run
//! on in-memory text, so a broken checker cannot pass by finding nothing.
//! Here is what they share: the files of a folder, and the module a file
//! is.

use std::fs;
use std::path::{Path, PathBuf};

mod crates;
mod cycles;
mod lesson_order;
mod module_lists;
mod single_lesson;
mod sizes;
mod untested_bins;

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file below `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

fn read(p: &Path) -> String {
    fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The module a file of a crate's folder `src` is, by Rust's rules: `a.rs`
/// and `a/mod.rs` are `a`; `a/b.rs` is `a::b` when an `a.rs` or an
/// `a/mod.rs` declares it. `common/src/scene/mesh.rs` → `scene::mesh`,
/// `lessons/lesson_05/stencil.rs` → `lesson_05::stencil`,
/// `book/generate/gpu_costs/costs.rs` → `gpu_costs::costs`. None for a
/// crate's root (`root`, and every `main.rs`) and for a file of a folder
/// that is no module (the unit tests a `#[path]` names, `bin/`).
fn module_name(path: &Path, src: &Path, root: &str) -> Option<String> {
    let rel = path.strip_prefix(src).ok()?;
    if rel == Path::new(root) || rel.file_name()? == "main.rs" {
        return None;
    }
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    let mut dir = src.to_path_buf();
    for folder in &parts[..parts.len() - 1] {
        let declared =
            dir.join(format!("{folder}.rs")).exists() || dir.join(folder).join("mod.rs").exists();
        if !declared {
            return None;
        }
        dir.push(folder);
    }
    if parts.last().is_some_and(|m| m == "mod") {
        parts.pop();
    }
    Some(parts.join("::"))
}
