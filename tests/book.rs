//! The book must not drift from the code. This test reads `book/src/` and
//! fails, with the file and line, when:
//!
//! - an `{{#include PATH}}`, `{{#include PATH:ANCHOR}}`, `{{#rustdoc_include ..}}`
//!   or `{{#playground ..}}` names a file that does not exist (PATH is
//!   relative to the chapter), or an ANCHOR that the file does not open with
//!   `ANCHOR: name` and close with `ANCHOR_END: name`;
//! - an image `![..](path)` or `<img src="..">` points to a missing file;
//! - `SUMMARY.md` links a missing file;
//! - a lesson, a `lessons/lesson_NN/` folder with a `main.rs`, has no
//!   `book/src/lesson_NN.md` listed in `SUMMARY.md`;
//! - a lesson chapter `lesson_NN.md` takes less than [`MIN_OWN_SHARE`] of
//!   its listing lines from its own lesson's files (`lessons/lesson_NN/`
//!   and `shaders/lesson_NN/`); listings from `common/` or from another
//!   lesson count as not its own, and included generated tables
//!   (`book/src/generated/`) are results, not listings. Run with `--nocapture` to see the table
//!   of every chapter's share;
//! - chapter 05 does not list `silhouette_edges`, or chapter 06 shows no
//!   code of `lessons/lesson_06/`.
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

/// The lessons among `entries`, the names found in `lessons/`: the folders
/// `lesson_NN` that hold a `main.rs` (the lesson's binary), sorted. A
/// folder without one, or anything else in `lessons/`, is not a lesson.
fn lesson_folders(files: &dyn Files, entries: &[String]) -> Vec<String> {
    let mut found: Vec<String> = entries
        .iter()
        .filter(|name| {
            name.strip_prefix("lesson_")
                .is_some_and(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()))
        })
        .filter(|name| files.exists(&Path::new("lessons").join(name).join("main.rs")))
        .cloned()
        .collect();
    found.sort();
    found
}

/// Checks SUMMARY.md's links, and that every lesson has its chapter listed
/// there. `lessons` are the lesson folders' names (`lesson_NN`, see
/// [`lesson_folders`]).
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
        let chapter = format!("{lesson}.md");
        if !files.exists(&src.join(&chapter)) {
            errors.push(format!(
                "lessons/{lesson}/main.rs has no chapter: write book/src/{chapter} and list it in book/src/SUMMARY.md"
            ));
        } else if !listed.contains(Path::new(&chapter)) {
            errors.push(format!(
                "lessons/{lesson}/main.rs: book/src/{chapter} exists but book/src/SUMMARY.md does not list it"
            ));
        }
    }
    errors
}

// ---------------------------------------------------------------------------
// Whose code a chapter shows
// ---------------------------------------------------------------------------

/// The least share of a lesson chapter's listing lines that must come from
/// the lesson's own files.
const MIN_OWN_SHARE: f64 = 0.70;

/// The lines a directive pulls in, as mdbook renders them: an anchor's
/// body without marker lines (its own and any nested anchor's), or the
/// line range, or the whole file. `None` when the anchor is not there.
fn listing_lines<'a>(source: &'a str, part: &Part) -> Option<Vec<&'a str>> {
    let lines = source.lines();
    match part {
        Part::Whole => Some(lines.collect()),
        Part::Lines { start, end } => {
            let lines = lines.skip(*start);
            Some(match end {
                Some(end) => lines.take(end.saturating_sub(*start)).collect(),
                None => lines.collect(),
            })
        }
        Part::Anchor(name) => {
            let mut body: Option<Vec<&str>> = None;
            for line in lines {
                let opens = anchor_names(line, "ANCHOR:");
                let closes = anchor_names(line, "ANCHOR_END:");
                if let Some(b) = body.as_mut() {
                    if closes.contains(&name.as_str()) {
                        return body;
                    }
                    // A nested anchor's marker line: mdbook drops it.
                    if opens.is_empty() && closes.is_empty() {
                        b.push(line);
                    }
                } else if opens.contains(&name.as_str()) {
                    body = Some(Vec::new());
                }
            }
            None // never opened, or never closed
        }
    }
}

