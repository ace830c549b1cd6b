//! No source file of a crate of [`CRATES`] is over [`MAX_LINES`] lines.

use crate::crates::CRATES;
use crate::{read, repo_root, rust_files};

const MAX_LINES: usize = 500;

/// `path: N lines` for each of `files` (path, text) over [`MAX_LINES`].
fn long_files(files: &[(String, String)]) -> Vec<String> {
    (files.iter())
        .map(|(path, text)| (path, text.lines().count()))
        .filter(|(_, n)| *n > MAX_LINES)
        .map(|(path, n)| format!("{path}: {n} lines"))
        .collect()
}

#[test]
fn size_checker_works() {
    let files = [
        ("long.rs".to_string(), "x\n".repeat(MAX_LINES + 1)),
        ("full.rs".to_string(), "x\n".repeat(MAX_LINES)),
        ("empty.rs".to_string(), String::new()),
    ];
    assert_eq!(
        long_files(&files),
        [format!("long.rs: {} lines", MAX_LINES + 1)]
    );
}

#[test]
fn no_source_file_is_over_500_lines() {
    let root = repo_root();
    let mut files = Vec::new();
    for &(dir, _, min_modules) in CRATES {
        let found = rust_files(&root.join(dir));
        assert!(
            found.len() > min_modules,
            "{dir}: expected {} files at least, found {}",
            min_modules + 1,
            found.len()
        );
        for p in found {
            let rel = p.strip_prefix(&root).unwrap_or(&p).display().to_string();
            files.push((rel, read(&p)));
        }
    }
    let long = long_files(&files);
    assert!(
        long.is_empty(),
        "over {MAX_LINES} lines:\n{}",
        long.join("\n")
    );
}
