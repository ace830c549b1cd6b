//! Writes every built-in mesh to `assets/<name>.obj`.
//!
//! Run: `cargo run --release --bin gen_assets`
//!
//! The built-ins are made by code (`common::scene::mesh::builtin`); these files
//! are copies for other tools (a model viewer, Blender, a scene that wants
//! a path). `tests/assets.rs` checks that they still match the code, so
//! after changing a built-in, run this and commit the new files.

use std::path::Path;

use common::scene::mesh::{builtin, BUILTIN_NAMES};
use common::scene::obj::to_obj_string;
use common::{Context, Result};

fn run() -> Result<()> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("{}: cannot create folder", dir.display()))?;
    for name in BUILTIN_NAMES {
        let mesh = builtin(name)?;
        let path = dir.join(format!("{name}.obj"));
        std::fs::write(&path, to_obj_string(&mesh))
            .with_context(|| format!("{}: cannot write", path.display()))?;
        println!(
            "{}: {} vertices, {} triangles",
            path.display(),
            mesh.positions.len(),
            mesh.triangle_count()
        );
    }
    Ok(())
}

fn main() {
    if let Err(e) = run() {
        eprintln!("gen_assets: {e:#}");
        std::process::exit(1);
    }
}