/// `lesson_NN` for a lesson chapter `.../lesson_NN.md`, else `None`.
fn chapter_lesson(chapter: &Path) -> Option<String> {
    let stem = chapter.file_stem()?.to_str()?;
    let n = stem.strip_prefix("lesson_")?;
    let is_lesson = chapter.extension().is_some_and(|e| e == "md")
        && !n.is_empty()
        && n.chars().all(|c| c.is_ascii_digit());
    is_lesson.then(|| stem.to_string())
}

/// Whether `file` (from the repository root) is one of `lesson`'s own
/// files: under `lessons/lesson_NN/` or `shaders/lesson_NN/`.
fn is_own_file(file: &Path, lesson: &str) -> bool {
    file.starts_with(Path::new("lessons").join(lesson))
        || file.starts_with(Path::new("shaders").join(lesson))
}

/// One listing of a chapter: the file it comes from, the anchor (if any),
/// its number of lines, and whether the file is the lesson's own.
#[derive(Debug, Clone, PartialEq)]
struct Listing {
    file: PathBuf,
    anchor: Option<String>,
    lines: usize,
    own: bool,
}

/// Where a lesson chapter's listing lines come from.
#[derive(Debug, Clone, PartialEq)]
struct Share {
    listings: Vec<Listing>,
}

impl Share {
    fn total(&self) -> usize {
        self.listings.iter().map(|l| l.lines).sum()
    }
    fn own(&self) -> usize {
        self.listings
            .iter()
            .filter(|l| l.own)
            .map(|l| l.lines)
            .sum()
    }
    /// The own share in [0, 1]; 0 for a chapter with no listing lines.
    fn fraction(&self) -> f64 {
        match self.total() {
            0 => 0.0,
            total => self.own() as f64 / total as f64,
        }
    }
}

/// The listings of chapter `chapter` (path from the repository root) and
/// whose they are, for lesson `lesson`. A listing that does not resolve is
/// an error here too: a share computed without it would not be the
/// chapter's.
fn listing_share(
    files: &dyn Files,
    chapter: &Path,
    markdown: &str,
    lesson: &str,
) -> Result<Share, Vec<String>> {
    let dir = chapter.parent().unwrap_or(Path::new(""));
    let mut listings = Vec::new();
    let mut errors = Vec::new();
    for d in parse_directives(markdown) {
        let file = normalize(&dir.join(&d.path));
        // A generated table (book/src/generated/) is a result, not code.
        if file.starts_with(dir.join("generated")) {
            continue;
        }
        let at = format!("{}:{}: {}", chapter.display(), d.line, d.text);
        let Some(source) = files.read(&file) else {
            errors.push(format!("{at}: file `{}` does not exist", file.display()));
            continue;
        };
        let Some(lines) = listing_lines(&source, &d.part) else {
            errors.push(format!("{at}: no anchor in `{}`", file.display()));
            continue;
        };
        listings.push(Listing {
            own: is_own_file(&file, lesson),
            anchor: match &d.part {
                Part::Anchor(name) => Some(name.clone()),
                _ => None,
            },
            lines: lines.len(),
            file,
        });
    }
    if errors.is_empty() {
        Ok(Share { listings })
    } else {
        Err(errors)
    }
}

/// Checks one lesson chapter's share: at least [`MIN_OWN_SHARE`], and at
/// least one listing line at all.
fn check_share(chapter: &Path, share: &Share) -> Result<(), String> {
    if share.total() == 0 {
        return Err(format!(
            "{}: no listing lines; a lesson chapter shows its lesson's code",
            chapter.display()
        ));
    }
    if share.fraction() < MIN_OWN_SHARE {
        let others: Vec<String> = share
            .listings
            .iter()
            .filter(|l| !l.own)
            .map(|l| {
                let anchor = l
                    .anchor
                    .as_deref()
                    .map(|a| format!(":{a}"))
                    .unwrap_or_default();
                format!("{}{anchor} ({} lines)", l.file.display(), l.lines)
            })
            .collect();
        return Err(format!(
            "{}: only {:.1} % of its listing lines ({} of {}) come from its own lesson's files, \
             at least {:.0} % must; not its own: {}. Show the lesson's own code \
             (add an anchor in lessons/{lesson}/ or shaders/{lesson}/) rather than \
             dropping explanatory listings",
            chapter.display(),
            100.0 * share.fraction(),
            share.own(),
            share.total(),
            100.0 * MIN_OWN_SHARE,
            others.join(", "),
            lesson = chapter_lesson(chapter).unwrap_or_default(),
        ));
    }
    Ok(())
}

