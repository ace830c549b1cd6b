//! No lesson's shader branches on a variant at run time (issue 50).
//!
//! A variant's choices (a mode, a tap count, a kernel, a port's model, a
//! switch) are pipeline constants: WGSL `override`s or entry points, fixed
//! when the variant's pipeline is built, so that each pipeline holds only
//! its own path and its loops unroll. A choice read from a buffer keeps
//! every variant's code in every pipeline, and a software rasteriser runs
//! every case, masked (lesson 03's `MODE` and lesson 10's `SOFT_MODE` say
//! what it cost).
//!
//! Two rules over every WGSL file under `shaders/`:
//! 1. A struct bound as a uniform or storage buffer holds no integer or
//!    boolean field (the type a switch or a count has) unless it is listed
//!    below as the scene's data, with why.
//! 2. No `if`, `switch`, `for`, `while` or `break if` reads a buffer's
//!    field (directly, or through a `let` that holds it) unless that field
//!    is listed below as the scene's data.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Fields of bound structs that branches may read: the scene's data, not
/// a variant's choice. (buffer variable or struct, field, why).
const SCENE_DATA: &[(&str, &str, &str)] = &[
    (
        "Level",
        "below",
        "lesson 10's min/max chain: where the level below starts in the buffer, the map's geometry",
    ),
    (
        "Level",
        "start",
        "lesson 10's min/max chain: where the level starts in the buffer, the map's geometry",
    ),
    (
        "Level",
        "side",
        "lesson 10's min/max chain: the level's side, the map's geometry",
    ),
    (
        "level",
        "side",
        "lesson 10's min/max chain: the threads past the level's side write nothing",
    ),
    (
        "light",
        "position_or_dir",
        "its w says the light's kind (directional or not): the scene's",
    ),
    (
        "light",
        "spot",
        "a spot's cone: the scene's light, whichever variant runs",
    ),
    (
        "light",
        "color_range",
        "a light's range (lesson 08): the scene's",
    ),
    (
        "camera",
        "eye",
        "which side of a surface the camera sees: geometry",
    ),
    (
        "Object",
        "id",
        "the object's index, written to the id target: geometry",
    ),
    (
        "params",
        "edges",
        "lesson 05's compute pass: the mesh's edge count decides which thread extrudes what",
    ),
    (
        "params",
        "faces",
        "lesson 05's compute pass: the mesh's face count",
    ),
    (
        "Params",
        "slot",
        "lesson 05: the caster's slot in the shared buffers",
    ),
    (
        "Params",
        "off_positions",
        "lesson 05: offsets into the mesh's buffer",
    ),
    (
        "Params",
        "off_normals",
        "lesson 05: offsets into the mesh's buffer",
    ),
    (
        "Params",
        "off_triangles",
        "lesson 05: offsets into the mesh's buffer",
    ),
    (
        "Params",
        "off_edges",
        "lesson 05: offsets into the mesh's buffer",
    ),
    (
        "Params",
        "off_edge_faces",
        "lesson 05: offsets into the mesh's buffer",
    ),
    (
        "Params",
        "row",
        "lesson 05: the caster's row of the indirect arguments",
    ),
    (
        "DrawArgs",
        "instance_count",
        "lesson 05: indirect draw arguments the pass writes",
    ),
    (
        "DrawArgs",
        "first_vertex",
        "lesson 05: indirect draw arguments the pass writes",
    ),
    (
        "DrawArgs",
        "first_instance",
        "lesson 05: indirect draw arguments the pass writes",
    ),
    (
        "soft",
        "perspective",
        "lesson 10: the light's projection (spot or sun); one pipeline serves both lights",
    ),
    (
        "blur",
        "perspective",
        "lesson 10: the light's projection, as `soft.perspective`",
    ),
    (
        "cascades", // not a counter: a WGSL struct
        "split_far",
        "lesson 09: where the view's slices end, a float of the camera's",
    ),
];

fn allowed(var: &str, ty: &str, field: &str) -> bool {
    field.starts_with('_')
        || SCENE_DATA
            .iter()
            .any(|&(v, f, _)| (v == var || v == ty) && f == field)
}

fn wgsl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("shaders/ is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            wgsl_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            out.push(path);
        }
    }
}

/// A line without its `//` comment.
fn code(line: &str) -> &str {
    line.split("//").next().unwrap_or("")
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// Every `name.field` in `text` whose `name` is a whole word.
fn reads<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let mut found = Vec::new();
    let pattern = format!("{name}.");
    let mut from = 0;
    while let Some(at) = text[from..].find(&pattern) {
        let start = from + at;
        let before = text[..start].chars().next_back();
        let rest = &text[start + pattern.len()..];
        let len = rest.find(|c: char| !is_ident(c)).unwrap_or(rest.len());
        if !before.is_some_and(|c| is_ident(c) || c == '.') && len > 0 {
            found.push(&rest[..len]);
        }
        from = start + pattern.len();
    }
    found
}

