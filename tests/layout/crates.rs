//! The workspace's crates, which the cycle and size rules check
//! ([`CRATES`]), and the check that every library and binary of the
//! workspace lies in one of them.

use std::path::{Path, PathBuf};

use crate::{module_name, read, repo_root, rust_files};

/// Every crate of the workspace, for the cycle and size rules: (the folder
/// of its sources, its root file there, the fewest modules a correct scan
/// of it finds, so that a scan broken into finding nothing fails). Every
/// `main.rs` is a binary's root too: the lessons' (`lesson_NN/main.rs`),
/// the generator's `workbook` beside its library. Each root of the
/// workspace's targets lies in one of these folders
/// (`every_target_is_in_a_checked_crate`).
pub(crate) const CRATES: &[(&str, &str, usize)] = &[
    // common: its folders' roots are `mod.rs`.
    ("common/src", "lib.rs", 50),
    // The root package's library (the lessons) and the lesson binaries.
    ("lessons", "lib.rs", 80),
    // The root package's `grade` binary.
    ("grade", "main.rs", 3),
    // workbook-generator: its library and the `workbook` binary; its
    // folders' roots are the `x.rs` beside them (`plots/mod.rs` aside).
    ("book/generate", "lib.rs", 70),
    // workbook-test-support, what the tests share.
    ("tests/support", "mod.rs", 10),
    // workbook-web: its root alone, which takes the lesson binaries by
    // `#[path]` (their files are the lessons' folder's).
    ("web", "lib.rs", 0),
];

/// The roots of a workspace member's targets: the `path` of each `[lib]`
/// and `[[bin]]` of its Cargo.toml (`manifest`, in folder `dir`), and
/// Cargo's own where it names none (`src/lib.rs`, `src/bin/*.rs`).
fn target_roots(dir: &Path, manifest: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut in_target = false;
    for l in manifest.lines().map(str::trim) {
        if l.starts_with('[') {
            in_target = l == "[lib]" || l == "[[bin]]";
        } else if let Some(p) = l.strip_prefix("path = ").filter(|_| in_target) {
            out.push(dir.join(p.trim_matches('"')));
        }
    }
    if !manifest.contains("[lib]") && dir.join("src/lib.rs").exists() {
        out.push(dir.join("src/lib.rs"));
    }
    out.extend(rust_files(&dir.join("src/bin")));
    out
}

/// The workspace's members, from the root Cargo.toml's `members = [...]`.
fn workspace_members(manifest: &str) -> Vec<String> {
    let list = manifest
        .split("members = [")
        .nth(1)
        .and_then(|r| r.split(']').next())
        .unwrap_or("");
    list.split(',')
        .map(|m| m.trim().trim_matches('"').to_string())
        .filter(|m| !m.is_empty())
        .collect()
}

/// Every library and binary of the workspace has its root in a folder of
/// [`CRATES`], as a root there (not a file the scan takes for a module).
#[test]
fn every_target_is_in_a_checked_crate() {
    let root = repo_root();
    let members = workspace_members(&read(&root.join("Cargo.toml")));
    assert!(members.len() >= 5, "{members:?}");
    let mut targets = Vec::new();
    for m in &members {
        let dir = root.join(m);
        let found = target_roots(&dir, &read(&dir.join("Cargo.toml")));
        assert!(!found.is_empty(), "{m}: no library or binary found");
        targets.extend(found);
    }
    assert!(targets.len() >= 16, "{targets:?}");
    let outside: Vec<String> = (targets.iter())
        .filter(|t| {
            !CRATES.iter().any(|(dir, crate_root, _)| {
                let dir = root.join(dir);
                t.starts_with(&dir) && module_name(t, &dir, crate_root).is_none()
            })
        })
        .map(|t| t.display().to_string())
        .collect();
    assert!(
        outside.is_empty(),
        "crate roots that CRATES (tests/layout/crates.rs) does not check:\n{}",
        outside.join("\n")
    );
}
