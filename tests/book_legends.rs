//! Every column of every generated table is defined where the table is
//! read. Fails, naming the file and the column, when a table under
//! `book/src/generated/` has a column that the legend under it (the
//! `<details><summary>What each column means</summary>` block the
//! generator writes, `book/generate/legend.rs`) does not define, or a
//! definition that is empty.
//!
//! Pure std, no GPU. The checker is tested on in-memory text first.

use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The line that opens a legend.
const LEGEND: &str = "<details><summary>What each column means</summary>";

/// The cells of a markdown table row (`\|` is a literal bar inside a cell).
fn cells(row: &str) -> Vec<String> {
    let t = row.trim().trim_start_matches('|').trim_end_matches('|');
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut chars = t.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\\' && chars.peek() == Some(&'|') {
            cur.push_str("\\|");
            chars.next();
        } else if c == '|' {
            out.push(cur.trim().to_string());
            cur.clear();
        } else {
            cur.push(c);
        }
    }
    out.push(cur.trim().to_string());
    out
}

/// `(line, column)` for every column of every table in `text` that the
/// legend after it (before the next table) does not define.
fn undefined(text: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i + 1 < lines.len() {
        let is_table = lines[i].trim_start().starts_with('|')
            && lines[i + 1].trim_start().starts_with("| ---")
            && (i == 0 || !lines[i - 1].trim_start().starts_with('|'));
        if !is_table {
            i += 1;
            continue;
        }
        let head = cells(lines[i]);
        // The legend: after the table's rows, before the next table.
        let mut j = i + 2;
        while j < lines.len() && lines[j].trim_start().starts_with('|') {
            j += 1;
        }
        let mut defined: Vec<(String, String)> = Vec::new();
        let mut k = j;
        let mut inside = false;
        while k < lines.len() {
            let l = lines[k].trim();
            if l.starts_with('|') && !inside {
                break;
            }
            if l == LEGEND {
                inside = true;
            } else if l == "</details>" && inside {
                break;
            } else if inside {
                if let Some((name, def)) = l.strip_prefix("- ").and_then(|d| d.split_once(": ")) {
                    defined.push((name.to_string(), def.trim().to_string()));
                }
            }
            k += 1;
        }
        for c in head {
            if !defined.iter().any(|(n, d)| *n == c && !d.is_empty()) {
                found.push((i + 1, c));
            }
        }
        i = j;
    }
    found
}

fn generated_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in fs::read_dir(dir).expect("generated").flatten() {
        let p = e.path();
        if p.is_dir() {
            generated_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "md") {
            out.push(p);
        }
    }
}

#[test]
fn the_checker_finds_undefined_columns() {
    let table =
        "| variant | misclassified % | mean \\|ΔV\\| % |\n| --- | --- | --- |\n| `a` | 1 | 2 |\n";
    assert_eq!(
        cells("| a | b \\| c |"),
        vec!["a".to_string(), "b \\| c".to_string()]
    );
    assert_eq!(undefined(table).len(), 3);
    let legend = format!(
        "{table}\n{LEGEND}\n\n- variant: the variant\n- misclassified %: wrong pixels\n- mean \\|ΔV\\| %: mean error\n\n</details>\n"
    );
    assert!(undefined(&legend).is_empty());
    let empty = legend.replace(": wrong pixels", ": ");
    assert_eq!(undefined(&empty), vec![(1, "misclassified %".to_string())]);
    // A second table does not borrow the first one's legend.
    let two = format!("{legend}\n| other |\n| --- |\n| 1 |\n");
    assert_eq!(undefined(&two), vec![(13, "other".to_string())]);
}

#[test]
fn every_generated_column_is_defined_under_its_table() {
    let mut files = Vec::new();
    generated_files(&root().join("book/src/generated"), &mut files);
    files.sort();
    let mut errors = Vec::new();
    for f in &files {
        let text = fs::read_to_string(f).expect("generated file");
        for (line, column) in undefined(&text) {
            errors.push(format!(
                "{}:{line}: {column}",
                f.strip_prefix(root()).unwrap_or(f).display()
            ));
        }
    }
    assert!(
        errors.is_empty(),
        "columns with no definition in the legend under their table ({}); define them in book/generate/legend.rs (or the table's writer) and run `cargo run --release --bin workbook -- tables`:\n  {}",
        errors.len(),
        errors.join("\n  ")
    );
}