/// Whether `share` has a listing of anchor `anchor` from the lesson's own
/// files.
fn lists_own_anchor(share: &Share, anchor: &str) -> bool {
    share
        .listings
        .iter()
        .any(|l| l.own && l.anchor.as_deref() == Some(anchor))
}

/// Whether `share` has a listing from a file under `dir` (from the
/// repository root).
fn lists_from(share: &Share, dir: &Path) -> bool {
    share.listings.iter().any(|l| l.file.starts_with(dir))
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
    let entries: Vec<String> = fs::read_dir(root.join("lessons"))
        .expect("cannot read lessons/")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    let lessons = lesson_folders(&Disk(root.clone()), &entries);
    assert!(
        !lessons.is_empty(),
        "no lessons/lesson_NN/main.rs found: is this the workbook's root?"
    );
    eprintln!("lessons: {}", lessons.join(", "));
    let errors = check_summary(
        &Disk(root.clone()),
        Path::new("book/src"),
        &summary,
        &lessons,
    );
    fail_with(&errors, "book/src/SUMMARY.md");
}

/// The share of every lesson chapter, printed as a table (`--nocapture`).
fn lesson_chapter_shares() -> Vec<(PathBuf, String, Result<Share, Vec<String>>)> {
    let root = repo_root();
    let mut out = Vec::new();
    for chapter in markdown_files(&root.join("book/src")) {
        let relative = chapter
            .strip_prefix(&root)
            .unwrap_or(&chapter)
            .to_path_buf();
        let Some(lesson) = chapter_lesson(&relative) else {
            continue;
        };
        if relative.parent() != Some(Path::new("book/src")) {
            continue; // lesson chapters sit in book/src/ itself
        }
        let markdown = fs::read_to_string(&chapter)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", chapter.display()));
        let share = listing_share(&Disk(root.clone()), &relative, &markdown, &lesson);
        out.push((relative, lesson, share));
    }
    out
}

#[test]
fn lesson_chapters_show_mostly_their_own_code() {
    let shares = lesson_chapter_shares();
    assert!(
        shares.len() >= 8,
        "found {} lesson chapters (book/src/lesson_NN.md), expected the workbook's 8",
        shares.len()
    );
    let mut errors = Vec::new();
    eprintln!(
        "share of listing lines from the lesson's own files (lessons/lesson_NN/, shaders/lesson_NN/), \
         at least {:.0} %:",
        100.0 * MIN_OWN_SHARE
    );
    eprintln!("| chapter | own lines | listing lines | own share |");
    eprintln!("|---|---|---|---|");
    for (chapter, _, share) in &shares {
        match share {
            Ok(share) => {
                eprintln!(
                    "| {} | {} | {} | {:.1} % |",
                    chapter.display(),
                    share.own(),
                    share.total(),
                    100.0 * share.fraction()
                );
                if let Err(e) = check_share(chapter, share) {
                    errors.push(e);
                }
            }
            Err(e) => {
                eprintln!("| {} | — | — | unresolved |", chapter.display());
                errors.extend(e.iter().cloned());
            }
        }
    }
    fail_with(&errors, "lesson chapters must show their own lesson's code");
}

