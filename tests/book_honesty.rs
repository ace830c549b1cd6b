//! The book shows only what runs made, and shows it readably. Fails, with
//! the file and line, when:
//!
//! - a chapter (or the README outside its generated block) has a table with
//!   a measured-looking number in a cell (a decimal, a percentage, a time)
//!   that is not included from `book/src/generated/`. A table of derived,
//!   not measured, numbers says so on the line above it:
//!   `<!-- not measured: why -->`. A view of a generated table
//!   (`<!--view: ...-->`, checked by `tests/book_views.rs`) is generated;
//! - a figure is shown without a visible caption: every image must be an
//!   `<img>` inside a `<figure>` with a `<figcaption>` (mdBook shows the alt
//!   text of `![alt](src)` only when the image fails to load);
//! - a file under `book/src/figures/` is used by no chapter, or a figure the
//!   generator's manifest writes is missing.
//!
//! Pure std, no GPU. The checkers are tested on in-memory text first.

use generator::manifest;

use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Lines outside fenced code blocks, numbered from 1.
fn prose(markdown: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut fenced = false;
    for (n, line) in markdown.lines().enumerate() {
        if line.trim_start().starts_with("```") || line.trim_start().starts_with("~~~") {
            fenced = !fenced;
            continue;
        }
        if !fenced {
            out.push((n + 1, line));
        }
    }
    out
}

/// Does a table cell look like a measurement: `0.056`, `48 %`, `12 ms`,
/// `1.2 M`? Counts and names (`5`, `res_256`, `1024²`) do not.
fn looks_measured(cell: &str) -> bool {
    let c: String = cell.replace(['*', '`'], "");
    let b = c.as_bytes();
    let decimal = (1..b.len().saturating_sub(1))
        .any(|i| b[i] == b'.' && b[i - 1].is_ascii_digit() && b[i + 1].is_ascii_digit());
    let unit = |u: &str| {
        c.match_indices(u).any(|(i, _)| {
            c[..i]
                .trim_end()
                .chars()
                .last()
                .is_some_and(|ch| ch.is_ascii_digit())
        })
    };
    decimal || unit("%") || unit("ms")
}

/// `(line, text)` of every hand-written table row with a measured cell.
fn hand_typed_measurements(markdown: &str) -> Vec<(usize, String)> {
    let lines = prose(markdown);
    let mut found = Vec::new();
    let mut exempt = false;
    let mut previous = "";
    let mut view = false;
    for (n, line) in &lines {
        let t = line.trim();
        // A view of a generated table (`<!--view: ...-->` ... `<!--/view-->`,
        // book/generate/views.rs) is the generator's, checked by
        // tests/book_views.rs.
        if t.starts_with("<!--view:") {
            view = true;
        }
        if t.starts_with("<!--/view-->") || t.ends_with("<!--/view-->") {
            view = false;
        }
        if view {
            previous = line;
            continue;
        }
        if t.starts_with('|') {
            if !previous.trim().starts_with('|') {
                // A table starts: exempt only if the line above says so.
                exempt = previous.trim().starts_with("<!-- not measured:");
            }
            if !exempt && t.split('|').skip(1).any(looks_measured) {
                found.push((*n, t.to_string()));
            }
        }
        previous = line;
    }
    found
}

/// `(line, message)` for every image not inside a captioned `<figure>`.
fn uncaptioned_figures(markdown: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut figure: Option<(usize, bool, bool)> = None; // start, has img, has caption
    for (n, line) in prose(markdown) {
        if line.contains("![") && line.contains("](") {
            found.push((n, "a markdown image: write it as <figure><img ...><figcaption>...</figcaption></figure>".into()));
        }
        if line.contains("<figure") {
            figure = Some((n, false, false));
        }
        let has_img = line.contains("<img");
        if has_img && figure.is_none() {
            found.push((n, "an <img> outside a <figure>".into()));
        }
        if let Some(f) = figure.as_mut() {
            f.1 |= has_img;
            f.2 |= line.contains("<figcaption>") && !line.contains("<figcaption></figcaption>");
        }
        if line.contains("</figure>") {
            if let Some((start, img, cap)) = figure.take() {
                if img && !cap {
                    found.push((start, "a <figure> without a <figcaption>".into()));
                }
            }
        }
    }
    found
}

/// The `src` of every `<img>`.
fn img_sources(markdown: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (_, line) in prose(markdown) {
        let mut rest = line;
        while let Some(at) = rest.find("src=\"") {
            rest = &rest[at + 5..];
            if let Some(end) = rest.find('"') {
                out.push(rest[..end].to_string());
                rest = &rest[end..];
            }
        }
    }
    out
}

