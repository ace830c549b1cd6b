//! A chapter is a reader's path; the full records are one link away.
//! Fails, naming the page, when:
//!
//! - a lesson chapter or the choosing chapter has more than [`WORDS`] words
//!   on its reader's path, or the introduction more than [`INTRO_WORDS`];
//! - one of them shows more than [`TABLES`] tables, or a table wider than
//!   [`COLS`] columns or longer than [`ROWS`] rows;
//! - a generated table (`book/src/generated/`) is shown on no page of the
//!   book: a table a chapter drops goes to its lesson's record page
//!   (`lesson_NN_records.md`), where the drift and claim tests still read it;
//! - a lesson has no record page in `SUMMARY.md`, or its chapter does not
//!   link to it.
//!
//! Counted as `../shared/hooks/reader_path.py` counts: the generated
//! tables a page includes are expanded (two levels), HTML comments are
//! dropped; words are those outside `<details>` and outside code blocks;
//! tables are counted wherever they are, folded into `<details>` or not (a
//! folded table is still a table on the page).
//!
//! Pure std, no GPU. The counter is tested on in-memory text first.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

/// A chapter's words on its reader's path, at most.
const WORDS: usize = 6500;
/// The introduction's, at most.
const INTRO_WORDS: usize = 2500;
/// Tables on a chapter's page, at most.
const TABLES: usize = 4;
/// A table's columns, at most.
const COLS: usize = 7;
/// A table's rows (not its heading and rule), at most.
const ROWS: usize = 12;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn src() -> PathBuf {
    root().join("book/src")
}

/// The pages the budget holds: the introduction, the lessons, the choosing.
fn budgeted() -> Vec<String> {
    let mut v = vec!["introduction.md".to_string()];
    v.extend((1..=10).map(|n| format!("lesson_{n:02}.md")));
    v.push("choosing.md".into());
    v
}

/// `text` with every line that is only `{{#include X.md}}` replaced by that
/// file (relative to `dir`), `depth` more levels down.
fn expand(text: &str, dir: &Path, depth: usize) -> String {
    let mut out = Vec::new();
    for line in text.split('\n') {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix("{{#include ") {
            if let Some(path) = rest.split("}}").next() {
                if depth > 0 && path.ends_with(".md") && !path.contains(':') {
                    let p = dir.join(path);
                    if let Ok(inner) = fs::read_to_string(&p) {
                        let parent = p.parent().unwrap_or(dir).to_path_buf();
                        out.push(expand(&inner, &parent, depth - 1));
                        continue;
                    }
                }
            }
        }
        out.push(line.to_string());
    }
    out.join("\n")
}

/// `text` without the spans from `open` to `close` (non-greedy).
fn strip(text: &str, open: &str, close: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(a) = rest.find(open) {
        let Some(b) = rest[a + open.len()..].find(close) else {
            break;
        };
        out.push_str(&rest[..a]);
        rest = &rest[a + open.len() + b + close.len()..];
    }
    out.push_str(rest);
    out
}

/// What one page weighs on its reader's path.
#[derive(Debug, PartialEq)]
struct Weight {
    words: usize,
    /// (columns, rows) of every table.
    tables: Vec<(usize, usize)>,
}

fn weigh(expanded: &str) -> Weight {
    let full = strip(expanded, "<!--", "-->");
    let mut tables = Vec::new();
    let mut current: Option<(usize, usize)> = None;
    for line in full.split('\n') {
        if line.trim_start().starts_with('|') {
            current = Some(match current {
                None => {
                    let cols = line.trim().trim_matches('|').split('|').count();
                    (cols, 0)
                }
                Some((c, n)) => (c, n + 1),
            });
        } else if let Some((c, n)) = current.take() {
            tables.push((c, n.saturating_sub(1)));
        }
    }
    if let Some((c, n)) = current {
        tables.push((c, n.saturating_sub(1)));
    }
    let path = strip(&full, "<details>", "</details>");
    let words = strip(&path, "```", "```").split_whitespace().count();
    Weight { words, tables }
}

/// What is over budget on a page, in words; empty when none is.
fn over_budget(w: &Weight, word_limit: usize) -> Vec<String> {
    let mut over = Vec::new();
    if w.words > word_limit {
        over.push(format!("{} words > {word_limit}", w.words));
    }
    if w.tables.len() > TABLES {
        over.push(format!("{} tables > {TABLES}", w.tables.len()));
    }
    for (i, &(c, r)) in w.tables.iter().enumerate() {
        if c > COLS {
            over.push(format!("table {} has {c} columns > {COLS}", i + 1));
        }
        if r > ROWS {
            over.push(format!("table {} has {r} rows > {ROWS}", i + 1));
        }
    }
    over
}