#[test]
fn chapters_05_and_06_list_their_own_technique() {
    let shares = lesson_chapter_shares();
    let share_of = |lesson: &str| -> Share {
        match shares.iter().find(|(_, l, _)| l == lesson) {
            Some((_, _, Ok(share))) => share.clone(),
            Some((chapter, _, Err(e))) => {
                panic!(
                    "{}: listings do not resolve:\n  {}",
                    chapter.display(),
                    e.join("\n  ")
                )
            }
            None => panic!("no book/src/{lesson}.md"),
        }
    };
    let ch05 = share_of("lesson_05");
    assert!(
        lists_own_anchor(&ch05, "silhouette_edges"),
        "book/src/lesson_05.md must list the silhouette: an include of anchor `silhouette_edges` \
         from lessons/lesson_05/ (it is in lessons/lesson_05/silhouette.rs); it lists {:?}",
        ch05.listings
    );
    let ch06 = share_of("lesson_06");
    assert!(
        lists_from(&ch06, Path::new("lessons/lesson_06")),
        "book/src/lesson_06.md must show lesson 06's own code (lessons/lesson_06/: caps.rs, \
         plan.rs, main.rs); it lists {:?}",
        ch06.listings
    );
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
        (PathBuf::from("lessons/lesson_01/main.rs"), String::new()),
        (
            PathBuf::from("lessons/lesson_01/shadow_map.rs"),
            String::new(),
        ),
        (PathBuf::from("lessons/lesson_02/main.rs"), String::new()),
        (PathBuf::from("lessons/lesson_03/main.rs"), String::new()),
        // A folder without a binary is not a lesson, nor is a helper folder.
        (PathBuf::from("lessons/lesson_04/mod.rs"), String::new()),
        (PathBuf::from("lessons/helpers/main.rs"), String::new()),
        (PathBuf::from("lessons/lib.rs"), String::new()),
    ]));
    let entries = [
        "lesson_03",
        "lesson_01",
        "lesson_02",
        "lesson_04",
        "helpers",
        "lib.rs",
        "lesson_x",
    ]
    .map(String::from);
    let lessons = lesson_folders(&files, &entries);
    assert_eq!(lessons, ["lesson_01", "lesson_02", "lesson_03"]);

    let summary =
        "# Summary\n[Intro](intro.md)\n- [One](./lesson_01.md)\n- [Gone](gone.md)\n- [Draft]()\n";
    let errors = check_summary(&files, Path::new("src"), summary, &lessons);
    assert_eq!(errors.len(), 3, "{errors:#?}");
    assert!(errors[0].contains("gone.md"), "{errors:#?}");
    assert!(errors[1].contains("lesson_02.md exists but"), "{errors:#?}");
    assert!(
        errors[2].contains("lessons/lesson_03/main.rs has no chapter"),
        "{errors:#?}"
    );
}

#[test]
fn line_ranges_and_anchor_bodies_are_what_mdbook_includes() {
    let part = |arg: &str| {
        let md = format!("{{{{#include {arg}}}}}");
        parse_directives(&md)[0].part.clone()
    };
    let lines = |start, end| Part::Lines { start, end };
    assert_eq!(part("f.rs"), Part::Whole);
    assert_eq!(part("f.rs:"), lines(0, None));
    assert_eq!(part("f.rs:3"), lines(2, Some(3)));
    assert_eq!(part("f.rs:3:5"), lines(2, Some(5)));
    assert_eq!(part("f.rs::5"), lines(0, Some(5)));
    assert_eq!(part("f.rs:3:"), lines(2, None));
    assert_eq!(part("f.rs:name"), Part::Anchor("name".into()));

    let source = "a\nb\nc\nd\ne\n";
    assert_eq!(listing_lines(source, &part("f.rs:2")), Some(vec!["b"]));
    assert_eq!(
        listing_lines(source, &part("f.rs:2:4")),
        Some(vec!["b", "c", "d"])
    );
    assert_eq!(
        listing_lines(source, &part("f.rs::2")),
        Some(vec!["a", "b"])
    );
    assert_eq!(
        listing_lines(source, &part("f.rs:4:")),
        Some(vec!["d", "e"])
    );
    assert_eq!(
        listing_lines(source, &Part::Whole).map(|l| l.len()),
        Some(5)
    );

    // An anchor's body: its own markers and a nested anchor's are dropped.
    let nested = "x\n// ANCHOR: outer\none\n  // ANCHOR: inner\ntwo\n  // ANCHOR_END: inner\n\
                  three\n// ANCHOR_END: outer\ny\n";
    let outer = listing_lines(nested, &Part::Anchor("outer".into()));
    assert_eq!(outer, Some(vec!["one", "two", "three"]));
    let inner = listing_lines(nested, &Part::Anchor("inner".into()));
    assert_eq!(inner, Some(vec!["two"]));
    // Missing, unclosed or longer-named anchors give nothing.
    assert_eq!(listing_lines(nested, &Part::Anchor("out".into())), None);
    assert_eq!(
        listing_lines("// ANCHOR: a\nx\n", &Part::Anchor("a".into())),
        None
    );
}

