//! A lesson uses an earlier lesson's technique, never a later one's:
//! `workbook::lesson_MM`, `crate::lesson_MM` or `shaders/lesson_MM/` with
//! MM > NN, in no file of `lessons/lesson_NN/`.

use std::path::{Path, PathBuf};

use crate::{read, repo_root, rust_files};

/// The lesson numbers that `text` refers to, with the line of each:
/// `workbook::lesson_MM`, `crate::lesson_MM`, `shaders/lesson_MM/`.
fn lesson_references(text: &str) -> Vec<(usize, u32)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        for prefix in ["workbook::lesson_", "crate::lesson_", "shaders/lesson_"] {
            let mut rest = code;
            while let Some(at) = rest.find(prefix) {
                let digits: String = rest[at + prefix.len()..]
                    .chars()
                    .take_while(char::is_ascii_digit)
                    .collect();
                if let Ok(n) = digits.parse() {
                    out.push((i + 1, n));
                }
                rest = &rest[at + prefix.len()..];
            }
        }
    }
    out
}

/// `lessons/lesson_NN/...` → NN.
pub(crate) fn lesson_of(path: &Path, root: &Path) -> Option<u32> {
    let rel = path.strip_prefix(root).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?;
    first.strip_prefix("lesson_")?.parse().ok()
}

/// Errors for every reference from lesson NN to a later lesson.
fn later_lesson_imports(files: &[(PathBuf, u32, String)]) -> Vec<String> {
    let mut errors = Vec::new();
    for (path, n, text) in files {
        for (line, m) in lesson_references(text) {
            if m > *n {
                errors.push(format!(
                    "{}:{line}: lesson {n:02} uses lesson {m:02}, a later lesson",
                    path.display()
                ));
            }
        }
    }
    errors
}

#[test]
fn later_lesson_checker_works() {
    let files = vec![
        (
            PathBuf::from("lessons/lesson_05/a.rs"),
            5,
            "use crate::lesson_06::caps;\nuse crate::lesson_01::x; // lesson_09\n".to_string(),
        ),
        (
            PathBuf::from("lessons/lesson_06/main.rs"),
            6,
            "use workbook::lesson_05::volumes;\ninclude_str!(\"../../shaders/lesson_07/a.wgsl\")\n"
                .to_string(),
        ),
    ];
    let errors = later_lesson_imports(&files);
    assert_eq!(errors.len(), 2, "{errors:#?}");
    assert!(errors[0].contains("a.rs:1") && errors[0].contains("lesson 06"));
    assert!(errors[1].contains("main.rs:2") && errors[1].contains("lesson 07"));
}

#[test]
fn no_lesson_uses_a_later_lesson() {
    let root = repo_root().join("lessons");
    let files: Vec<(PathBuf, u32, String)> = rust_files(&root)
        .into_iter()
        .filter_map(|p| {
            let n = lesson_of(&p, &root)?;
            let text = read(&p);
            Some((p, n, text))
        })
        .collect();
    assert!(
        files.len() >= 16,
        "expected the lesson folders' files, found {}",
        files.len()
    );
    let errors = later_lesson_imports(&files);
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}
