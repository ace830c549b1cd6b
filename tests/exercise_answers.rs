//! An exercise's answer is nowhere in the repository but `solutions/`.
//!
//! For every chapter with a `lessons/lesson_NN/exercises.toml`, each
//! exercise's `task` names the function a student writes ("write NAME() in
//! FILE"). No `.rs` or `.wgsl` file under `lessons/`, `shaders/`,
//! `common/`, `book/` or `web/` may define a function of that name, but
//! the starter FILE itself: a lesson that holds the answer hands it out,
//! whatever its exercise module leaves out. The reference solutions
//! (`solutions/`), the chapters' copies (`tests/chapter_copies/`) and the
//! half-right answers (`tests/half_right/`) are where answers belong, and
//! lie outside the folders searched.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The folders searched for a definition.
const SEARCHED: [&str; 5] = ["lessons", "shaders", "common", "book", "web"];

/// One exercise's function: where the task asks for it.
struct Asked {
    lesson: String,
    variant: String,
    name: String,
    /// The starter file, relative to the root (`shaders/lesson_10/exercises.wgsl`).
    starter: String,
}

/// Every exercise of every chapter's spec, with the function its task asks
/// for: `write NAME() in FILE`.
fn asked() -> Vec<Asked> {
    let mut chapters: Vec<PathBuf> = std::fs::read_dir(root().join("lessons"))
        .expect("lessons/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("exercises.toml").is_file())
        .collect();
    chapters.sort();
    assert!(!chapters.is_empty(), "no lessons/lesson_NN/exercises.toml");
    let mut out = Vec::new();
    for dir in chapters {
        let lesson = dir.file_name().unwrap().to_string_lossy().to_string();
        let path = dir.join("exercises.toml");
        let text = std::fs::read_to_string(&path).expect("the spec");
        let spec: toml::Value =
            toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let exercises = spec["exercise"].as_array().expect("[[exercise]]");
        for ex in exercises {
            let variant = ex["variant"].as_str().expect("variant").to_string();
            let task = ex["task"].as_str().expect("task");
            let (name, starter) = task
                .strip_prefix("write ")
                .and_then(|t| t.split_once("() in "))
                .unwrap_or_else(|| {
                    panic!("{lesson} {variant}: task {task:?} is not `write NAME() in FILE`")
                });
            assert!(
                root().join(starter).is_file(),
                "{lesson} {variant}: the task's file {starter} does not exist"
            );
            out.push(Asked {
                lesson: lesson.clone(),
                variant,
                name: name.to_string(),
                starter: starter.to_string(),
            });
        }
    }
    out
}

/// The `.rs` and `.wgsl` files under `dir`, recursively (build outputs left out).
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        let name = e.file_name().to_string_lossy().to_string();
        if p.is_dir() {
            if !["target", "node_modules", "pkg"].contains(&name.as_str()) && !name.starts_with('.')
            {
                sources(&p, out);
            }
        } else if name.ends_with(".rs") || name.ends_with(".wgsl") {
            out.push(p);
        }
    }
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// The 1-based lines of `text` where a function `name` is defined, in Rust
/// or WGSL: the word `fn`, white space (line breaks too), `name` as a
/// whole word, then, after optional white space and generic parameters
/// (`<T: Copy>`), an opening parenthesis.
fn definitions(text: &str, name: &str) -> Vec<usize> {
    let b = text.as_bytes();
    let skip_space = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        i
    };
    let mut lines = Vec::new();
    let mut from = 0;
    while let Some(at) = text[from..].find("fn") {
        let start = from + at;
        from = start + 2;
        if start > 0 && is_ident(b[start - 1]) {
            continue;
        }
        let i = skip_space(start + 2);
        if i == start + 2 || !text[i..].starts_with(name) {
            continue;
        }
        let mut j = i + name.len();
        if j < b.len() && is_ident(b[j]) {
            continue;
        }
        j = skip_space(j);
        if j < b.len() && b[j] == b'<' {
            // Generic parameters: to the matching '>'.
            let mut depth = 0;
            while j < b.len() {
                match b[j] {
                    b'<' => depth += 1,
                    b'>' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
                j += 1;
            }
            j = skip_space(j + 1);
        }
        if j < b.len() && b[j] == b'(' {
            lines.push(text[..i].matches('\n').count() + 1);
        }
    }
    lines
}

#[test]
fn definitions_are_found_with_any_white_space_and_only_as_a_whole_name() {
    let name = "exercise_footprint";
    for (text, want) in [
        ("fn exercise_footprint(s: vec3<f32>) -> f32 {", vec![1]),
        ("pub fn  exercise_footprint  (x: u32) {}", vec![1]),
        ("\n\tfn\texercise_footprint<T: Copy>(t: T) {}", vec![2]),
        ("pub(crate) fn\nexercise_footprint\n(", vec![2]),
        ("fn exercise_footprint_tail(s: f32) {}", vec![]),
        ("fn my_exercise_footprint(s: f32) {}", vec![]),
        ("defn exercise_footprint(s: f32) {}", vec![]),
        ("let m = exercise_footprint(s, d_r, d_b);", vec![]),
        ("fnexercise_footprint(", vec![]),
        ("fn exercise_footprint;", vec![]),
    ] {
        assert_eq!(definitions(text, name), want, "in {text:?}");
    }
}

/// No lesson, shader, shared module, book generator or web file defines
/// the function an exercise asks for (its starter file aside).
#[test]
fn no_exercise_answer_is_defined_outside_its_starter() {
    let mut files = Vec::new();
    for dir in SEARCHED {
        sources(&root().join(dir), &mut files);
    }
    files.sort();
    assert!(
        files
            .iter()
            .any(|f| f.ends_with("shaders/lesson_10/soft.wgsl")),
        "the search found no lesson shader: {} files",
        files.len()
    );
    let asked = asked();
    let mut found = Vec::new();
    for file in &files {
        let rel = file.strip_prefix(root()).unwrap_or(file);
        let rel_text = rel.to_string_lossy().replace('\\', "/");
        let text = std::fs::read_to_string(file).unwrap_or_default();
        for a in &asked {
            if rel_text == a.starter {
                continue;
            }
            for line in definitions(&text, &a.name) {
                found.push(format!(
                    "{rel_text}:{line}: defines fn {}, which {} {} asks for in {}",
                    a.name, a.lesson, a.variant, a.starter
                ));
            }
        }
    }
    assert!(
        found.is_empty(),
        "an exercise's answer outside its starter, solutions/, tests/chapter_copies/ \
         and tests/half_right/:\n{}",
        found.join("\n")
    );
}