#[test]
fn share_counts_each_listing_for_its_own_lesson() {
    // Lesson 06's chapter: 4 own lines (3 of an anchor in lessons/lesson_06/,
    // 1 of a line range in shaders/lesson_06/), 2 from lesson 05 and 2 from
    // common/. A `lessons/lesson_060/` or `lessons/lesson_06.rs` is not
    // lesson 06's folder.
    let files = Memory(HashMap::from([
        (
            PathBuf::from("lessons/lesson_06/caps.rs"),
            "use x;\n// ANCHOR: zfail_stencil\nfn a() {\n    // ANCHOR: inner\n    b();\n    \
             // ANCHOR_END: inner\n}\n// ANCHOR_END: zfail_stencil\n"
                .to_string(),
        ),
        (
            PathBuf::from("shaders/lesson_06/caps.wgsl"),
            "// header\nfn caps() {}\n// more\n".to_string(),
        ),
        (
            PathBuf::from("lessons/lesson_05/silhouette.rs"),
            "// ANCHOR: silhouette_edges\nfn s() {}\nfn t() {}\n// ANCHOR_END: silhouette_edges\n"
                .to_string(),
        ),
        (
            PathBuf::from("common/src/camera.rs"),
            "fn c() {}\nfn d() {}\n".to_string(),
        ),
        (
            PathBuf::from("lessons/lesson_060/x.rs"),
            "one\n".to_string(),
        ),
        (PathBuf::from("lessons/lesson_06.rs"), "one\n".to_string()),
    ]));
    let chapter = Path::new("book/src/lesson_06.md");
    assert_eq!(chapter_lesson(chapter).as_deref(), Some("lesson_06"));
    assert_eq!(chapter_lesson(Path::new("book/src/introduction.md")), None);
    assert_eq!(chapter_lesson(Path::new("book/src/lesson_.md")), None);

    let md = "# 06\n```rust\n{{#include ../../lessons/lesson_06/caps.rs:zfail_stencil}}\n```\n\
              ```wgsl\n{{#include ../../shaders/lesson_06/caps.wgsl:2}}\n```\n\
              ```rust\n{{#include ../../lessons/lesson_05/silhouette.rs:silhouette_edges}}\n```\n\
              ```rust\n{{#include ../../common/src/camera.rs}}\n```\n";
    let share = listing_share(&files, chapter, md, "lesson_06").expect("all listings resolve");
    let got: Vec<(&str, usize, bool)> = share
        .listings
        .iter()
        .map(|l| (l.file.to_str().unwrap(), l.lines, l.own))
        .collect();
    assert_eq!(
        got,
        vec![
            ("lessons/lesson_06/caps.rs", 3, true),
            ("shaders/lesson_06/caps.wgsl", 1, true),
            ("lessons/lesson_05/silhouette.rs", 2, false),
            ("common/src/camera.rs", 2, false),
        ]
    );
    assert_eq!((share.own(), share.total()), (4, 8));
    assert!((share.fraction() - 0.5).abs() < 1e-12);
    // 50 % is below the bar, and the failure names the chapter, its share
    // and what is not its own.
    let err = check_share(chapter, &share).expect_err("50 % must fail");
    assert!(
        err.contains("book/src/lesson_06.md") && err.contains("50.0 %"),
        "{err}"
    );
    assert!(
        err.contains("lessons/lesson_05/silhouette.rs:silhouette_edges (2 lines)"),
        "{err}"
    );
    assert!(lists_from(&share, Path::new("lessons/lesson_06")));
    assert!(
        !lists_own_anchor(&share, "silhouette_edges"),
        "lesson 05's, not 06's"
    );
    assert!(lists_own_anchor(&share, "zfail_stencil"));

    // The same chapter as lesson 05's: the silhouette is its own.
    let as_05 = listing_share(&files, chapter, md, "lesson_05").unwrap();
    assert!(lists_own_anchor(&as_05, "silhouette_edges"));
    assert_eq!(as_05.own(), 2);

    // Folders that only look like lesson 06's are not its own.
    let lookalikes = "{{#include ../../lessons/lesson_060/x.rs}}\n\
                      {{#include ../../lessons/lesson_06.rs}}\n\
                      {{#include ../../lessons/lesson_06/caps.rs:zfail_stencil}}\n";
    let share = listing_share(&files, chapter, lookalikes, "lesson_06").unwrap();
    assert_eq!((share.own(), share.total()), (3, 5));
    assert!(check_share(chapter, &share).is_err(), "60 % fails");

    // Dropping the foreign listings passes (100 %); a chapter with no
    // listing at all fails, and so does one whose listing does not resolve.
    let own_only = "{{#include ../../lessons/lesson_06/caps.rs:zfail_stencil}}\n";
    let share = listing_share(&files, chapter, own_only, "lesson_06").unwrap();
    assert_eq!(check_share(chapter, &share), Ok(()));
    let empty = listing_share(&files, chapter, "# no code\n", "lesson_06").unwrap();
    assert!(check_share(chapter, &empty)
        .unwrap_err()
        .contains("no listing lines"));
    let broken = "{{#include ../../lessons/lesson_06/caps.rs:gone}}\n\
                  {{#include ../../lessons/lesson_06/missing.rs}}\n";
    let errors = listing_share(&files, chapter, broken, "lesson_06").unwrap_err();
    assert_eq!(errors.len(), 2, "{errors:#?}");
}

