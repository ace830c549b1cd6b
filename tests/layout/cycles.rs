//! No import cycles between the modules of any crate of [`CRATES`]: the
//! modules a file uses, read from its paths (`crate::`, `super::`,
//! `self::`, its own submodules), and a cycle among them.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

use crate::crates::CRATES;
use crate::{module_name, read, repo_root, rust_files};

/// The paths a use tree spells from its start, to where it ends:
/// `a::b::C;` → [a, b, C]; `a::{b, c::{d, self}}` → [a, b], [a, c, d],
/// [a, c, self].
fn tree_paths(tree: &str) -> Vec<Vec<String>> {
    let mut segs = Vec::new();
    let mut rest = tree;
    loop {
        let ident: String = (rest.chars())
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if ident.is_empty() {
            break;
        }
        segs.push(ident.clone());
        match rest[ident.len()..].strip_prefix("::") {
            Some(r) => rest = r,
            None => return vec![segs],
        }
    }
    let Some(group) = rest.strip_prefix('{') else {
        return vec![segs];
    };
    // The group's items, split at its own commas, up to its closing brace.
    let (mut items, mut depth, mut start) = (Vec::new(), 0, 0);
    for (i, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => {
                items.push(&group[start..i]);
                break;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&group[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    (items.into_iter())
        .flat_map(|item| tree_paths(item.trim()))
        .filter(|p| !p.is_empty())
        .map(|p| [segs.clone(), p].concat())
        .collect()
}

/// The name of the inline module a top-level line opens (`mod tests {`,
/// `pub(crate) mod tests {`), if it opens one.
fn inline_module(line: &str) -> Option<&str> {
    let rest = ["pub(crate) mod ", "pub mod ", "mod "]
        .iter()
        .find_map(|p| line.strip_prefix(p))?;
    rest.strip_suffix(" {")
}

/// Where `token` starts a path in `code`: not inside a longer name nor
/// after another segment (`super::` in `super::super::` counts once).
fn path_starts<'a>(code: &'a str, token: &'a str) -> impl Iterator<Item = usize> + 'a {
    code.match_indices(token).map(|(at, _)| at).filter(|&at| {
        let before = code[..at].chars().next_back().unwrap_or(' ');
        !(before.is_alphanumeric() || before == '_' || before == ':')
    })
}

/// The modules among `known` that `text`, the file of module `me`, uses:
/// through a path from the crate (`crate::a::b`), from a parent
/// (`super::x`, `super::super::x`) or from itself (`self::x`), `use`
/// groups included (`crate::{a, b::{c}}`, across lines), and its own
/// submodules by their names (`costs::rows`, a 2018 path). Code in a
/// top-level inline module (`mod tests {` to its `}`, as rustfmt writes
/// them) is one level deeper, so that its `super::` is `me`. Comments are
/// skipped. A use of `me`'s own parents (`super::A`: what a module shares
/// with its submodules) is no edge: to the modules outside, a module and
/// the submodules it declares are one, used through the parent, whose use
/// of a submodule is an edge (`crate::a` → `a` → `a::b` → `crate::a` is a
/// cycle; `a` → `a::b` → `a` alone is not).
fn uses(me: &str, text: &str, known: &BTreeSet<String>) -> BTreeSet<String> {
    let me_path: Vec<String> = me.split("::").map(String::from).collect();
    // The code, and the module of each line, by the offset it starts at.
    let (mut code, mut lines) = (String::new(), Vec::new());
    let mut inline: Option<String> = None;
    for line in text.lines() {
        let line = line.split("//").next().unwrap_or("");
        if inline.is_some() && line == "}" {
            inline = None;
        } else if let Some(name) = inline_module(line).filter(|_| inline.is_none()) {
            inline = Some(name.to_string());
        }
        let mut module = me_path.clone();
        module.extend(inline.clone());
        lines.push((code.len(), module));
        code.push_str(line);
        code.push('\n');
    }
    let mut out = BTreeSet::new();
    for child in known
        .iter()
        .filter_map(|k| k.strip_prefix(&format!("{me}::")))
    {
        let token = format!("{child}::");
        if !child.contains("::") && path_starts(&code, &token).next().is_some() {
            out.insert(format!("{me}::{child}"));
        }
    }
    for start in ["crate::", "super::", "self::"] {
        for at in path_starts(&code, start) {
            let line = lines.partition_point(|(o, _)| *o <= at) - 1;
            for path in tree_paths(&code[at..]) {
                let mut full = match path[0].as_str() {
                    "crate" => Vec::new(),
                    _ => lines[line].1.clone(),
                };
                let mut segs = path[1..].iter().peekable();
                if path[0] == "super" {
                    full.pop();
                    while segs.next_if(|s| *s == "super").is_some() {
                        full.pop();
                    }
                }
                full.extend(segs.filter(|s| *s != "self").cloned());
                let used = (1..=full.len())
                    .rev()
                    .map(|n| full[..n].join("::"))
                    .find(|m| known.contains(m));
                let own = |m: &String| m == me || me.starts_with(&format!("{m}::"));
                if let Some(m) = used.filter(|m| !own(m)) {
                    out.insert(m);
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

/// Each module of a crate's folder `src` (root file `root`) and the
/// modules it uses.
fn import_graph(src: &Path, root: &str) -> BTreeMap<String, BTreeSet<String>> {
    let files: Vec<(String, String)> = rust_files(src)
        .into_iter()
        .filter_map(|p| Some((module_name(&p, src, root)?, read(&p))))
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

/// Writes a crate's files under a fresh folder of the tests' scratch space.
fn scratch_crate(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = fs::remove_dir_all(&dir);
    for (path, text) in files {
        let path = dir.join(path);
        fs::create_dir_all(path.parent().expect("a folder")).expect("the scratch folder");
        fs::write(&path, text).expect("a scratch file");
    }
    dir
}

/// The naming of `x.rs` + `x/` folders (the generator's), of `mod.rs`
/// folders (common's) and of `#[path]` folders; a cycle between `a.rs`
/// and `a/b.rs` through `c`, found through a `use` group across lines and
/// a submodule named by itself; none between `a` and its own `a::b` alone.
#[test]
fn module_naming_checker_works() {
    let files = [
        ("lib.rs", "pub mod a;\npub mod c;\npub mod d;\n"),
        ("main.rs", "use generator::a;\n"),
        ("a.rs", "mod b;\npub struct A;\npub use b::f;\n"),
        (
            "a/b.rs",
            "use super::A;\nuse crate::{\n    c::C,\n};\n\n#[cfg(test)]\nmod tests {\n    use super::super::A;\n}\n",
        ),
        ("c.rs", "pub struct C;\nuse crate::a::A;\n"),
        ("d/mod.rs", "mod e;\n"),
        ("d/e.rs", "use super::super::c::C;\n"),
        ("d/unit_tests/e.rs", "use crate::a::A;\n"),
    ];
    let src = scratch_crate("layout_naming", &files);
    let names: Vec<String> = (rust_files(&src).iter())
        .map(|p| module_name(p, &src, "lib.rs").unwrap_or("-".into()))
        .collect();
    // By path: a/b.rs, a.rs, c.rs, d/e.rs, d/mod.rs, d/unit_tests/e.rs,
    // lib.rs, main.rs.
    assert_eq!(names, ["a::b", "a", "c", "d::e", "d", "-", "-", "-"]);
    let graph = import_graph(&src, "lib.rs");
    let set = |m: &[&str]| m.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>();
    assert_eq!(graph["a"], set(&["a::b"]), "{graph:?}");
    assert_eq!(graph["a::b"], set(&["c"]), "{graph:?}");
    assert_eq!(graph["c"], set(&["a"]), "{graph:?}");
    assert_eq!(graph["d::e"], set(&["c"]), "{graph:?}");
    assert_eq!(
        find_cycle(&graph).expect("a cycle"),
        ["a", "a::b", "c", "a"]
    );
    // `c` without its import: `a` and `a::b` alone make no cycle.
    let files = [files[0], files[2], files[3], ("c.rs", "pub struct C;\n")];
    let graph = import_graph(&scratch_crate("layout_naming_own", &files), "lib.rs");
    assert_eq!(find_cycle(&graph), None, "{graph:?}");
}

#[test]
fn no_import_cycles() {
    let mut cycles = Vec::new();
    for &(dir, root, min_modules) in CRATES {
        let graph = import_graph(&repo_root().join(dir), root);
        assert!(
            graph.len() >= min_modules,
            "{dir}: expected {min_modules} modules at least, found {}",
            graph.len()
        );
        assert!(
            min_modules == 0 || graph.values().any(|u| !u.is_empty()),
            "{dir}: found no imports at all"
        );
        if let Some(cycle) = find_cycle(&graph) {
            cycles.push(format!("{dir}: import cycle {}", cycle.join(" -> ")));
        }
    }
    assert!(cycles.is_empty(), "{}", cycles.join("\n"));
}
