//! No measured number typed in the book's sentences. Fails, with the file
//! and line, when:
//!
//! - a sentence quotes a measured-looking figure (a percentage, a time, a
//!   size in bytes, a ratio `×1.68`, a decimal with two or more places, a
//!   count with thousands groups `74 784`) that is not in that chapter's
//!   generated output (the `book/src/generated/` files it includes). A
//!   figure a run made belongs in a marker the generator fills
//!   (`<!--fig:RUN:VARIANT:FIELD-->…<!--/fig-->`, see
//!   `book/generate/prose.rs`); a figure no run made (a pass criterion, a
//!   constant from another renderer) is listed on a comment above its
//!   paragraph: `<!-- not measured: 0.5 %, 1 % (the tests' criteria) -->`;
//! - a marker's value is not what its record says today (the generator
//!   was not run after the records changed).
//!
//! Pure std and the generator's own modules; no GPU. The scanner is tested
//! on in-memory text first.

use generator::prose;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Characters that group thousands or join a number to its unit.
fn is_space(c: char) -> bool {
    matches!(c, ' ' | '\u{2009}' | '\u{a0}' | '\u{202f}')
}

/// Units after which a number reads as measured.
const UNITS: &[&str] = &["%", "ms", "µs", "ns", "s", "KiB", "MiB", "GiB", "MB", "GB"];

/// Every number in `text`, as `(digits without groups or sign, measured-looking)`.
fn numbers(text: &str) -> Vec<(String, bool)> {
    let c: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let starts = c[i].is_ascii_digit()
            && (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_' || c[i - 1] == '.'));
        if !starts {
            i += 1;
            continue;
        }
        let start = i;
        let mut digits = String::new();
        while i < c.len() && c[i].is_ascii_digit() {
            digits.push(c[i]);
            i += 1;
        }
        let mut grouped = false;
        // Thousands groups: a head of 1-3 digits, then groups of exactly 3.
        while digits.len() <= 3 || grouped {
            let three = i + 4 <= c.len()
                && is_space(c[i])
                && c[i + 1..i + 4].iter().all(|d| d.is_ascii_digit())
                && (i + 4 == c.len() || !c[i + 4].is_ascii_digit());
            if !three {
                break;
            }
            digits.extend(&c[i + 1..i + 4]);
            grouped = true;
            i += 4;
        }
        let mut places = 0;
        if i + 1 < c.len() && c[i] == '.' && c[i + 1].is_ascii_digit() {
            digits.push('.');
            i += 1;
            while i < c.len() && c[i].is_ascii_digit() {
                digits.push(c[i]);
                places += 1;
                i += 1;
            }
        }
        // Part of a path, a DOI or a fraction (`10.1145/…`, `1/2`): not a figure.
        if (start > 0 && c[start - 1] == '/') || c.get(i) == Some(&'/') {
            continue;
        }
        let before: String = c[start.saturating_sub(2)..start].iter().collect();
        let ratio = before.contains('×');
        let mut j = i;
        if j < c.len() && is_space(c[j]) {
            j += 1;
        }
        let rest: String = c[j..c.len().min(j + 4)].iter().collect();
        let unit = UNITS.iter().any(|u| {
            rest.starts_with(u)
                && rest[u.len()..]
                    .chars()
                    .next()
                    .is_none_or(|n| !n.is_alphanumeric())
        }) || rest.starts_with('×');
        out.push((digits, unit || ratio || places >= 2 || grouped));
    }
    out
}

/// `line` without inline code, math, HTML comments and tags, link targets
/// and filled markers: what a reader reads as prose.
fn readable(line: &str) -> String {
    let mut s = line.to_string();
    // Filled markers first: their values are checked against the records.
    while let Some(a) = s.find(prose::OPEN) {
        match s[a..].find(prose::CLOSE) {
            Some(b) => s.replace_range(a..a + b + prose::CLOSE.len(), " "),
            None => break,
        }
    }
    for (open, close) in [
        ("<!--", "-->"),
        ("`", "`"),
        ("$$", "$$"),
        ("$", "$"),
        ("](", ")"),
        ("<", ">"),
    ] {
        let mut out = String::new();
        let mut rest = s.as_str();
        while let Some(a) = rest.find(open) {
            out.push_str(&rest[..a]);
            match rest[a + open.len()..].find(close) {
                Some(b) => {
                    out.push(' ');
                    if open == "](" {
                        out.push(']');
                    }
                    rest = &rest[a + open.len() + b + close.len()..];
                }
                None => {
                    rest = &rest[a..];
                    break;
                }
            }
        }
        out.push_str(rest);
        s = out;
    }
    s
}

