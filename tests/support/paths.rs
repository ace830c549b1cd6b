//! Where the tests' files are: the repository's root ([`root`]), the
//! scratch folder cargo gives integration tests ([`target_tmp`]) and a
//! fresh output folder there ([`out_dir`]), the committed scenes
//! ([`scene_path`]).

use std::path::{Path, PathBuf};

/// The repository's root: this library is its `tests/support/` (its
/// path checked, so that moving the library is an error, not another
/// folder read). A test can use this or its own
/// `env!("CARGO_MANIFEST_DIR")`, which is the root too (the tests are the
/// root package's); this library's code can only use this.
pub fn root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = here.parent().and_then(Path::parent);
    match root {
        Some(r) if r.join("tests/support/Cargo.toml") == here.join("Cargo.toml") => r.to_path_buf(),
        _ => panic!(
            "{}: the test support library is not the root's tests/support/",
            here.display()
        ),
    }
}

/// The folder cargo gives integration tests for their files
/// (`CARGO_TARGET_TMPDIR`, `<target>/tmp`). Cargo sets it only when it
/// compiles an integration test, not this library, so it is found from
/// the running test binary, which cargo puts in `<profile>/deps/`
/// (`target/release/deps/lesson_01-…`): the folder `tmp` beside the
/// profile's folder (`target/tmp`; with `--target T`, `target/T/tmp`). A
/// test binary anywhere else is an error that says so. A test can read its
/// own `env!("CARGO_TARGET_TMPDIR")`, the same folder.
pub fn target_tmp() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let above_profile = exe
        .parent()
        .filter(|deps| deps.file_name().is_some_and(|n| n == "deps"))
        .and_then(Path::parent)
        .and_then(Path::parent);
    match above_profile {
        Some(above) => above.join("tmp"),
        None => panic!(
            "{}: not a test binary in cargo's <target>/<profile>/deps/ folder",
            exe.display()
        ),
    }
}

/// A fresh output folder under the target directory.
pub fn out_dir(name: &str) -> PathBuf {
    let backend = std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "auto".into());
    let dir = target_tmp().join(format!("{name}-{backend}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create test output folder");
    dir
}

/// A committed scene file, by name (`"lesson_02_grazing_85.toml"`).
pub fn scene_path(name: &str) -> PathBuf {
    root().join("scenes").join(name)
}
