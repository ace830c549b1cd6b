//! The book must not drift from the code. This test reads `book/src/` and
//! fails, with the file and line, when:
//!
//! - an `{{#include PATH}}`, `{{#include PATH:ANCHOR}}`, `{{#rustdoc_include ..}}`
//!   or `{{#playground ..}}` names a file that does not exist (PATH is
//!   relative to the chapter), or an ANCHOR that the file does not open with
//!   `ANCHOR: name` and close with `ANCHOR_END: name`;
//! - an image `![..](path)` or `<img src="..">` points to a missing file;
//! - `SUMMARY.md` links a missing file;
//! - a `lessons/lesson_NN.rs` has no `book/src/lesson_NN.md` listed in
//!   `SUMMARY.md`.
//!
//! mdbook itself only logs a missing include and builds anyway, so without
//! this test a renamed anchor silently empties a listing.
//!
//! Pure std: no mdbook needed. The checker's parsers are tested on in-memory
//! text first, so a broken checker cannot pass by finding nothing.

use std::collections::{BTreeSet, HashMap};
use std::fs;
use std::path::{Component, Path, PathBuf};

// ---------------------------------------------------------------------------
// Parsing
// ---------------------------------------------------------------------------

/// Which part of an included file a directive asks for.
#[derive(Debug, Clone, PartialEq)]
enum Part {
    Whole,
    /// `PATH:10:20`, `PATH:10`, `PATH::20`: line numbers, nothing to check.
    Lines,
    Anchor(String),
}

/// One `{{#include ..}}`-style directive in a chapter.
#[derive(Debug, Clone, PartialEq)]
struct Directive {
    kind: String,
    path: String,
    part: Part,
    /// 1-based line in the chapter.
    line: usize,
    text: String,
}

