//! The book's live lessons: the web module committed in `book/src/web/`
//! (`workbook web`) must be built from the sources in this tree. Its
//! `SOURCES` file holds the digest of every file it was built from
//! (`book/generate/web_sources.rs`); a change to a lesson, a shader, a
//! default scene or `common` without `workbook web` fails here, so a
//! reader's page never runs an older lesson than the chapter prints.
//!
//! What the page does with the module is checked in a real browser by
//! `.ci/web-check` (CI runs it after the tests).

use std::path::{Path, PathBuf};

use generator::web_sources;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn web_module_is_built_from_these_sources() {
    let root = root();
    let web = root.join("book/src/web");
    for f in ["workbook_web.js", "workbook_web_bg.wasm.gz", "SOURCES"] {
        assert!(
            web.join(f).is_file(),
            "book/src/web/{f} is missing: run `cargo run --release --bin workbook -- web`"
        );
    }
    let stamped = std::fs::read_to_string(web.join("SOURCES")).expect("SOURCES");
    let now = web_sources::digest(&root).expect("digest of the sources");
    assert_eq!(
        stamped.trim(),
        now,
        "book/src/web/ was built from other sources than this tree's (a lesson, shader, scene or common changed since): run `cargo run --release --bin workbook -- web` (it needs `rustup target add wasm32-unknown-unknown` and wasm-bindgen-cli at Cargo.lock's version) and commit book/src/web/ and book/src/generated/web/"
    );
}

/// The digest moves when any byte of a source moves, and not with the
/// line endings a checkout chose.
#[test]
fn digest_sees_a_changed_byte_and_not_line_endings() {
    let dir = std::env::temp_dir().join(format!("workbook-web-digest-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let write = |p: &str, text: &str| {
        let path = dir.join(p);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    };
    write("Cargo.toml", "[workspace]\n");
    write("lessons/lesson_05/main.rs", "fn main() {\n    draw();\n}\n");
    write("shaders/lesson_05/volume.wgsl", "// w = 0\n");
    write("target/ignored.rs", "anything\n");
    let digest = |d: &Path| web_sources::digest(d).unwrap();
    let before = digest(&dir);
    write("target/ignored.rs", "a build output, not a source\n");
    assert_eq!(digest(&dir), before, "a build output moved the digest");
    write(
        "lessons/lesson_05/main.rs",
        "fn main() {\r\n    draw();\r\n}\r\n",
    );
    assert_eq!(digest(&dir), before, "line endings moved the digest");
    write("shaders/lesson_05/volume.wgsl", "// w = 1\n");
    assert_ne!(digest(&dir), before, "a changed shader kept the digest");
    std::fs::remove_dir_all(&dir).unwrap();
}
