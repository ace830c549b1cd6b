//! Reading the book's markdown as mdBook does: its `{{#include ..}}`
//! directives and line ranges, anchor markers, images, links and
//! SUMMARY.md's entries, and paths resolved without the disk.

use std::path::{Component, Path, PathBuf};

/// Which part of an included file a directive asks for.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Part {
    Whole,
    /// `PATH:10:20`, `PATH:10`, `PATH::20`, `PATH:10:`: line numbers,
    /// nothing to check. As mdbook reads them: `start` is 0-based, `end`
    /// exclusive (so `PATH:10:20` is lines 10 to 20 counted from 1, and
    /// `PATH:10` is line 10 alone).
    Lines {
        start: usize,
        end: Option<usize>,
    },
    Anchor(String),
}

/// One `{{#include ..}}`-style directive in a chapter.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Directive {
    pub(crate) kind: String,
    pub(crate) path: String,
    pub(crate) part: Part,
    /// 1-based line in the chapter.
    pub(crate) line: usize,
    pub(crate) text: String,
}

/// Finds mdbook's link directives, as mdbook does: `{{#kind args}}` with
/// optional blanks after `{{`; a backslash before `{{#` escapes it. mdbook
/// expands them inside code blocks too (that is how listings work), so code
/// blocks are not skipped here.
pub(crate) fn parse_directives(markdown: &str) -> Vec<Directive> {
    let mut found = Vec::new();
    let bytes = markdown.as_bytes();
    let mut i = 0;
    while let Some(offset) = markdown[i..].find("{{") {
        let start = i + offset;
        let Some(close) = markdown[start..].find("}}").map(|c| start + c) else {
            break;
        };
        i = close + 2;
        if start > 0 && bytes[start - 1] == b'\\' {
            continue; // `\{{#include ..}}` is shown literally
        }
        let inner = markdown[start + 2..close].trim_start();
        let Some(inner) = inner.strip_prefix('#') else {
            continue;
        };
        let kind: String = inner
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        let args = &inner[kind.len()..];
        if !matches!(kind.as_str(), "include" | "rustdoc_include" | "playground") {
            continue;
        }
        if !args.starts_with(char::is_whitespace) || args.contains('}') {
            continue; // not a directive mdbook would expand
        }
        // The first blank-separated word is the file argument; the rest are
        // properties (`editable` for playground).
        let file_arg = args.split_whitespace().next().unwrap_or("");
        let mut pieces = file_arg.splitn(2, ':');
        let path = pieces.next().unwrap_or("").to_string();
        let part = match (kind.as_str(), pieces.next()) {
            ("playground", _) | (_, None) => Part::Whole,
            (_, Some(sel)) => {
                let mut bounds = sel.splitn(3, ':');
                let first = bounds.next().unwrap_or("");
                if first.is_empty() || first.parse::<usize>().is_ok() {
                    line_range(first, bounds.next())
                } else {
                    Part::Anchor(first.to_string())
                }
            }
        };
        found.push(Directive {
            kind,
            path,
            part,
            line: 1 + markdown[..start].matches('\n').count(),
            text: markdown[start..close + 2].to_string(),
        });
    }
    found
}

/// mdbook's line range after `PATH:`: `first` is the text before the
/// second colon, `second` what follows it (`None` when there is no second
/// colon). A start alone is that one line; an end that is not a number
/// runs to the end of the file.
fn line_range(first: &str, second: Option<&str>) -> Part {
    let start = first.parse::<usize>().ok().map(|n| n.saturating_sub(1));
    let end = second.map(|s| s.parse::<usize>().ok());
    match (start, end) {
        (Some(start), Some(end)) => Part::Lines { start, end },
        (Some(start), None) => Part::Lines {
            start,
            end: Some(start + 1),
        },
        (None, Some(end)) => Part::Lines { start: 0, end },
        (None, None) => Part::Lines {
            start: 0,
            end: None,
        },
    }
}

/// The anchor name that follows `marker` on a line, if any (mdbook's
/// `ANCHOR:\s*([\w_-]+)`).
pub(crate) fn anchor_names<'a>(line: &'a str, marker: &str) -> Vec<&'a str> {
    let mut names = Vec::new();
    let mut rest = line;
    while let Some(at) = rest.find(marker) {
        let after = rest[at + marker.len()..].trim_start();
        let end = after
            .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '-'))
            .unwrap_or(after.len());
        if end > 0 {
            names.push(&after[..end]);
        }
        rest = &rest[at + marker.len()..];
    }
    names
}