/// The book's chapters (not the generated tables), sorted.
fn chapters() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![root().join("book/src")];
    while let Some(d) = stack.pop() {
        for e in fs::read_dir(&d).expect("book/src").flatten() {
            let p = e.path();
            if p.is_dir() && !p.ends_with("generated") && !p.ends_with("katex") {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "md")
                && !p.starts_with(root().join("book/src/figures"))
            {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

fn rel(p: &Path) -> String {
    p.strip_prefix(root()).unwrap_or(p).display().to_string()
}

#[test]
fn checkers_find_what_they_look_for() {
    assert!(looks_measured(" 0.056 "));
    assert!(looks_measured(" **12 %** "));
    assert!(looks_measured(" 38.5 [31.5–43.3] "));
    assert!(looks_measured(" 3 ms "));
    assert!(!looks_measured(" `res_256` "));
    assert!(!looks_measured(" 5 "));
    assert!(!looks_measured(" lesson_05.toml "));
    let t = "text\n\n| a | b |\n|---|---|\n| x | 1.5 |\n";
    assert_eq!(hand_typed_measurements(t).len(), 1);
    let ok = "<!-- not measured: derived -->\n| a | b |\n|---|---|\n| x | 1.5 |\n";
    assert!(hand_typed_measurements(ok).is_empty());
    let fenced = "```\n| x | 1.5 |\n```\n";
    assert!(hand_typed_measurements(fenced).is_empty());
    assert_eq!(uncaptioned_figures("![a](b.png)\n").len(), 1);
    assert_eq!(
        uncaptioned_figures("<figure>\n<img src=\"b.png\">\n</figure>\n").len(),
        1
    );
    let good = "<figure>\n<img src=\"b.png\" alt=\"a\">\n<figcaption>Look at the edge.</figcaption>\n</figure>\n";
    assert!(uncaptioned_figures(good).is_empty());
    assert_eq!(img_sources(good), vec!["b.png".to_string()]);
}

#[test]
fn no_chapter_has_a_hand_typed_table_of_measurements() {
    let mut errors = Vec::new();
    for ch in chapters() {
        let text = fs::read_to_string(&ch).expect("chapter");
        for (n, row) in hand_typed_measurements(&text) {
            errors.push(format!("{}:{n}: {row}", rel(&ch)));
        }
    }
    let readme = fs::read_to_string(root().join("README.md")).expect("README.md");
    let outside: String = match (
        readme.find("<!-- results:begin"),
        readme.find("<!-- results:end"),
    ) {
        (Some(a), Some(b)) => format!("{}{}", &readme[..a], &readme[b..]),
        _ => readme.clone(),
    };
    for (n, row) in hand_typed_measurements(&outside) {
        errors.push(format!(
            "README.md (outside the results block), table line {n}: {row}"
        ));
    }
    assert!(
        errors.is_empty(),
        "measured numbers typed into tables by hand ({}); include the generated table instead ({{{{#include generated/...}}}}), or mark a table of derived numbers with `<!-- not measured: why -->` on the line above:\n  {}",
        errors.len(),
        errors.join("\n  ")
    );
}

#[test]
fn every_figure_has_a_visible_caption() {
    let mut errors = Vec::new();
    for ch in chapters() {
        let text = fs::read_to_string(&ch).expect("chapter");
        for (n, why) in uncaptioned_figures(&text) {
            errors.push(format!("{}:{n}: {why}", rel(&ch)));
        }
    }
    assert!(
        errors.is_empty(),
        "figures without a caption:\n  {}",
        errors.join("\n  ")
    );
}

#[test]
fn every_figure_file_is_used_and_every_generated_figure_exists() {
    let src = root().join("book/src");
    let mut used = std::collections::BTreeSet::new();
    for ch in chapters() {
        let text = fs::read_to_string(&ch).expect("chapter");
        let dir = ch.parent().expect("chapter folder").to_path_buf();
        for s in img_sources(&text) {
            used.insert(dir.join(s));
        }
        // Included files (a lesson's own generated table, say) count as used.
        for piece in text.split("{{#include ").skip(1) {
            if let Some(end) = piece.find("}}") {
                let path = piece[..end].split(':').next().unwrap_or("").trim();
                used.insert(dir.join(path));
            }
        }
    }
    let mut errors = Vec::new();
    let mut stack = vec![src.join("figures")];
    while let Some(d) = stack.pop() {
        for e in fs::read_dir(&d).expect("figures").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if !used.contains(&p) {
                errors.push(format!(
                    "{} is used by no chapter: delete it, or show it",
                    rel(&p)
                ));
            }
        }
    }
    for f in manifest::FIGURES {
        let p = src.join("figures").join(f.dest);
        if !p.exists() {
            errors.push(format!(
                "{} is missing: run `cargo run --release --bin workbook -- book`",
                rel(&p)
            ));
        }
    }
    for u in &used {
        if !u.exists() {
            errors.push(format!("{} is shown but missing", rel(u)));
        }
    }
    assert!(
        errors.is_empty(),
        "figures out of step with the book:\n  {}",
        errors.join("\n  ")
    );
}