/// Finds mdbook's link directives, as mdbook does: `{{#kind args}}` with
/// optional blanks after `{{`; a backslash before `{{#` escapes it. mdbook
/// expands them inside code blocks too (that is how listings work), so code
/// blocks are not skipped here.
fn parse_directives(markdown: &str) -> Vec<Directive> {
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
                let first = sel.split(':').next().unwrap_or("");
                if first.is_empty() || first.parse::<usize>().is_ok() {
                    Part::Lines
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

/// The anchor name that follows `marker` on a line, if any (mdbook's
/// `ANCHOR:\s*([\w_-]+)`).
fn anchor_names<'a>(line: &'a str, marker: &str) -> Vec<&'a str> {
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

/// Checks that `source` opens anchor `name` and closes it afterwards.
fn check_anchor(source: &str, name: &str) -> Result<(), String> {
    let mut open = None;
    let mut close = None;
    for (n, line) in source.lines().enumerate() {
        // "ANCHOR:" is not a substring of "ANCHOR_END:", so the two never mix.
        if open.is_none() && anchor_names(line, "ANCHOR:").contains(&name) {
            open = Some(n + 1);
        }
        if close.is_none() && anchor_names(line, "ANCHOR_END:").contains(&name) {
            close = Some(n + 1);
        }
    }
    match (open, close) {
        (Some(o), Some(c)) if o < c => Ok(()),
        (Some(o), Some(c)) => Err(format!(
            "`ANCHOR_END: {name}` (line {c}) comes before `ANCHOR: {name}` (line {o})"
        )),
        (Some(_), None) => Err(format!("`ANCHOR: {name}` is never closed by `ANCHOR_END: {name}`")),
        (None, Some(_)) => Err(format!("`ANCHOR_END: {name}` has no `ANCHOR: {name}` before it")),
        (None, None) => Err(format!(
            "no anchor `{name}`: add `// ANCHOR: {name}` and `// ANCHOR_END: {name}` around the listing"
        )),
    }
}

/// Lines of markdown outside fenced code blocks, with inline code removed:
/// an image or link shown as code is not a real one.
fn prose_lines(markdown: &str) -> Vec<(usize, String)> {
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
fn link_target(after_paren: &str) -> Option<String> {
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
fn image_targets(markdown: &str) -> Vec<(usize, String)> {
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
fn summary_links(summary: &str) -> Vec<(usize, String)> {
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
fn strip_fragment(target: &str) -> &str {
    let end = target.find(['#', '?']).unwrap_or(target.len());
    &target[..end]
}

/// Resolves `.` and `..` without touching the disk.
fn normalize(path: &Path) -> PathBuf {
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
// Checking
// ---------------------------------------------------------------------------

/// What the checker needs from a file system, so that it can be tested on
/// in-memory files as well as on the real repository.
trait Files {
    /// `None` when the file does not exist or is not text.
    fn read(&self, path: &Path) -> Option<String>;
    fn exists(&self, path: &Path) -> bool;
}

/// The repository on disk; paths are relative to its root.
struct Disk(PathBuf);

impl Files for Disk {
    fn read(&self, path: &Path) -> Option<String> {
        fs::read_to_string(self.0.join(path)).ok()
    }
    fn exists(&self, path: &Path) -> bool {
        self.0.join(path).is_file()
    }
}

/// In-memory files, for the checker's own tests.
struct Memory(HashMap<PathBuf, String>);

impl Files for Memory {
    fn read(&self, path: &Path) -> Option<String> {
        self.0.get(&normalize(path)).cloned()
    }
    fn exists(&self, path: &Path) -> bool {
        self.0.contains_key(&normalize(path))
    }
}

/// Checks one chapter's directives and images. `chapter` is the chapter's
/// path from the repository root.
fn check_chapter(files: &dyn Files, chapter: &Path, markdown: &str) -> Vec<String> {
    let dir = chapter.parent().unwrap_or(Path::new(""));
    let shown = chapter.display();
    let mut errors = Vec::new();
    for d in parse_directives(markdown) {
        let target = dir.join(&d.path);
        let at = format!("{shown}:{}: {}", d.line, d.text);
        if d.path.is_empty() {
            errors.push(format!("{at}: no file named"));
            continue;
        }
        let Some(source) = files.read(&target) else {
            errors.push(format!(
                "{at}: file `{}` does not exist (paths are relative to the chapter's folder)",
                normalize(&target).display()
            ));
            continue;
        };
        if let Part::Anchor(name) = &d.part {
            if let Err(why) = check_anchor(&source, name) {
                errors.push(format!(
                    "{at}: in `{}`: {why}",
                    normalize(&target).display()
                ));
            }
        }
    }
    for (line, target) in image_targets(markdown) {
        let at = format!("{shown}:{line}: image `{target}`");
        if target.contains("://") || target.starts_with("//") || target.starts_with("data:") {
            errors.push(format!(
                "{at}: not a local file; figures are outputs of the lessons, kept beside the book, \
                 and the book must read offline"
            ));
            continue;
        }
        let path = strip_fragment(&target);
        if path.is_empty() || !files.exists(&dir.join(path)) {
            errors.push(format!(
                "{at}: file `{}` does not exist (run the lesson that makes it, and keep it under book/src/)",
                normalize(&dir.join(path)).display()
            ));
        }
    }
    errors
}

/// Checks SUMMARY.md's links, and that every lesson binary has its chapter
/// listed there. `lessons` are the file names found in `lessons/`.
fn check_summary(files: &dyn Files, src: &Path, summary: &str, lessons: &[String]) -> Vec<String> {
    let mut errors = Vec::new();
    let mut listed = BTreeSet::new();
    for (line, target) in summary_links(summary) {
        let path = strip_fragment(&target);
        if path.is_empty() {
            continue; // a draft chapter: mdbook shows its title only
        }
        if target.contains("://") {
            continue; // an outside link, not a chapter
        }
        let file = normalize(Path::new(path));
        if !files.exists(&src.join(&file)) {
            errors.push(format!(
                "book/src/SUMMARY.md:{line}: links `{path}`, which does not exist in book/src/"
            ));
        }
        listed.insert(file);
    }
    for lesson in lessons {
        let Some(stem) = lesson.strip_suffix(".rs") else {
            continue;
        };
        let is_lesson = stem
            .strip_prefix("lesson_")
            .is_some_and(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        if !is_lesson {
            continue;
        }
        let chapter = format!("{stem}.md");
        if !files.exists(&src.join(&chapter)) {
            errors.push(format!(
                "lessons/{lesson} has no chapter: write book/src/{chapter} and list it in book/src/SUMMARY.md"
            ));
        } else if !listed.contains(Path::new(&chapter)) {
            errors.push(format!(
                "lessons/{lesson}: book/src/{chapter} exists but book/src/SUMMARY.md does not list it"
            ));
        }
    }
    errors
}

/// Every `.md` file under `dir`, sorted.
fn markdown_files(dir: &Path) -> Vec<PathBuf> {
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

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn fail_with(errors: &[String], what: &str) {
    assert!(
        errors.is_empty(),
        "{what}: {} problem(s):\n  {}\n",
        errors.len(),
        errors.join("\n  ")
    );
}

// ---------------------------------------------------------------------------
// The real book
// ---------------------------------------------------------------------------

#[test]
fn book_includes_anchors_and_images_resolve() {
    let root = repo_root();
    let src = root.join("book/src");
    let chapters = markdown_files(&src);
    assert!(
        !chapters.is_empty(),
        "no chapters found under {}",
        src.display()
    );
    let mut errors = Vec::new();
    let mut directives = 0;
    for chapter in &chapters {
        let markdown = fs::read_to_string(chapter)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", chapter.display()));
        directives += parse_directives(&markdown).len();
        let relative = chapter.strip_prefix(&root).unwrap_or(chapter);
        errors.extend(check_chapter(&Disk(root.clone()), relative, &markdown));
    }
    eprintln!(
        "checked {} chapters, {directives} include directives",
        chapters.len()
    );
    fail_with(&errors, "the book is out of step with the code");
}

#[test]
fn every_lesson_has_a_listed_chapter() {
    let root = repo_root();
    let src = root.join("book/src");
    let summary = fs::read_to_string(src.join("SUMMARY.md"))
        .unwrap_or_else(|e| panic!("cannot read book/src/SUMMARY.md: {e}"));
    let mut lessons: Vec<String> = fs::read_dir(root.join("lessons"))
        .expect("cannot read lessons/")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    lessons.sort();
    assert!(
        lessons.iter().any(|l| l.starts_with("lesson_")),
        "no lessons/lesson_NN.rs found: is this the workbook's root?"
    );
    let errors = check_summary(
        &Disk(root.clone()),
        Path::new("book/src"),
        &summary,
        &lessons,
    );
    fail_with(&errors, "book/src/SUMMARY.md");
}

// ---------------------------------------------------------------------------
// The checker's own tests, on in-memory text
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
            ("rustdoc_include", "../x.rs", Part::Lines, 5),
            ("include", "a.wgsl", Part::Whole, 5),
            ("playground", "demo.rs", Part::Whole, 7),
        ]
    );
}

#[test]
fn checker_reports_a_broken_anchor() {
    // The anchor is opened but closed under a misspelt name.
    let broken = "// ANCHOR: light_view_proj\nlet m = p * v;\n// ANCHOR_END: light_view_prj\n";
    let err =
        check_anchor(broken, "light_view_proj").expect_err("a broken anchor must be reported");
    assert!(err.contains("never closed"), "{err}");
    // A longer name that starts with the wanted one is not the anchor.
    let longer = "// ANCHOR: shadow_pass_2\nx\n// ANCHOR_END: shadow_pass_2\n";
    assert!(check_anchor(longer, "shadow_pass").is_err());
    // Closed before it is opened.
    let backwards = "// ANCHOR_END: a\nx\n// ANCHOR: a\n";
    assert!(check_anchor(backwards, "a").is_err());
    // Missing altogether.
    assert!(check_anchor("fn main() {}\n", "a").is_err());
    // And a good one passes, in Rust and in WGSL comments alike.
    let good = "// ANCHOR: shadow_pass\nx\n    // ANCHOR_END: shadow_pass\n";
    assert_eq!(check_anchor(good, "shadow_pass"), Ok(()));

    // End to end: the same broken file, included by a chapter, is reported
    // with the chapter's line.
    let files = Memory(HashMap::from([
        (PathBuf::from("common/src/light.rs"), broken.to_string()),
        (PathBuf::from("book/src/figures/ok.png"), String::new()),
    ]));
    let chapter = "# Ch\n\n```rust\n{{#include ../../common/src/light.rs:light_view_proj}}\n```\n\
                   {{#include ../../common/src/gone.rs}}\n\
                   ![ok](figures/ok.png \"fine\") ![missing](figures/missing.png)\n\
                   `![shown as code](nowhere.png)`\n";
    let errors = check_chapter(&files, Path::new("book/src/ch.md"), chapter);
    assert_eq!(errors.len(), 3, "{errors:#?}");
    assert!(
        errors[0].starts_with("book/src/ch.md:4:") && errors[0].contains("never closed"),
        "{errors:#?}"
    );
    assert!(
        errors[1].contains("common/src/gone.rs") && errors[1].contains("does not exist"),
        "{errors:#?}"
    );
    assert!(errors[2].contains("figures/missing.png"), "{errors:#?}");
}

#[test]
fn checker_reports_summary_and_lesson_gaps() {
    let files = Memory(HashMap::from([
        (PathBuf::from("src/intro.md"), String::new()),
        (PathBuf::from("src/lesson_01.md"), String::new()),
        (PathBuf::from("src/lesson_02.md"), String::new()),
    ]));
    let summary =
        "# Summary\n[Intro](intro.md)\n- [One](./lesson_01.md)\n- [Gone](gone.md)\n- [Draft]()\n";
    let lessons = ["lesson_01.rs", "lesson_02.rs", "lesson_03.rs", "helpers.rs"].map(String::from);
    let errors = check_summary(&files, Path::new("src"), summary, &lessons);
    assert_eq!(errors.len(), 3, "{errors:#?}");
    assert!(errors[0].contains("gone.md"), "{errors:#?}");
    assert!(errors[1].contains("lesson_02.md exists but"), "{errors:#?}");
    assert!(
        errors[2].contains("lesson_03.rs has no chapter"),
        "{errors:#?}"
    );
}
