//! Whose code a chapter shows: a lesson chapter takes at least
//! [`MIN_OWN_SHARE`] of its listing lines from its own lesson's files, and
//! chapters 05 and 06 list their own technique.

use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};

use crate::helpers::{fail_with, markdown_files, repo_root, Disk, Files, Memory};
use crate::parse::{anchor_names, normalize, parse_directives, Part};

/// The least share of a lesson chapter's listing lines that must come from
/// the lesson's own files.
const MIN_OWN_SHARE: f64 = 0.70;

/// The lines a directive pulls in, as mdbook renders them: an anchor's
/// body without marker lines (its own and any nested anchor's), or the
/// line range, or the whole file. `None` when the anchor is not there.
pub(crate) fn listing_lines<'a>(source: &'a str, part: &Part) -> Option<Vec<&'a str>> {
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
pub(crate) fn chapter_lesson(chapter: &Path) -> Option<String> {
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

// ---------------------------------------------------------------------------
// The real book
// ---------------------------------------------------------------------------

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
        lists_own_anchor(&ch05, "silhouette_edges"), // not a counter: an anchor
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
        !lists_own_anchor(&share, "silhouette_edges"), // not a counter: an anchor
        "lesson 05's, not 06's"
    );
    assert!(lists_own_anchor(&share, "zfail_stencil"));

    // The same chapter as lesson 05's: the silhouette is its own.
    let as_05 = listing_share(&files, chapter, md, "lesson_05").unwrap();
    assert!(lists_own_anchor(&as_05, "silhouette_edges")); // not a counter: an anchor
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