/// `markdown` with every HTML comment that spans lines (a claim that
/// wraps, `book/generate/claims.rs`) blanked, its line breaks kept: a
/// reader reads none of it.
fn blank_wrapped_comments(markdown: &str) -> String {
    let mut out = String::with_capacity(markdown.len());
    let mut rest = markdown;
    while let Some(a) = rest.find("<!--") {
        let Some(b) = rest[a..].find("-->") else {
            break;
        };
        let comment = &rest[a..a + b + 3];
        out.push_str(&rest[..a]);
        if comment.contains('\n') {
            out.extend(comment.chars().map(|c| if c == '\n' { '\n' } else { ' ' }));
        } else {
            out.push_str(comment);
        }
        rest = &rest[a + b + 3..];
    }
    out.push_str(rest);
    out
}

/// `(line, figure)` for every measured-looking figure in the prose of
/// `markdown` that is not in `known` (the numbers of its generated output)
/// and not listed by a `<!-- not measured: ... -->` comment above its paragraph.
fn unsourced(markdown: &str, known: &BTreeSet<String>) -> Vec<(usize, String)> {
    let markdown = &blank_wrapped_comments(markdown);
    let mut found = Vec::new();
    let mut fenced = false;
    let mut exempt: BTreeSet<String> = BTreeSet::new();
    for (n, line) in markdown.lines().enumerate() {
        let t = line.trim();
        if t.starts_with("```") || t.starts_with("~~~") {
            fenced = !fenced;
            continue;
        }
        if fenced || t.starts_with('|') || t.starts_with("{{#") {
            continue;
        }
        if t.is_empty() {
            exempt.clear();
            continue;
        }
        if let Some(at) = t.find("<!-- not measured:") {
            let note = &t[at..];
            exempt.extend(numbers(note).into_iter().map(|(d, _)| d));
            continue;
        }
        for (digits, measured) in numbers(&readable(line)) {
            if measured && !known.contains(&digits) && !exempt.contains(&digits) {
                found.push((n + 1, digits));
            }
        }
    }
    found
}

/// The numbers of every generated file `chapter` includes, or shows a
/// view of (`<!--view: SOURCE`, a path under `book/src/generated/`).
fn generated_numbers(chapter: &Path, text: &str) -> BTreeSet<String> {
    let dir = chapter.parent().expect("chapter folder");
    let mut known = BTreeSet::new();
    for piece in text.split("<!--view:").skip(1) {
        let source = piece.split_whitespace().next().unwrap_or("");
        let path = root().join("book/src/generated").join(source);
        if let Ok(g) = fs::read_to_string(path) {
            known.extend(numbers(&g).into_iter().map(|(d, _)| d));
        }
    }
    for piece in text.split("{{#include ").skip(1) {
        let Some(end) = piece.find("}}") else {
            continue;
        };
        let path = piece[..end].split(':').next().unwrap_or("").trim();
        if !path.contains("generated/") {
            continue;
        }
        if let Ok(g) = fs::read_to_string(dir.join(path)) {
            known.extend(numbers(&g).into_iter().map(|(d, _)| d));
        }
    }
    known
}

/// The book's pages (not the generated files), sorted.
fn chapters() -> Vec<PathBuf> {
    prose::chapters(&root().join("book/src")).expect("book/src")
}

fn rel(p: &Path) -> String {
    p.strip_prefix(root()).unwrap_or(p).display().to_string()
}

