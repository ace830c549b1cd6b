//! `workbook web`: the lessons' web build, placed in the book. Every
//! lesson's own code compiles into one WebAssembly module
//! (`web/lib.rs`, for `wasm32-unknown-unknown`), which `wasm-bindgen`
//! wraps for the page and which ships gzip-compressed
//! (`book/src/web/`); each chapter's window figure gets its live bar
//! (`generated/web/lesson_NN.md`), which `book/theme/live.js` turns into the
//! lesson when the reader presses it.
//!
//! The module is committed with the book, as the book's figures are:
//! `web/SOURCES` holds a digest of every file it is built from, and
//! `tests/web.rs` fails when a source changed since (run `workbook web`).

use std::io::Write;
use std::path::Path;
use std::process::Command;

use anyhow::{bail, Context, Result};

use crate::window_shots::SHOTS;

/// The live lesson's size in the page's pixels (CSS): it fits the book's
/// text column (the screenshot, 960×540, is scaled down to it). The
/// frame is drawn at the screen's pixels under it.
pub const WEB_SIZE: (u32, u32) = (640, 360);

/// Where the module and its glue go, under `book/src/`.
pub const WEB_DIR: &str = "web";
/// The digest of the sources it was built from ([`crate::web_sources`]),
/// in [`WEB_DIR`].
pub const SOURCES_FILE: &str = "SOURCES";
/// What the page downloads: the compressed module, and its glue.
pub const MODULE: &str = "workbook_web_bg.wasm.gz";
pub const GLUE: &str = "workbook_web.js";

/// Builds the module, places it in `book/src/web/`, and writes each
/// chapter's live bar.
pub fn build(root: &Path) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let target = "wasm32-unknown-unknown";
    println!(
        "building the web module: {cargo} build --profile web --target {target} -p workbook-web"
    );
    let status = Command::new(&cargo)
        .args([
            "build",
            "--profile",
            "web",
            "--target",
            target,
            "-p",
            "workbook-web",
        ])
        .current_dir(root)
        .status()
        .with_context(|| format!("cannot run {cargo}"))?;
    if !status.success() {
        bail!("the web module did not build; if the target is missing: rustup target add {target}");
    }
    let wasm = root.join(format!("target/{target}/web/workbook_web.wasm"));
    let want = bindgen_version(root)?;
    let have = Command::new("wasm-bindgen").arg("--version").output();
    let have = match have {
        Ok(o) => String::from_utf8_lossy(&o.stdout).trim().to_string(),
        Err(_) => String::new(),
    };
    if !have.ends_with(&want) {
        bail!(
            "wasm-bindgen {want} is needed (found {:?}): cargo install wasm-bindgen-cli --version {want}",
            have
        );
    }
    let out = root.join("book/src").join(WEB_DIR);
    std::fs::create_dir_all(&out)?;
    let ok = Command::new("wasm-bindgen")
        .args(["--target", "web", "--no-typescript", "--out-dir"])
        .arg(&out)
        .arg(&wasm)
        .status()
        .context("cannot run wasm-bindgen")?
        .success();
    if !ok {
        bail!("wasm-bindgen failed on {}", wasm.display());
    }
    // The page fetches the module compressed and inflates it itself
    // (DecompressionStream): `mdbook serve` and a plain file server send
    // it as it is, so it is stored compressed.
    let raw_path = out.join("workbook_web_bg.wasm");
    let raw = std::fs::read(&raw_path)?;
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(&raw)?;
    let packed = gz.finish()?;
    std::fs::write(out.join(MODULE), &packed)?;
    std::fs::remove_file(&raw_path)?;
    let glue = std::fs::metadata(out.join(GLUE))?.len();
    let size = format!("{:.1} MB", (packed.len() as u64 + glue) as f64 / 1e6);
    crate::write(
        &out.join(SOURCES_FILE),
        &format!("{}\n", crate::web_sources::digest(root)?),
    )?;
    let generated = root.join("book/src/generated/web");
    std::fs::create_dir_all(&generated)?;
    for shot in &SHOTS {
        crate::write(
            &generated.join(format!("{}.md", shot.lesson)),
            // The window shot's view, the buffer view too (a page reads it
            // back a frame or more later, `common::gpu::read_later`).
            &live_bar(shot.lesson, shot.variant, shot.view, &size),
        )?;
    }
    crate::write(
        &generated.join("download.md"),
        &format!(
            "{size} (the module of all ten lessons, {:.1} MB before compression, and its {:.0} kB of glue)",
            raw.len() as f64 / 1e6,
            glue as f64 / 1e3
        ),
    )?;
    println!(
        "web module: {} bytes compressed ({} raw), in {}",
        packed.len(),
        raw.len(),
        out.display()
    );
    Ok(())
}

/// The live bar of a chapter's window figure: the button, and what the
/// lesson is started with (`data-args`: the window's flags).
fn live_bar(lesson: &str, variant: &str, view: &str, size: &str) -> String {
    let (w, h) = WEB_SIZE;
    let keys = "Drag to orbit, scroll to zoom, arrows move the light, V changes the variant, \
                1 to 5 the view (frame, visibility, diff, buffer, dv), H hides the overlay. Its \
                figure is the error against the exact reference, ray cast in a worker thread of \
                this page.";
    format!(
        "<p class=\"live-bar\" data-lesson=\"{lesson}\" data-args=\"--variant {variant} --view {view} --width {w} --height {h}\" data-size=\"{size}\" data-keys=\"{keys}\">\
<button type=\"button\">Run {lesson} live in this page</button>\
<span class=\"live-note\">WebGPU; loads {size} once for all ten lessons, then runs on your GPU.</span></p>\n"
    )
}

/// The wasm-bindgen version the lock file holds: the command-line tool
/// must be the same.
fn bindgen_version(root: &Path) -> Result<String> {
    let text = std::fs::read_to_string(root.join("Cargo.lock"))?;
    let lock: toml::Table = toml::from_str(&text).context("Cargo.lock")?;
    let packages = lock.get("package").and_then(|p| p.as_array());
    let found = packages.into_iter().flatten().find_map(|p| {
        (p.get("name")?.as_str()? == "wasm-bindgen").then(|| p.get("version")?.as_str())?
    });
    match found {
        Some(v) => Ok(v.to_string()),
        None => bail!("Cargo.lock holds no wasm-bindgen: the web module has no glue to make"),
    }
}