/// Lines of markdown outside fenced code blocks, with inline code removed:
/// an image or link shown as code is not a real one.
pub(crate) fn prose_lines(markdown: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fence: Option<&str> = None;
    for (n, line) in markdown.lines().enumerate() {
        let t = line.trim_start();
        let marker = ["```", "~~~"].into_iter().find(|m| t.starts_with(m));
        if let Some(m) = marker {
            match fence {
                None => fence = Some(m),
                Some(open) if open == m => fence = None,
                Some(_) => {}
            }
            continue;
        }
        if fence.is_some() {
            continue;
        }
        // Drop `inline code`.
        let mut kept = String::new();
        for (k, piece) in line.split('`').enumerate() {
            if k % 2 == 0 {
                kept.push_str(piece);
            }
        }
        out.push((n + 1, kept));
    }
    out
}

/// The target of a markdown link or image starting right after `](`:
/// `path`, `path "title"` or `<path with spaces>`.
pub(crate) fn link_target(after_paren: &str) -> Option<String> {
    let s = after_paren.trim_start();
    let target = if let Some(rest) = s.strip_prefix('<') {
        &rest[..rest.find('>')?]
    } else {
        let end = s.find(|c: char| c == ')' || c.is_whitespace())?;
        &s[..end]
    };
    Some(target.to_string())
}

/// `(line, target)` of every `![alt](target)` and `<img src="target">`.
pub(crate) fn image_targets(markdown: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (line, text) in prose_lines(markdown) {
        let mut rest = text.as_str();
        while let Some(at) = rest.find("![") {
            rest = &rest[at + 2..];
            let Some(close) = rest.find("](") else { break };
            if let Some(target) = link_target(&rest[close + 2..]) {
                found.push((line, target));
            }
            rest = &rest[close + 2..];
        }
        let mut rest = text.as_str();
        while let Some(at) = rest.find("<img") {
            rest = &rest[at + 4..];
            let Some(src) = rest.find("src=") else { break };
            let value = &rest[src + 4..];
            let quote = value.chars().next().filter(|c| *c == '"' || *c == '\'');
            if let Some(q) = quote {
                if let Some(end) = value[1..].find(q) {
                    found.push((line, value[1..1 + end].to_string()));
                }
            }
        }
    }
    found
}

/// `(line, target)` of every `[title](target)` link in SUMMARY.md.
pub(crate) fn summary_links(summary: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (line, text) in prose_lines(summary) {
        let mut rest = text.as_str();
        while let Some(at) = rest.find("](") {
            if let Some(target) = link_target(&rest[at + 2..]) {
                found.push((line, target));
            } else {
                found.push((line, String::new())); // `[Draft]()`
            }
            rest = &rest[at + 2..];
        }
    }
    found
}

/// Removes `#fragment` and `?query` from a local link.
pub(crate) fn strip_fragment(target: &str) -> &str {
    let end = target.find(['#', '?']).unwrap_or(target.len());
    &target[..end]
}

/// Resolves `.` and `..` without touching the disk.
pub(crate) fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

// ---------------------------------------------------------------------------
// The parser's own test, on in-memory text
// ---------------------------------------------------------------------------

#[test]
fn parser_finds_directives_as_mdbook_does() {
    let md = "# T\n\
              ```rust\n\
              {{#include ../../lessons/lesson_01.rs:shadow_pass}}\n\
              ```\n\
              {{ #rustdoc_include ../x.rs:3:9 }} and {{#include a.wgsl}}\n\
              \\{{#include escaped.rs:not_me}}\n\
              {{#playground demo.rs editable}} {{#title Not a file}}\n";
    let found = parse_directives(md);
    let got: Vec<(&str, &str, Part, usize)> = found
        .iter()
        .map(|d| (d.kind.as_str(), d.path.as_str(), d.part.clone(), d.line))
        .collect();
    assert_eq!(
        got,
        vec![
            (
                "include",
                "../../lessons/lesson_01.rs",
                Part::Anchor("shadow_pass".into()),
                3
            ),
            (
                "rustdoc_include",
                "../x.rs",
                Part::Lines {
                    start: 2,
                    end: Some(9)
                },
                5
            ),
            ("include", "a.wgsl", Part::Whole, 5),
            ("playground", "demo.rs", Part::Whole, 7),
        ]
    );
}
