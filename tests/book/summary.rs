//! SUMMARY.md: its links land on files that exist, and every lesson
//! (`lessons/lesson_NN/main.rs`) has its chapter listed there.

use std::collections::{BTreeSet, HashMap};
use std::fs;
use std::path::{Path, PathBuf};

use crate::helpers::{fail_with, repo_root, Disk, Files, Memory};
use crate::parse::{normalize, strip_fragment, summary_links};

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
// The real book
// ---------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------
// The checker's own test, on in-memory text
// ---------------------------------------------------------------------------

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
