//! No binary built with `test = false` (the lessons', the generator's)
//! holds a unit test, which `cargo test` would never run.

use std::path::{Path, PathBuf};

use crate::{read, repo_root};

/// The `path` of every `[[bin]]` of a Cargo.toml that sets `test = false`.
fn untested_bins(manifest: &str) -> Vec<String> {
    let mut out = Vec::new();
    for block in manifest.split("[[bin]]").skip(1) {
        // The block ends at the next table header.
        let block: Vec<&str> = block
            .lines()
            .skip(1)
            .take_while(|l| !l.trim_start().starts_with('['))
            .map(str::trim)
            .collect();
        if !block.contains(&"test = false") {
            continue;
        }
        if let Some(path) = block.iter().find_map(|l| l.strip_prefix("path = ")) {
            out.push(path.trim_matches('"').to_string());
        }
    }
    out
}

/// A binary's files: its `main.rs` and the modules it declares (`mod x;`,
/// `x.rs` beside it).
fn bin_files(main: &Path, text: &str) -> Vec<PathBuf> {
    let dir = main.parent().expect("a folder");
    let mut out = vec![main.to_path_buf()];
    for l in text.lines() {
        let l = l
            .trim()
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub ");
        if let Some(name) = l.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
            out.push(dir.join(format!("{name}.rs")));
        }
    }
    out
}

/// The lines (1-based) of `text` that declare a unit test.
fn test_attributes(text: &str) -> Vec<usize> {
    (text.lines().enumerate())
        .filter(|(_, l)| {
            let l = l.trim();
            l.starts_with("#[test]") || l.starts_with("#[cfg(test)]")
        })
        .map(|(i, _)| i + 1)
        .collect()
}

#[test]
fn untested_bin_checker_works() {
    let manifest = "[[bin]]\nname = \"a\"\npath = \"a/main.rs\"\ntest = false\n\n\
                    [[bin]]\nname = \"b\"\npath = \"b/main.rs\"\n\n[features]\ntest = false\n";
    assert_eq!(untested_bins(manifest), ["a/main.rs"]);
    let main = "use x;\nmod harness;\npub(crate) mod view;\nfn main() {}\n";
    let files = bin_files(Path::new("l/main.rs"), main);
    assert_eq!(
        files,
        [
            PathBuf::from("l/main.rs"),
            PathBuf::from("l/harness.rs"),
            PathBuf::from("l/view.rs")
        ]
    );
    assert_eq!(
        test_attributes("fn a() {}\n  #[test]\nfn b() {}\n#[cfg(test)]\n"),
        [2, 4]
    );
}

/// The lesson binaries and the generator's are built with `test = false`
/// (Cargo.toml, book/generate/Cargo.toml): `cargo test` would otherwise
/// compile each again as an empty test harness. A
/// unit test written in one of their files would then never run, so none
/// may hold one: the lesson's tests go in the library (`lessons/`) or in
/// `tests/`.
#[test]
fn no_untested_binary_holds_a_unit_test() {
    let root = repo_root();
    // Each manifest's binaries, by their path from the repository's root.
    let mut bins = Vec::new();
    for dir in ["", "book/generate"] {
        let manifest = read(&root.join(dir).join("Cargo.toml"));
        bins.extend(
            untested_bins(&manifest)
                .into_iter()
                .map(|b| root.join(dir).join(b)),
        );
    }
    assert!(
        bins.len() >= 11,
        "{bins:?}: the ten lessons and the generator at least"
    );
    let mut found = Vec::new();
    for main in &bins {
        for f in bin_files(main, &read(main)) {
            for line in test_attributes(&read(&f)) {
                found.push(format!("{}:{line}", f.display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "a unit test in a binary that `cargo test` does not build as a test (Cargo.toml: test = false), so it never runs; move it to the library or to tests/:\n{}",
        found.join("\n")
    );
}