/// Whether `text` holds `word` as a whole identifier.
fn has_word(text: &str, word: &str) -> bool {
    text.match_indices(word).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + word.len()..].chars().next();
        !before.is_some_and(is_ident) && !after.is_some_and(is_ident)
    })
}

/// The shaders' sources, by path from the repository root.
fn sources() -> BTreeMap<String, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    wgsl_files(&root.join("shaders"), &mut files);
    assert!(files.len() > 20, "found the shaders ({})", files.len());
    files
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("a readable shader");
            let name = p.strip_prefix(root).unwrap().display().to_string();
            (name, text)
        })
        .collect()
}

/// Struct name → its fields (name, type), from every file.
fn structs(sources: &BTreeMap<String, String>) -> BTreeMap<String, Vec<(String, String)>> {
    let mut out = BTreeMap::new();
    for text in sources.values() {
        let mut current: Option<(String, Vec<(String, String)>)> = None;
        for line in text.lines() {
            let line = code(line).trim();
            if let Some(rest) = line.strip_prefix("struct ") {
                let name = rest.trim_end_matches('{').trim().to_string();
                current = Some((name, Vec::new()));
            } else if line.starts_with('}') {
                if let Some((name, fields)) = current.take() {
                    out.insert(name, fields);
                }
            } else if let Some((_, fields)) = current.as_mut() {
                if let Some((field, ty)) = line.trim_end_matches(',').split_once(':') {
                    let field = field.split_whitespace().last().unwrap_or("");
                    fields.push((field.to_string(), ty.trim().to_string()));
                }
            }
        }
    }
    out
}

/// Every buffer variable: (file, variable, its type).
fn buffers(sources: &BTreeMap<String, String>) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    for (file, text) in sources {
        for line in text.lines() {
            let line = code(line);
            if !(line.contains("var<uniform>") || line.contains("var<storage")) {
                continue;
            }
            let decl = line.rsplit('>').next().unwrap_or("");
            if let Some((name, ty)) = decl.split_once(':') {
                let ty = ty.trim().trim_end_matches(';').to_string();
                out.push((file.clone(), name.trim().to_string(), ty));
            }
        }
    }
    out
}

fn integer(ty: &str) -> bool {
    ["u32", "i32", "bool"].iter().any(|t| ty.contains(t))
}

/// Rule 1: the integer and boolean fields of bound structs.
fn integer_fields(sources: &BTreeMap<String, String>) -> Vec<String> {
    let structs = structs(sources);
    let mut bad = BTreeSet::new();
    for (file, var, ty) in buffers(sources) {
        let Some(fields) = structs.get(&ty) else {
            continue;
        };
        for (field, fty) in fields {
            if integer(fty) && !allowed(&var, &ty, field) {
                bad.insert(format!(
                    "{file}: `{var}.{field}: {fty}` (struct {ty}), an integer in a buffer: a variant's mode or count? Make it an `override`, or list it in SCENE_DATA with why"
                ));
            }
        }
    }
    bad.into_iter().collect()
}

fn is_control(line: &str) -> bool {
    let t = line.trim_start_matches(['}', ' ']);
    [
        "if ", "if(", "else if", "switch ", "for (", "for(", "while ", "break if",
    ]
    .iter()
    .any(|k| t.starts_with(k))
}