// ---------------------------------------------------------------------------
// Sources by name, and links that land on a heading
// ---------------------------------------------------------------------------

/// `(line, word)` of every word that starts with "seed", any case
/// (`seed`, `Seeds'`, `constant_seed`): the workbook names its sources
/// instead ("the lwjgl book", "tinyrenderer's shadow lesson").
fn seed_words(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let lower = line.to_ascii_lowercase();
        for (at, _) in lower.match_indices("seed") {
            let before = lower[..at].chars().next_back();
            if before.is_some_and(|c| c.is_ascii_alphabetic()) {
                continue; // "linseed" is not the word
            }
            let end = lower[at..]
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '\''))
                .map_or(line.len(), |e| at + e);
            found.push((n + 1, line[at..end].to_string()));
        }
    }
    found
}

/// The sources the workbook follows, as the bibliography must name them:
/// each entry is the words that must all appear, spelt as here. Proper
/// names are matched with their capitals, so that the bibliography's
/// lower-case keys (`[heidmann]`) do not count as naming the source.
const SOURCES: &[&[&str]] = &[
    &["ogldev", "Tutorial 40"],
    &["LWJGL", "Hernández Bejarano"],
    &["yyh", "DonewsBlog"],
    &["tinyrenderer", "Sokolov"],
    &["Pupius"],
    &["Everitt"],
    &["Kilgard"],
    &["Common Techniques to Improve Shadow Depth Maps"],
    &["Cascaded Shadow Maps"],
    &["Williams"],
    &["Crow"],
    &["Heidmann"],
];

/// The sources of [`SOURCES`] that `bibliography` does not name.
fn missing_sources(bibliography: &str) -> Vec<String> {
    SOURCES
        .iter()
        .filter(|words| !words.iter().all(|w| bibliography.contains(w)))
        .map(|words| words.join(" + "))
        .collect()
}

