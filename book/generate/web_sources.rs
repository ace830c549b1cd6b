//! What the web module (`workbook web`) is built from, and their digest:
//! `book/src/web/SOURCES` holds it, and `tests/web.rs` (through the
//! generator's library) fails when the sources' digest is no longer the one the committed
//! module was built from.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use sha2::{Digest, Sha256};

/// The files and folders the module is built from: a change to any of
/// them means `workbook web` again.
pub const INPUTS: &[&str] = &[
    "Cargo.toml",
    "Cargo.lock",
    ".cargo",
    "common",
    "lessons",
    "shaders",
    "scenes",
    "solutions",
    "tests/chapter_copies",
    "web",
];

/// The digest of [`INPUTS`]: every file's path and contents, in path
/// order, with line endings as `\n` (a checkout on Windows digests alike).
pub fn digest(root: &Path) -> Result<String> {
    let mut files = Vec::new();
    for input in INPUTS {
        collect(&root.join(input), &mut files)?;
    }
    files.sort();
    let mut hash = Sha256::new();
    for f in files {
        let rel = f.strip_prefix(root).unwrap_or(&f);
        let text = std::fs::read(&f).with_context(|| format!("cannot read {}", f.display()))?;
        let text: Vec<u8> = text.into_iter().filter(|&b| b != b'\r').collect();
        hash.update(rel.to_string_lossy().replace('\\', "/").as_bytes());
        hash.update([0]);
        hash.update((text.len() as u64).to_le_bytes());
        hash.update(&text);
    }
    Ok(format!("{:x}", hash.finalize()))
}

fn collect(path: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    // An input a tree lacks adds nothing (its path is in the digest once it has it).
    if !path.exists() {
        return Ok(());
    }
    if path.is_file() {
        out.push(path.to_path_buf());
        return Ok(());
    }
    let entries =
        std::fs::read_dir(path).with_context(|| format!("cannot list {}", path.display()))?;
    for e in entries {
        let p = e?.path();
        // Build outputs never: only what a clone holds.
        if p.file_name().is_some_and(|n| n == "target") {
            continue;
        }
        collect(&p, out)?;
    }
    Ok(())
}