/// Rule 2: branches and loops that read a buffer's field.
fn branches_on_buffers(sources: &BTreeMap<String, String>) -> Vec<String> {
    let buffers = buffers(sources);
    let mut bad = Vec::new();
    for (file, text) in sources {
        // `let x = var.field;` (or `var.field.w`, `u32(var.field)`,
        // `i32(…)`, `f32(…)`): x is a copy of the field.
        let mut aliases: Vec<(String, String, String, String)> = Vec::new();
        for line in text.lines().map(code) {
            let t = line.trim();
            let Some(rest) = t.strip_prefix("let ").or_else(|| t.strip_prefix("var ")) else {
                continue;
            };
            let Some((name, value)) = rest.split_once('=') else {
                continue;
            };
            let name = name.split(':').next().unwrap_or("").trim();
            let mut value = value.trim().trim_end_matches(';').trim();
            for cast in ["u32(", "i32(", "f32("] {
                if let Some(inner) = value.strip_prefix(cast).and_then(|v| v.strip_suffix(')')) {
                    value = inner;
                }
            }
            for (_, var, ty) in &buffers {
                let Some(path) = value.strip_prefix(&format!("{var}.")) else {
                    continue;
                };
                // The field, then at most a swizzle (`forward.w`).
                let (field, swizzle) = path.split_once('.').unwrap_or((path, "x"));
                let swizzle = swizzle.chars().all(|c| "xyzwrgba".contains(c));
                if field.chars().all(is_ident) && swizzle {
                    aliases.push((name.into(), var.clone(), ty.clone(), field.into()));
                }
            }
        }
        for (n, line) in text.lines().enumerate() {
            let line = code(line);
            if !is_control(line) {
                continue;
            }
            let mut read = Vec::new();
            for (_, var, ty) in &buffers {
                for field in reads(line, var) {
                    read.push((var.clone(), ty.clone(), field.to_string()));
                }
            }
            for (alias, var, ty, field) in &aliases {
                if has_word(line, alias) {
                    read.push((var.clone(), ty.clone(), field.clone()));
                }
            }
            for (var, ty, field) in read {
                if !allowed(&var, &ty, &field) {
                    bad.push(format!(
                        "{file}:{}: `{}` branches on `{var}.{field}`, read from a buffer at run time: a variant's choice belongs in an `override` (or list the field in SCENE_DATA if it is the scene's)",
                        n + 1,
                        line.trim()
                    ));
                }
            }
        }
    }
    bad
}

#[test]
fn no_shader_reads_a_variants_choice_from_a_buffer() {
    let sources = sources();
    let mut bad = integer_fields(&sources);
    bad.extend(branches_on_buffers(&sources));
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The rules catch what they are for: lesson 10's `soft.mode` put back
/// (the struct's field and the switch on it), a loop bound read through a
/// `let`, and a flag in a uniform.
#[test]
fn the_rules_catch_a_mode_read_from_a_buffer() {
    let mut sources = sources();
    let soft = "shaders/lesson_10/soft.wgsl";
    let text = sources[soft].clone();
    assert!(text.contains("struct Soft {\n") && text.contains("switch SOFT_MODE {"));
    let mode_back = text
        .replace("struct Soft {\n", "struct Soft {\n    mode: u32,\n")
        .replace("switch SOFT_MODE {", "switch soft.mode {");
    sources.insert(soft.into(), mode_back);
    let fields = integer_fields(&sources);
    assert!(
        fields.iter().any(|b| b.contains("`soft.mode: u32`")),
        "{fields:?}"
    );
    let branches = branches_on_buffers(&sources);
    assert!(
        branches.iter().any(|b| b.contains("`soft.mode`")),
        "{branches:?}"
    );

    let mut sources = self::sources();
    let peers = "shaders/lesson_10/peers.wgsl";
    let text = sources[peers].clone();
    assert!(text.contains("    let n = SEARCH_TAPS;"));
    let through_let = text.replace("    let n = SEARCH_TAPS;", "    let n = soft.size;");
    sources.insert(peers.into(), through_let);
    let branches = branches_on_buffers(&sources);
    assert!(
        branches.iter().any(|b| b.contains("`soft.size`")),
        "{branches:?}"
    );

    // Lesson 09's cascade count back in the buffer, as it was: the w of a
    // vec4, through a conversion and a `let`, bounding a loop.
    let mut sources = self::sources();
    let csm = "shaders/lesson_09/csm.wgsl";
    let text = sources[csm].clone();
    assert!(text.contains("    let count = CASCADES;"));
    let count_back = text.replace(
        "    let count = CASCADES;",
        "    let count = u32(cascades.forward.w);",
    );
    sources.insert(csm.into(), count_back);
    let branches = branches_on_buffers(&sources);
    assert!(
        branches.iter().any(|b| b.contains("`cascades.forward`")),
        "{branches:?}"
    );
    assert!(integer("vec4<u32>") && integer("bool") && !integer("f32"));
}

/// Every listed field is still read somewhere: a stale entry would let a
/// later variant's switch of the same name through.
#[test]
fn every_scene_data_entry_is_a_field_of_a_bound_struct() {
    let sources = sources();
    let structs = structs(&sources);
    let buffers = buffers(&sources);
    for &(var, field, why) in SCENE_DATA {
        assert!(!why.is_empty());
        let found = buffers.iter().any(|(_, v, ty)| {
            (v == var || ty == var)
                && structs
                    .get(ty)
                    .is_some_and(|f| f.iter().any(|(name, _)| name == field))
        }) || structs
            .get(var)
            .is_some_and(|f| f.iter().any(|(name, _)| name == field));
        assert!(
            found,
            "SCENE_DATA lists `{var}.{field}`, which no bound struct has"
        );
    }
}