/// A heading's id as mdBook makes it: inline markup dropped, letters,
/// digits, `_` and `-` kept (ASCII lower-cased), each blank a `-`.
fn heading_id(heading: &str) -> String {
    heading
        .trim()
        .trim_start_matches('#')
        .trim()
        .chars()
        .filter(|c| !matches!(c, '`' | '*'))
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '_' || c == '-' {
                Some(c.to_ascii_lowercase())
            } else if c.is_whitespace() {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

/// Every fragment a page answers to: its headings' ids (a repeated id
/// gets `-1`, `-2`, … as mdBook does) and every `id="…"` it writes.
fn page_ids(markdown: &str) -> BTreeSet<String> {
    let mut ids = BTreeSet::new();
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut fence = false;
    for line in markdown.lines() {
        let t = line.trim_start();
        if t.starts_with("```") || t.starts_with("~~~") {
            fence = !fence;
            continue;
        }
        if fence {
            continue;
        }
        if t.starts_with('#') {
            let id = heading_id(t);
            let n = seen.entry(id.clone()).or_insert(0);
            ids.insert(if *n == 0 { id } else { format!("{id}-{n}") });
            *n += 1;
        }
        let mut rest = line;
        while let Some(at) = rest.find("id=\"") {
            rest = &rest[at + 4..];
            if let Some(end) = rest.find('"') {
                ids.insert(rest[..end].to_string());
            }
        }
    }
    ids
}

/// `(line, target)` of every `[text](target)` link that stays in the
/// book: no scheme, not an image.
fn local_links(markdown: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (line, text) in prose_lines(markdown) {
        let mut rest = text.as_str();
        while let Some(at) = rest.find("](") {
            let image = rest[..at]
                .rfind('[')
                .is_some_and(|o| rest[..o].ends_with('!'));
            if let Some(target) = link_target(&rest[at + 2..]) {
                if !image && !target.contains("://") && !target.starts_with("mailto:") {
                    found.push((line, target));
                }
            }
            rest = &rest[at + 2..];
        }
    }
    found
}

/// Errors for `chapter`'s links (paths relative to the book's `src`)
/// whose page is missing or has no heading or id for the fragment.
fn check_links(pages: &HashMap<PathBuf, String>, chapter: &Path, markdown: &str) -> Vec<String> {
    let dir = chapter.parent().unwrap_or(Path::new(""));
    let mut errors = Vec::new();
    for (line, target) in local_links(markdown) {
        let path = strip_fragment(&target);
        let page = if path.is_empty() {
            chapter.to_path_buf()
        } else {
            normalize(&dir.join(path))
        };
        if !path.is_empty() && !path.ends_with(".md") {
            continue; // a file, not a page: the include check's job
        }
        let Some(text) = pages.get(&page) else {
            errors.push(format!(
                "{}:{line}: link to missing page {target}",
                chapter.display()
            ));
            continue;
        };
        if let Some((_, fragment)) = target.split_once('#') {
            if !page_ids(text).contains(fragment) {
                errors.push(format!(
                    "{}:{line}: {target}: no heading or id \"{fragment}\" in {}",
                    chapter.display(),
                    page.display()
                ));
            }
        }
    }
    errors
}

/// The hand-written pages: every `.md` under `book/src` but `generated/`.
fn written_pages(src: &Path) -> HashMap<PathBuf, String> {
    markdown_files(src)
        .into_iter()
        .filter(|p| !p.starts_with(src.join("generated")))
        .map(|p| {
            let text = fs::read_to_string(&p)
                .unwrap_or_else(|e| panic!("cannot read {}: {e}", p.display()));
            (p.strip_prefix(src).unwrap_or(&p).to_path_buf(), text)
        })
        .collect()
}

#[test]
fn checkers_find_seeds_sources_and_broken_fragments() {
    let seeds = seed_words("the Seeds' constant\n`constant_seed`, linseed, seeded\n");
    let words: Vec<&str> = seeds.iter().map(|(_, w)| w.as_str()).collect();
    assert_eq!(words, ["Seeds'", "seed", "seeded"], "{seeds:?}");
    assert_eq!(seeds[1].0, 2);
    assert!(seed_words("the lwjgl book's constant, proceed").is_empty());

    let all = "ogldev Tutorial 40, LWJGL by Hernández Bejarano, yyh on DonewsBlog, \
               tinyrenderer by Sokolov, Pupius, Everitt and Kilgard, Common \
               Techniques to Improve Shadow Depth Maps, Cascaded Shadow Maps, \
               Williams, Crow, Heidmann";
    assert!(
        missing_sources(all).is_empty(),
        "{:?}",
        missing_sources(all)
    );
    let without = all
        .replace("Heidmann", "[heidmann] H.")
        .replace("DonewsBlog", "a blog");
    assert_eq!(missing_sources(&without), ["yyh + DonewsBlog", "Heidmann"]);

    assert_eq!(
        heading_id("## Why acne appears: texel footprint × tan θ"),
        "why-acne-appears-texel-footprint--tan-θ"
    );
    assert_eq!(heading_id("## To infinity: w = 0"), "to-infinity-w--0");
    assert_eq!(
        heading_id("### The `pcf` kernel's *taps*"),
        "the-pcf-kernels-taps"
    );
    let page = "# Top\n## Results\n```\n# not a heading\n```\n## Results\n\
                <a id=\"lwjgl\"></a>**[lwjgl]** …\n";
    let ids = page_ids(page);
    let want = ["lwjgl", "results", "results-1", "top"];
    assert_eq!(ids.iter().map(String::as_str).collect::<Vec<_>>(), want);

    let pages: HashMap<PathBuf, String> = [
        (PathBuf::from("appendix/bibliography.md"), page.to_string()),
        (
            PathBuf::from("lesson_01.md"),
            "# 01\n## The light's view\n".into(),
        ),
    ]
    .into();
    let chapter = Path::new("appendix/glossary.md");
    let good = "[a](bibliography.md#lwjgl) [b](../lesson_01.md#the-lights-view) \
                ![img](../figures/x.png) [c](https://example.org#x)\n";
    assert_eq!(check_links(&pages, chapter, good), Vec::<String>::new());
    let bad = "[a](bibliography.md#gone)\n[b](../lesson_02.md)\n`[c](nowhere.md)`\n";
    let errors = check_links(&pages, chapter, bad);
    assert_eq!(errors.len(), 2, "{errors:#?}");
    assert!(errors[0].contains(":1:") && errors[0].contains("\"gone\""));
    assert!(errors[1].contains(":2:") && errors[1].contains("missing page"));
}

/// "Seed" meant nothing to a reader: the book names its sources. Only the
/// hand-written pages are checked. `book/src/generated/` is left out on
/// purpose: the generator rewrites it from the lessons' variant names, so
/// a stale `constant_seed` there is fixed by rerunning the generator
/// (`cargo run --release --bin workbook -- book`), not by editing it.
#[test]
fn the_book_names_its_sources_and_never_says_seed() {
    let root = repo_root();
    let src = root.join("book/src");
    let mut pages: Vec<(PathBuf, String)> = written_pages(&src)
        .into_iter()
        .map(|(p, text)| (Path::new("book/src").join(p), text))
        .collect();
    let readme = fs::read_to_string(root.join("README.md")).expect("README.md");
    pages.push((PathBuf::from("README.md"), readme));
    let mut errors = Vec::new();
    for (page, text) in &pages {
        for (line, word) in seed_words(text) {
            errors.push(format!(
                "{}:{line}: \"{word}\": name the source instead",
                page.display()
            ));
        }
    }
    let bibliography = fs::read_to_string(src.join("appendix/bibliography.md"))
        .expect("book/src/appendix/bibliography.md");
    for source in missing_sources(&bibliography) {
        errors.push(format!(
            "book/src/appendix/bibliography.md does not name {source}"
        ));
    }
    fail_with(&errors, "the book must name its sources");
}

/// Every link between the book's pages lands on a page that exists and,
/// with a `#fragment`, on one of its headings or `id`s (mdBook itself
/// builds a link to a missing heading without a word).
#[test]
fn links_between_pages_land_on_a_heading() {
    let src = repo_root().join("book/src");
    let pages = written_pages(&src);
    let mut errors = Vec::new();
    let mut links = 0;
    for (page, text) in &pages {
        links += local_links(text).len();
        errors.extend(check_links(&pages, page, text));
    }
    eprintln!("checked {links} links in {} pages", pages.len());
    assert!(links > 0, "no links found under {}", src.display());
    fail_with(&errors, "links between the book's pages");
}
