//! Includes and images: every `{{#include ..}}`-style directive names a file
//! that exists and an anchor that it opens and closes; every image is a
//! local file that exists.

use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};

use crate::helpers::{fail_with, markdown_files, repo_root, Disk, Files, Memory};
use crate::parse::{
    anchor_names, image_targets, normalize, parse_directives, strip_fragment, Part,
};

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

// ---------------------------------------------------------------------------
// The checker's own test, on in-memory text
// ---------------------------------------------------------------------------

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
