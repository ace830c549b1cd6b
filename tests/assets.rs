//! The files in `assets/` match the built-in meshes they were generated
//! from, load back through the OBJ loader, and bad OBJ input fails with a
//! message that names the file.

use std::path::{Path, PathBuf};

use common::scene::mesh::{builtin, BUILTIN_NAMES};
use common::scene::obj::{load_obj, to_obj_string};
use workbook::lesson_05::adjacency::validate;

fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(format!("{name}.obj"))
}

#[test]
fn assets_match_the_builtin_meshes() {
    for name in BUILTIN_NAMES {
        let expected = to_obj_string(&builtin(name).unwrap());
        let path = asset(name);
        let committed = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| {
                panic!(
                    "{}: {e}; run `cargo run --release --bin gen_assets`",
                    path.display()
                )
            })
            .replace("\r\n", "\n");
        if committed != expected {
            let line = committed
                .lines()
                .zip(expected.lines())
                .position(|(a, b)| a != b);
            panic!(
                "{} differs from `builtin({name:?})` (first at line {}); \
                 run `cargo run --release --bin gen_assets` and commit the result",
                path.display(),
                line.map_or("end".to_string(), |l| (l + 1).to_string())
            );
        }
    }
}

#[test]
fn assets_load_back_closed() {
    for name in BUILTIN_NAMES {
        let mesh = builtin(name).unwrap();
        let loaded = load_obj(&asset(name)).unwrap();
        assert_eq!(loaded.name, name);
        assert_eq!(loaded.triangle_count(), mesh.triangle_count(), "{name}");
        assert_eq!(loaded.positions.len(), mesh.positions.len(), "{name}");
        let report = validate(&loaded);
        assert_eq!(report.closed, name != "plane", "{name}: {report}");
        assert_eq!(report.degenerate_triangles, 0, "{name}: {report}");
    }
}

/// Writes `text` to a file of its own under the temp folder.
fn temp_obj(tag: &str, text: &[u8]) -> PathBuf {
    let path =
        std::env::temp_dir().join(format!("shadow_workbook_{}_{tag}.obj", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

/// Loads `text` from a temp file, expects an error, and returns its message
/// after checking that it is one line naming the file.
fn load_error(tag: &str, text: &[u8]) -> String {
    let path = temp_obj(tag, text);
    let result = load_obj(&path);
    std::fs::remove_file(&path).unwrap();
    let message = format!("{:#}", result.expect_err(tag));
    assert!(
        message.starts_with(&path.display().to_string()),
        "{tag}: {message}"
    );
    assert!(!message.contains('\n'), "{tag}: {message}");
    message
}

#[test]
fn missing_file_is_an_error() {
    let path = std::env::temp_dir().join("shadow_workbook_no_such_file.obj");
    let message = format!("{:#}", load_obj(&path).unwrap_err());
    assert!(
        message.starts_with(&path.display().to_string()),
        "{message}"
    );
    assert!(message.contains("cannot read"), "{message}");
}

#[test]
fn garbage_text_is_an_error() {
    let message = load_error("garbage", b"Dear learner,\nthis is not a mesh.\n");
    assert!(message.contains("no triangles"), "{message}");
}

#[test]
fn binary_garbage_is_an_error() {
    let message = load_error("binary", b"v 0 0 0\n\xff\xfe\x00PNG\n");
    assert!(message.contains(":2: not UTF-8"), "{message}");
}

#[test]
fn malformed_line_is_an_error_with_its_line() {
    let message = load_error("malformed", b"v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n");
    assert!(message.contains(":3: cannot parse a vertex"), "{message}");
}

#[test]
fn nan_vertex_is_an_error() {
    let message = load_error("nan", b"v 0 0 0\nv 1 0 0\nv 0 NaN 0\nf 1 2 3\n");
    assert!(
        message.contains(":3: vertex position is not finite"),
        "{message}"
    );
}

#[test]
fn empty_file_is_an_error() {
    let message = load_error("empty", b"");
    assert!(message.contains("no triangles"), "{message}");
}

#[test]
fn out_of_range_index_is_an_error() {
    let message = load_error("range", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    assert!(
        message.contains(":4: face refers to vertex 4 but the file has 3"),
        "{message}"
    );
}

#[test]
fn all_degenerate_faces_are_an_error() {
    let message = load_error(
        "degenerate",
        b"v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n",
    );
    assert!(
        message.contains("every triangle is degenerate"),
        "{message}"
    );
}
