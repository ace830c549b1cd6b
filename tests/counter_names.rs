//! Counters are a type: each is defined once, with its name, unit and
//! legend, in `common/src/measure/counters.rs`, and every other Rust file
//! names it by its constant (`DRAWS.name`), so that renaming a counter
//! fails to compile instead of failing later in a snapshot or a table.
//!
//! This test reads every Rust file of the workspace and fails on a string
//! literal equal to a counter's name outside its definition. A literal
//! that means something else (a knob, an anchor, a unit of the same
//! spelling) says so on its line: `// not a counter: what it is`.
//!
//! The web check's `.ci/web/check.mjs` spells its counters' classes in
//! JavaScript, which cannot import them; `tests/snapshot_tolerance.rs`
//! checks its table against `tests/support/tolerance.rs`'s, which uses the
//! constants.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::measure::counters::{self, Counter};

/// Where the definitions are: the one file that spells the names.
const DEFINITION: &str = "common/src/measure/counters.rs";

/// The mark on a line whose literal is not a counter.
const NOT_A_COUNTER: &str = "// not a counter:";

/// The workspace's folders that hold Rust sources.
const SOURCE_DIRS: &[&str] = &[
    "lessons",
    "common",
    "book/generate",
    "grade",
    "web",
    "tests",
    "solutions",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The lines of `text` that spell one of `names` as a string literal
/// (`"draws"`), outside comments and unmarked: (line number, name).
fn literal_names(text: &str, names: &[&str]) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.contains(NOT_A_COUNTER) {
            continue;
        }
        let code = line.split("//").next().unwrap_or("");
        for name in names {
            if code.contains(&format!("\"{name}\"")) {
                found.push((i + 1, name.to_string()));
            }
        }
    }
    found
}

#[test]
fn the_scanner_finds_a_counter_literal() {
    let (draws, taps) = (counters::DRAWS.name, counters::TAPS.name);
    let names = [draws, taps];
    let q = |s: &str| format!("\"{s}\"");
    let text = format!(
        "c.insert({}.into(), 1);\n\
         c.set(DRAWS, 1); // was {}\n\
         knob({}) {NOT_A_COUNTER} a knob\n\
         let s = {};\n",
        q(draws),
        q(draws),
        q(taps),
        q(&format!("{draws}x")),
    );
    assert_eq!(literal_names(&text, &names), [(1, draws.to_string())]);
}

#[test]
fn every_counter_is_listed_once() {
    let definition = std::fs::read_to_string(root().join(DEFINITION)).unwrap();
    let defined = definition.matches(": Counter = Counter {").count();
    assert!(defined >= 40, "found {defined} counter definitions");
    assert_eq!(
        counters::ALL.len(),
        defined,
        "counters::ALL lists every one"
    );
    let names: BTreeSet<&str> = counters::ALL.iter().map(|c| c.name).collect();
    assert_eq!(names.len(), defined, "the names are unique");
    for c in counters::ALL {
        assert_eq!(Counter::named(c.name), Some(*c));
        assert!(!c.unit.is_empty() && !c.legend.is_empty(), "{}", c.name);
    }
}

#[test]
fn no_file_spells_a_counter_name() {
    let names: Vec<&str> = counters::ALL.iter().map(|c| c.name).collect();
    let mut files = Vec::new();
    for dir in SOURCE_DIRS {
        rust_files(&root().join(dir), &mut files);
    }
    assert!(files.len() >= 200, "found {} Rust files", files.len());
    let definition = root().join(DEFINITION);
    let mut spelled = Vec::new();
    for f in files.iter().filter(|f| **f != definition) {
        let text = std::fs::read_to_string(f).unwrap();
        for (line, name) in literal_names(&text, &names) {
            let rel = f.strip_prefix(root()).unwrap_or(f).display().to_string();
            spelled.push(format!("{rel}:{line}: \"{name}\""));
        }
    }
    assert!(
        spelled.is_empty(),
        "counter names spelt as strings outside {DEFINITION} (use its constant, \
         e.g. DRAWS.name, or mark a literal that is not a counter with \
         `{NOT_A_COUNTER} what it is`):\n{}",
        spelled.join("\n")
    );
}