#[test]
fn the_counter_counts_what_a_reader_reads() {
    let page = "One two three.\n\n<!-- a comment of many words here -->\n\
                ```rust\nlet code = not_words;\n```\n\
                <details><summary>Folded</summary>\n\nmany folded words\n\n\
                | a | b |\n| --- | --- |\n| 1 | 2 |\n\n</details>\n\n\
                | x | y | z |\n| --- | --- | --- |\n| 1 | 2 | 3 |\n| 4 | 5 | 6 |\n";
    let w = weigh(page);
    // "One two three." and the unfolded table's 3 + 3 + 3 + 3 cells and pipes.
    assert_eq!(w.tables, vec![(2, 1), (3, 2)]);
    let table_words = "| x | y | z |\n| --- | --- | --- |\n| 1 | 2 | 3 |\n| 4 | 5 | 6 |"
        .split_whitespace()
        .count();
    assert_eq!(w.words, 3 + table_words);
    assert!(over_budget(&w, w.words).is_empty());
    assert!(over_budget(&w, w.words - 1)[0].contains("words"));
    // A table wider than COLS, or longer than ROWS, is over.
    let wide = format!(
        "| {} |\n|{}\n| {} |\n",
        ["h"; COLS + 1].join(" | "),
        " --- |".repeat(COLS + 1),
        ["1"; COLS + 1].join(" | ")
    );
    assert!(over_budget(&weigh(&wide), WORDS)[0].contains("columns"));
    let long = format!("| a |\n| --- |\n{}", "| 1 |\n".repeat(ROWS + 1));
    assert!(over_budget(&weigh(&long), WORDS)[0].contains("rows"));
    let many = "| a |\n| --- |\n| 1 |\n\n".repeat(TABLES + 1);
    assert!(over_budget(&weigh(&many), WORDS)[0].contains("tables"));
}

#[test]
fn includes_expand_two_levels_and_stop() {
    let dir = std::env::temp_dir().join(format!("reader_path_{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    fs::write(dir.join("a.md"), "alpha\n{{#include b.md}}\n").unwrap();
    fs::write(dir.join("b.md"), "beta\n{{#include c.md}}\n").unwrap();
    fs::write(dir.join("c.md"), "gamma\n").unwrap();
    let got = expand("top\n{{#include a.md}}\n", &dir, 2);
    assert!(got.contains("alpha") && got.contains("beta"), "{got}");
    assert!(
        got.contains("{{#include c.md}}") && !got.contains("gamma"),
        "{got}"
    );
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn every_chapter_is_within_its_reader_path_budget() {
    let mut failures = Vec::new();
    let mut lines = Vec::new();
    for ch in budgeted() {
        let p = src().join(&ch);
        let text = fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let w = weigh(&expand(&text, &src(), 2));
        let limit = if ch == "introduction.md" {
            INTRO_WORDS
        } else {
            WORDS
        };
        let over = over_budget(&w, limit);
        lines.push(format!(
            "{ch}: {} words, {} tables",
            w.words,
            w.tables.len()
        ));
        if !over.is_empty() {
            failures.push(format!("book/src/{ch}: {}", over.join("; ")));
        }
    }
    println!("{}", lines.join("\n"));
    assert!(
        failures.is_empty(),
        "over the reader's-path budget (at most {WORDS} words, {INTRO_WORDS} for the \
         introduction; {TABLES} tables of at most {COLS} columns and {ROWS} rows): move the \
         full tables to the lesson's record page and show a view \
         (`<!--view: ...-->`, book/generate/views.rs):\n  {}",
        failures.join("\n  ")
    );
}

/// The pages `SUMMARY.md` links, relative to `book/src`.
fn summary_pages() -> Vec<String> {
    let text = fs::read_to_string(src().join("SUMMARY.md")).expect("SUMMARY.md");
    let mut pages = Vec::new();
    for piece in text.split("](").skip(1) {
        if let Some(end) = piece.find(')') {
            let p = &piece[..end];
            if p.ends_with(".md") {
                pages.push(p.to_string());
            }
        }
    }
    pages
}

/// Every file a page includes, transitively, as paths under `book/src`.
fn included(page: &Path, seen: &mut BTreeSet<PathBuf>) {
    let Ok(text) = fs::read_to_string(page) else {
        return;
    };
    let dir = page.parent().expect("a page's folder");
    for piece in text.split("{{#include ").skip(1) {
        let Some(end) = piece.find("}}") else {
            continue;
        };
        let path = piece[..end].split(':').next().unwrap_or("").trim();
        let p = normalise(&dir.join(path));
        if seen.insert(p.clone()) && path.ends_with(".md") {
            included(&p, seen);
        }
    }
}

fn normalise(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

#[test]
fn every_generated_table_is_on_a_page() {
    let mut shown = BTreeSet::new();
    for page in summary_pages() {
        included(&normalise(&src().join(&page)), &mut shown);
    }
    let generated = src().join("generated");
    let mut missing = Vec::new();
    let mut stack = vec![generated.clone()];
    while let Some(dir) = stack.pop() {
        for e in fs::read_dir(&dir).expect("generated folder") {
            let p = e.expect("entry").path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "md") {
                let text = fs::read_to_string(&p).unwrap_or_default();
                let is_table = text.lines().any(|l| l.trim_start().starts_with('|'));
                if is_table && !shown.contains(&normalise(&p)) {
                    missing.push(p.strip_prefix(src()).unwrap_or(&p).display().to_string());
                }
            }
        }
    }
    missing.sort();
    assert!(
        missing.is_empty(),
        "generated tables that no page of SUMMARY.md shows; include each on its lesson's \
         record page (`lesson_NN_records.md`) or the page it belongs to:\n  {}",
        missing.join("\n  ")
    );
}

#[test]
fn every_lesson_has_a_record_page_its_chapter_links() {
    let pages = summary_pages();
    let mut failures = Vec::new();
    for n in 1..=10 {
        let records = format!("lesson_{n:02}_records.md");
        if !pages.contains(&records) {
            failures.push(format!("SUMMARY.md does not list {records}"));
        }
        let chapter = fs::read_to_string(src().join(format!("lesson_{n:02}.md"))).unwrap();
        if !chapter.contains(&format!("]({records}")) {
            failures.push(format!("lesson_{n:02}.md does not link to {records}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
