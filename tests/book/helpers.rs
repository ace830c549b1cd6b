//! Shared helpers: the files the checkers read (the repository on disk, or
//! in-memory files for the checkers' own tests), the book's markdown files,
//! and the failure message.

use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};

use crate::parse::normalize;

/// What the checker needs from a file system, so that it can be tested on
/// in-memory files as well as on the real repository.
pub(crate) trait Files {
    /// `None` when the file does not exist or is not text.
    fn read(&self, path: &Path) -> Option<String>;
    fn exists(&self, path: &Path) -> bool;
}

/// The repository on disk; paths are relative to its root.
pub(crate) struct Disk(pub(crate) PathBuf);

impl Files for Disk {
    fn read(&self, path: &Path) -> Option<String> {
        fs::read_to_string(self.0.join(path)).ok()
    }
    fn exists(&self, path: &Path) -> bool {
        self.0.join(path).is_file()
    }
}

/// In-memory files, for the checker's own tests.
pub(crate) struct Memory(pub(crate) HashMap<PathBuf, String>);

impl Files for Memory {
    fn read(&self, path: &Path) -> Option<String> {
        self.0.get(&normalize(path)).cloned()
    }
    fn exists(&self, path: &Path) -> bool {
        self.0.contains_key(&normalize(path))
    }
}

/// Every `.md` file under `dir`, sorted.
pub(crate) fn markdown_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let entries =
            fs::read_dir(&d).unwrap_or_else(|e| panic!("cannot read {}: {e}", d.display()));
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

pub(crate) fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub(crate) fn fail_with(errors: &[String], what: &str) {
    assert!(
        errors.is_empty(),
        "{what}: {} problem(s):\n  {}\n",
        errors.len(),
        errors.join("\n  ")
    );
}