#[test]
fn the_scanner_finds_what_it_looks_for() {
    let n = |s: &str| numbers(s);
    assert_eq!(n("misclassify 1.863 % of"), vec![("1.863".into(), true)]);
    assert_eq!(n("costs +17.1 ms more"), vec![("17.1".into(), true)]);
    assert_eq!(n("sends 74 784 triangles"), vec![("74784".into(), true)]);
    assert_eq!(n("×1.68 the baseline"), vec![("1.68".into(), true)]);
    assert_eq!(n("a 2.5× wider"), vec![("2.5".into(), true)]);
    assert_eq!(n("0.056 of a pixel"), vec![("0.056".into(), true)]);
    assert_eq!(n("in 76 s"), vec![("76".into(), true)]);
    // Not measured-looking: counts, names, one decimal place.
    assert_eq!(
        n("lesson 05 has 3 variants"),
        vec![("05".into(), false), ("3".into(), false)]
    );
    assert!(n("res_1024 and k4").is_empty());
    assert_eq!(
        n("tan 85° is 11.4"),
        vec![("85".into(), false), ("11.4".into(), false)]
    );
    assert_eq!(n("5 steps"), vec![("5".into(), false)]);
    assert!(n("doi:10.1145/37402 and 1/2").is_empty());
    // What a reader does not read as prose is left out.
    assert_eq!(
        readable("`1.863 %` and $0.05$ <!-- 3.14 % -->"),
        "  and    "
    );
    let marked = format!("{}k:v:f-->1.889 %{} here", prose::OPEN, prose::CLOSE);
    assert!(numbers(&readable(&marked)).is_empty());
    // A figure in the generated output passes; others fail, unless exempt.
    let known: BTreeSet<String> = ["1.889".to_string()].into();
    let text = "clamp misclassifies 1.889 % and infinite 1.449 %.\n";
    assert_eq!(unsourced(text, &known), vec![(1, "1.449".to_string())]);
    let exempt =
        "<!-- not measured: 1.449 % (a criterion) -->\ninfinite 1.449 %.\n\nagain 1.449 %\n";
    assert_eq!(unsourced(exempt, &known), vec![(4, "1.449".to_string())]);
    assert!(unsourced("```\n1.449 %\n```\n| 1.449 % |\n", &known).is_empty());
    // A comment that wraps (a claim) is not prose, on any of its lines.
    let wrapped = "a<!--claim: r:a:f > 0.95 * r:b:f;\n  r:a:f < 1.05 * r:b:f-->.\nthen 1.449 %\n";
    assert_eq!(unsourced(wrapped, &known), vec![(3, "1.449".to_string())]);
}

#[test]
fn markers_are_filled_from_their_records() {
    let text = format!("a {}r:v:f-->old{} b", prose::OPEN, prose::CLOSE);
    let filled = prose::fill(&text, &mut |k| Ok(format!("[{k}]"))).expect("fills");
    assert_eq!(
        filled,
        format!("a {}r:v:f-->[r:v:f]{} b", prose::OPEN, prose::CLOSE)
    );
    let open = format!("a {}r:v:f-->1 %\nb", prose::OPEN);
    assert!(prose::fill(&open, &mut |_| Ok(String::new())).is_err());
}

#[test]
fn no_sentence_quotes_a_measured_figure_by_hand() {
    let mut errors = Vec::new();
    for ch in chapters() {
        let text = fs::read_to_string(&ch).expect("chapter");
        let known = generated_numbers(&ch, &text);
        for (n, figure) in unsourced(&text, &known) {
            errors.push(format!("{}:{n}: {figure}", rel(&ch)));
        }
    }
    assert!(
        errors.is_empty(),
        "figures typed into sentences that are not in the chapter's generated output ({}): \
         write a measured one as a marker the generator fills \
         (`<!--fig:RUN:VARIANT:FIELD-->…<!--/fig-->`, book/generate/prose.rs), or list one no run \
         made on `<!-- not measured: FIGURES (why) -->` above its paragraph:\n  {}",
        errors.len(),
        errors.join("\n  ")
    );
}

#[test]
fn every_marker_holds_its_records_value() {
    let generated = root().join("book/src/generated");
    let mut errors = Vec::new();
    for ch in chapters() {
        let text = fs::read_to_string(&ch).expect("chapter");
        if !text.contains(prose::OPEN) {
            continue;
        }
        match prose::fill(&text, &mut |k| prose::lookup(&generated, k)) {
            Err(e) => errors.push(format!("{}: {e:#}", rel(&ch))),
            Ok(filled) if filled != text => {
                let line = text
                    .lines()
                    .zip(filled.lines())
                    .position(|(a, b)| a != b)
                    .map_or(0, |i| i + 1);
                errors.push(format!(
                    "{}:{line}: a marker's value is not its record's; run `cargo run --release --bin workbook -- tables`",
                    rel(&ch)
                ));
            }
            Ok(_) => {}
        }
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}
