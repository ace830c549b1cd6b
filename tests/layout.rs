//! The layout rules of the workbook, checked on the source tree:
//!
//! - a lesson uses an earlier lesson's technique, never a later one's
//!   (`workbook::lesson_MM`, `crate::lesson_MM` or `shaders/lesson_MM/`
//!   with MM > NN, in any file of `lessons/lesson_NN/`);
//! - there are no import cycles between the modules of `common/` nor
//!   between the modules of the lessons;
//! - no source file in `lessons/` or `common/` is over 500 lines;
//! - `common/src/lib.rs` and each folder's `mod.rs` list every module they
//!   have, in their docs too;
//! - no module of `common/` serves a single lesson (used by exactly one
//!   lesson folder and by no other module of `common/`).
//! - no binary built with `test = false` (the lessons', the generator's)
//!   holds a unit test, which would never run.
//!
//! Pure std: the checks read the files as text. Each checker is first run
//! on in-memory text, so a broken checker cannot pass by finding nothing.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file below `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

fn read(p: &Path) -> String {
    fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

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
fn lesson_of(path: &Path, root: &Path) -> Option<u32> {
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

// ---------------------------------------------------------------------------
// Import cycles
// ---------------------------------------------------------------------------

/// The module name of a file: `common/src/render.rs` → `render`,
/// `lessons/lesson_05/stencil.rs` → `lesson_05::stencil`.
fn module_name(path: &Path, src: &Path, lessons: bool) -> Option<String> {
    let rel = path.strip_prefix(src).ok()?;
    let parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    match (lessons, parts.as_slice()) {
        (false, [m]) if m != "lib" => Some(m.clone()),
        // A folder of `common/src/` (at any depth) is a module whose
        // `mod.rs` is its root.
        (false, [g, .., m]) if g != "bin" && m == "mod" => {
            Some(parts[..parts.len() - 1].join("::"))
        }
        // A file in a folder that has a `mod.rs` (not a `#[path]` folder
        // of unit tests).
        (false, [g, _, ..]) if g != "bin" && path.with_file_name("mod.rs").exists() => {
            Some(parts.join("::"))
        }
        (true, [l, m]) if l.starts_with("lesson_") && m != "mod" && m != "main" => {
            Some(format!("{l}::{m}"))
        }
        _ => None,
    }
}

/// The modules `text` (the file of module `me`) uses, among `known`:
/// `crate::x`, and in a lesson also `super::x` and `crate::lesson_NN::x`.
fn uses(me: &str, text: &str, known: &BTreeSet<String>) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let lesson = me.split("::").next().unwrap_or("");
    let code: String = text
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    for (prefix, qualify) in [("crate::", false), ("super::", true)] {
        let mut rest = code.as_str();
        while let Some(at) = rest.find(prefix) {
            rest = &rest[at + prefix.len()..];
            let path: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            let segs: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
            let candidates = match (qualify, segs.as_slice()) {
                (true, [m, ..]) => vec![format!("{lesson}::{m}")],
                (false, [l, m, ..]) => vec![format!("{l}::{m}"), l.to_string()],
                (false, [m]) => vec![m.to_string()],
                _ => vec![],
            };
            if let Some(c) = candidates.into_iter().find(|c| known.contains(c)) {
                if c != me {
                    out.insert(c);
                }
            }
        }
    }
    out
}

/// A cycle in the graph, as module names, if there is one.
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(n.to_string(), 1);
        stack.push(n.to_string());
        for m in graph.get(n).into_iter().flatten() {
            match state.get(m.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = stack.iter().position(|s| s == m).unwrap_or(0);
                    let mut cycle = stack[start..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(m, graph, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        if state.get(n.as_str()).copied().unwrap_or(0) == 0 {
            let mut stack = Vec::new();
            if let Some(c) = visit(n, graph, &mut state, &mut stack) {
                return Some(c);
            }
        }
    }
    None
}

fn import_graph(src: &Path, lessons: bool) -> BTreeMap<String, BTreeSet<String>> {
    let files: Vec<(String, String)> = rust_files(src)
        .into_iter()
        .filter_map(|p| Some((module_name(&p, src, lessons)?, read(&p))))
        .collect();
    let known: BTreeSet<String> = files.iter().map(|(m, _)| m.clone()).collect();
    files
        .iter()
        .map(|(m, text)| (m.clone(), uses(m, text, &known)))
        .collect()
}

#[test]
fn cycle_checker_works() {
    let known: BTreeSet<String> = ["mesh", "adjacency", "render"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let mut graph = BTreeMap::new();
    graph.insert(
        "mesh".to_string(),
        uses("mesh", "use crate::adjacency::Adjacency;", &known),
    );
    graph.insert(
        "adjacency".to_string(),
        uses("adjacency", "use crate::mesh::{Mesh, face_normal};", &known),
    );
    graph.insert(
        "render".to_string(),
        uses(
            "render",
            "// crate::mesh in a comment\nuse crate::adjacency;",
            &known,
        ),
    );
    assert_eq!(graph["render"].len(), 1, "{graph:?}");
    let cycle = find_cycle(&graph).expect("mesh <-> adjacency is a cycle");
    assert!(cycle.contains(&"mesh".to_string()) && cycle.contains(&"adjacency".to_string()));
    graph.insert("mesh".to_string(), BTreeSet::new());
    assert_eq!(find_cycle(&graph), None);

    let lessons: BTreeSet<String> = ["lesson_05::a", "lesson_05::b", "lesson_06::c"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let a = uses("lesson_05::a", "use super::b::X;", &lessons);
    let c = uses("lesson_06::c", "use crate::lesson_05::a::Y;", &lessons);
    assert_eq!(a.into_iter().collect::<Vec<_>>(), ["lesson_05::b"]);
    assert_eq!(c.into_iter().collect::<Vec<_>>(), ["lesson_05::a"]);
}

#[test]
fn no_import_cycles() {
    for (dir, lessons) in [("common/src", false), ("lessons", true)] {
        let graph = import_graph(&repo_root().join(dir), lessons);
        assert!(
            graph.len() >= 10,
            "{dir}: expected its modules, found {}",
            graph.len()
        );
        assert!(
            graph.values().any(|u| !u.is_empty()),
            "{dir}: found no imports at all"
        );
        if let Some(cycle) = find_cycle(&graph) {
            panic!("{dir}: import cycle {}", cycle.join(" -> "));
        }
    }
}

// ---------------------------------------------------------------------------
// Sizes and module lists
// ---------------------------------------------------------------------------

const MAX_LINES: usize = 500;

#[test]
fn no_source_file_is_over_500_lines() {
    let mut files = rust_files(&repo_root().join("lessons"));
    files.extend(rust_files(&repo_root().join("common")));
    assert!(files.len() >= 30, "found {} files", files.len());
    let long: Vec<String> = files
        .iter()
        .map(|p| (p, read(p).lines().count()))
        .filter(|(_, n)| *n > MAX_LINES)
        .map(|(p, n)| format!("{}: {n} lines", p.display()))
        .collect();
    assert!(
        long.is_empty(),
        "over {MAX_LINES} lines:\n{}",
        long.join("\n")
    );
}

/// `pub mod x;` declarations of a lib.rs.
fn declared_modules(lib: &str) -> BTreeSet<String> {
    lib.lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod "))
        .map(|m| m.trim_end_matches(';').trim().to_string())
        .collect()
}

#[test]
fn common_lib_lists_every_module() {
    let src = repo_root().join("common/src");
    // lib.rs declares the folders; each folder's mod.rs its own modules.
    let mut declared = BTreeSet::new();
    let lib = read(&src.join("lib.rs"));
    let mut roots = vec![(String::new(), src.join("lib.rs"), lib)];
    // Folders within folders: each declared module with a `mod.rs`.
    let mut i = 0;
    while i < roots.len() {
        let (prefix, _, text) = roots[i].clone();
        let dir = src.join(prefix.trim_end_matches("::").replace("::", "/"));
        for g in declared_modules(&text) {
            let root = dir.join(&g).join("mod.rs");
            if root.exists() {
                let text = read(&root);
                roots.push((format!("{prefix}{g}::"), root, text));
            }
        }
        i += 1;
    }
    for (prefix, path, text) in &roots {
        for m in declared_modules(text) {
            assert!(
                text.contains(&format!("[`{m}`]")),
                "{}'s docs do not list [`{m}`]",
                path.display()
            );
            declared.insert(format!("{prefix}{m}"));
        }
    }
    assert!(
        roots.len() >= 4,
        "found {} folders with a mod.rs",
        roots.len() - 1
    );
    let files: BTreeSet<String> = rust_files(&src)
        .iter()
        .filter_map(|p| module_name(p, &src, false))
        .collect();
    assert!(files.len() >= 10, "found {files:?}");
    assert_eq!(
        declared, files,
        "the `pub mod`s of common/src/lib.rs and its folders' mod.rs, and the files of common/src differ"
    );
}

/// For each common module: the lesson folders and the other common
/// modules that use it.
fn common_users(
    common: &[(String, String)],
    lessons: &[(u32, String)],
) -> BTreeMap<String, (BTreeSet<u32>, BTreeSet<String>)> {
    let mut users = BTreeMap::new();
    for (m, _) in common {
        let by_lessons = lessons
            .iter()
            .filter(|(_, text)| {
                text.contains(&format!("common::{m}::"))
                    || text.contains(&format!("common::{m};"))
                    || text.contains(&format!("common::{{{m}"))
            })
            .map(|(n, _)| *n)
            .collect();
        let by_common = common
            .iter()
            .filter(|(other, text)| {
                other != m
                    && (text.contains(&format!("crate::{m}::"))
                        || text.contains(&format!("crate::{m};")))
            })
            .map(|(other, _)| other.clone())
            .collect();
        users.insert(m.clone(), (by_lessons, by_common));
    }
    users
}

fn single_lesson_modules(
    users: &BTreeMap<String, (BTreeSet<u32>, BTreeSet<String>)>,
) -> Vec<String> {
    users
        .iter()
        .filter(|(_, (l, c))| l.len() == 1 && c.is_empty())
        .map(|(m, (l, _))| {
            format!(
                "common::{m} is used only by lesson {:02}",
                l.first().unwrap_or(&0)
            )
        })
        .collect()
}

#[test]
fn single_lesson_checker_works() {
    let common = vec![
        ("render".to_string(), "use crate::camera::x;".to_string()),
        ("camera".to_string(), String::new()),
        ("cube".to_string(), String::new()),
        ("gpu".to_string(), String::new()),
    ];
    let lessons = vec![
        (
            4,
            "use common::cube::Cube;\nuse common::gpu::Gpu;".to_string(),
        ),
        (
            5,
            "use common::gpu::Gpu;\nuse common::camera::light;".to_string(),
        ),
    ];
    let users = common_users(&common, &lessons);
    let single = single_lesson_modules(&users);
    assert_eq!(
        single,
        ["common::cube is used only by lesson 04"],
        "{users:?}"
    );
}

#[test]
fn no_common_module_serves_a_single_lesson() {
    let src = repo_root().join("common/src");
    let common: Vec<(String, String)> = rust_files(&src)
        .iter()
        .filter_map(|p| Some((module_name(p, &src, false)?, read(p))))
        .collect();
    let root = repo_root().join("lessons");
    let mut lessons: BTreeMap<u32, String> = BTreeMap::new();
    for p in rust_files(&root) {
        if let Some(n) = lesson_of(&p, &root) {
            lessons.entry(n).or_default().push_str(&read(&p));
        }
    }
    let lessons: Vec<(u32, String)> = lessons.into_iter().collect();
    assert!(lessons.len() >= 8, "found {} lesson folders", lessons.len());
    let users = common_users(&common, &lessons);
    assert!(
        users.values().any(|(l, _)| l.len() >= 8),
        "no common module is used by every lesson: the checker finds nothing"
    );
    let single = single_lesson_modules(&users);
    assert!(single.is_empty(), "{}", single.join("\n"));
}

// ---------------------------------------------------------------------------
// Binaries that `cargo test` does not compile as test harnesses
// ---------------------------------------------------------------------------

/// The `path` of every `[[bin]]` of a Cargo.toml that sets `test = false`.
fn untested_bins(manifest: &str) -> Vec<String> {
    let mut out = Vec::new();
    for block in manifest.split("[[bin]]").skip(1) {
        // The block ends at the next table header.
        let block: Vec<&str> = block
            .lines()
            .skip(1)
            .take_while(|l| !l.trim_start().starts_with('['))
            .map(str::trim)
            .collect();
        if !block.contains(&"test = false") {
            continue;
        }
        if let Some(path) = block.iter().find_map(|l| l.strip_prefix("path = ")) {
            out.push(path.trim_matches('"').to_string());
        }
    }
    out
}

/// A binary's files: its `main.rs` and the modules it declares (`mod x;`,
/// `x.rs` beside it).
fn bin_files(main: &Path, text: &str) -> Vec<PathBuf> {
    let dir = main.parent().expect("a folder");
    let mut out = vec![main.to_path_buf()];
    for l in text.lines() {
        let l = l
            .trim()
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub ");
        if let Some(name) = l.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
            out.push(dir.join(format!("{name}.rs")));
        }
    }
    out
}

/// The lines (1-based) of `text` that declare a unit test.
fn test_attributes(text: &str) -> Vec<usize> {
    (text.lines().enumerate())
        .filter(|(_, l)| {
            let l = l.trim();
            l.starts_with("#[test]") || l.starts_with("#[cfg(test)]")
        })
        .map(|(i, _)| i + 1)
        .collect()
}

#[test]
fn untested_bin_checker_works() {
    let manifest = "[[bin]]\nname = \"a\"\npath = \"a/main.rs\"\ntest = false\n\n\
                    [[bin]]\nname = \"b\"\npath = \"b/main.rs\"\n\n[features]\ntest = false\n";
    assert_eq!(untested_bins(manifest), ["a/main.rs"]);
    let main = "use x;\nmod harness;\npub(crate) mod view;\nfn main() {}\n";
    let files = bin_files(Path::new("l/main.rs"), main);
    assert_eq!(
        files,
        [
            PathBuf::from("l/main.rs"),
            PathBuf::from("l/harness.rs"),
            PathBuf::from("l/view.rs")
        ]
    );
    assert_eq!(
        test_attributes("fn a() {}\n  #[test]\nfn b() {}\n#[cfg(test)]\n"),
        [2, 4]
    );
}

/// The lesson binaries and the generator's are built with `test = false`
/// (Cargo.toml, book/generate/Cargo.toml): `cargo test` would otherwise
/// compile each again as an empty test harness. A
/// unit test written in one of their files would then never run, so none
/// may hold one: the lesson's tests go in the library (`lessons/`) or in
/// `tests/`.
#[test]
fn no_untested_binary_holds_a_unit_test() {
    let root = repo_root();
    // Each manifest's binaries, by their path from the repository's root.
    let mut bins = Vec::new();
    for dir in ["", "book/generate"] {
        let manifest = read(&root.join(dir).join("Cargo.toml"));
        bins.extend(
            untested_bins(&manifest)
                .into_iter()
                .map(|b| root.join(dir).join(b)),
        );
    }
    assert!(
        bins.len() >= 11,
        "{bins:?}: the ten lessons and the generator at least"
    );
    let mut found = Vec::new();
    for main in &bins {
        for f in bin_files(main, &read(main)) {
            for line in test_attributes(&read(&f)) {
                found.push(format!("{}:{line}", f.display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "a unit test in a binary that `cargo test` does not build as a test (Cargo.toml: test = false), so it never runs; move it to the library or to tests/:\n{}",
        found.join("\n")
    );
}
