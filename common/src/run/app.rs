//! A lesson's `main`: parse the command line, then list the variants, run
//! headless ([`crate::run::headless`]) or open the window ([`crate::run::window`]).

use std::process::ExitCode;

use anyhow::Result;
use clap::Parser;

use crate::gpu::wgsl::WgslError;
use crate::run::cli::{clip_values, Args};
use crate::run::headless::run_headless;
use crate::run::instruments::Instruments;
use crate::run::lesson::{all_variants, exercise_variants, select_variants, variant_name};
use crate::run::times_only::run_times_only;
use crate::scene::Scene;

/// A lesson's `main`: parse the command line, run, and turn any error into
/// one line on stderr and a non-zero exit code.
pub fn main<L: Instruments>() -> ExitCode {
    let args = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                use std::io::Write;
                // Like `e.print()`, but a failed write is an error, not a silent exit 0.
                let mut out = std::io::stdout().lock();
                if let Err(err) = write!(out, "{}", e.render()).and_then(|()| out.flush()) {
                    eprintln!("error: {}: cannot write to stdout: {err}", L::NAME);
                    return ExitCode::FAILURE;
                }
                return ExitCode::SUCCESS;
            }
            let msg = e.to_string();
            let line = msg.lines().next().unwrap_or("error: bad command line");
            eprintln!("{}", clip_values(line));
            return ExitCode::from(2);
        }
    };
    match run::<L>(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let msg = format!("{e:#}").replace('\n', " ");
            // A WGSL error: first the compiler's message at the file's own
            // line, then the one line (last, where the grader reads it).
            let wgsl = e.chain().find_map(|c| c.downcast_ref::<WgslError>());
            for line in wgsl.map_or(&[][..], |w| w.detail()) {
                eprintln!("{line}");
            }
            eprintln!("error: {}: {}", L::NAME, clip_values(&msg));
            ExitCode::FAILURE
        }
    }
}

/// Whether a window can open: on Linux and the BSDs, an X11 or Wayland
/// display is named; Windows and macOS always have their desktop.
fn display_available() -> bool {
    if cfg!(any(target_os = "windows", target_os = "macos")) {
        return true;
    }
    std::env::var_os("DISPLAY").is_some_and(|v| !v.is_empty())
        || std::env::var_os("WAYLAND_DISPLAY").is_some_and(|v| !v.is_empty())
}

/// Runs as the command line says: list variants, headless, or the window.
fn run<L: Instruments>(args: &Args) -> Result<()> {
    if args.list_variants {
        // The lesson's variants, then its exercises (run only when named).
        let names: Vec<String> = all_variants::<L>()
            .into_iter()
            .chain(exercise_variants::<L>())
            .map(variant_name)
            .collect();
        return print_stdout(&(names.join("\n") + "\n"));
    }
    let variants = select_variants::<L>(&args.variants)?;
    let scene = load_scene::<L>(args)?;
    let window_only = args.window_flags();
    if let (false, Some(flag)) = (display_available() && !args.headless, window_only.first()) {
        anyhow::bail!(
            "{flag}: is for the window, and {}; run under a display (Linux without one: xvfb-run -a cargo run --release --bin {} -- {flag} ...)",
            if args.headless { "--headless was given" } else { "there is no display (DISPLAY and WAYLAND_DISPLAY are unset)" },
            L::NAME
        );
    }
    if args.times_only {
        if let Some(flag) = args.times_only_conflict() {
            anyhow::bail!(
                "--times-only: measures times alone, so {flag} does not apply; leave one out"
            );
        }
        let (times, out) = run_times_only::<L>(args, scene, &variants)?;
        let table = times.table();
        return print_stdout(&format!("{table}outputs: {}\n", out.display()));
    }
    if args.headless || !display_available() {
        let result = run_headless::<L>(args, scene, &variants)?;
        if let Some(w) = result.report.coverage_warning() {
            eprintln!("{w}");
        }
        let table = result.report.table();
        print_stdout(&format!("{table}outputs: {}\n", result.out_dir.display()))
    } else {
        crate::run::window::run_window::<L>(args, scene, variants)
    }
}

/// Writes to stdout and flushes: a full disk or a closed pipe is an error
/// (`println!` would panic).
fn print_stdout(text: &str) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| anyhow::anyhow!("cannot write to stdout: {e}"))
}

/// A light with a size in a lesson that casts hard shadows: one line that
/// names lesson 10, which renders it.
pub fn refuse_area_lights<L: Instruments>(scene: &Scene) -> Result<()> {
    if L::CAPABILITIES.area_lights {
        return Ok(());
    }
    let Some((k, light)) = (scene.lights.iter().enumerate()).find(|(_, l)| l.size.is_area()) else {
        return Ok(());
    };
    let field = match light.size {
        crate::scene::LightSize::Radius(_) => "radius",
        crate::scene::LightSize::AngularRadiusDeg(_) => "angular_radius_deg",
    };
    anyhow::bail!(
        "scene {}: lights[{k}].{field}: {} casts hard shadows from a point or a single direction; the soft shadows of a light with a size are lesson_10 (or set {field} = 0)",
        scene.name,
        L::NAME
    )
}

/// The `--scene` file, or the lesson's default scene.
pub(crate) fn load_scene<L: Instruments>(args: &Args) -> Result<Scene> {
    let scene = match &args.scene {
        Some(p) => Scene::load(p)?,
        None => Scene::builtin(&format!("{} default scene", L::NAME), L::DEFAULT_SCENE)?,
    };
    L::check_scene(&scene)?;
    refuse_area_lights::<L>(&scene)?;
    if scene.camera.shift != glam::DVec2::ZERO && !L::CAPABILITIES.camera_shift {
        anyhow::bail!(
            "scene {}: camera.shift: {} fits to a centred frustum (fov_y_deg and the aspect alone) and would be wrong off-centre; lesson_07 draws a shifted camera (or set shift = [0, 0])",
            scene.name,
            L::NAME
        );
    }
    Ok(scene)
}
