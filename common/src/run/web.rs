//! The lessons in a web page (the web build, `workbook web`): the same
//! [`Lesson`] and the same window ([`crate::run::window`]), on the
//! browser's WebGPU and the page's canvas.
//!
//! The page names the canvas and the command line: `start` reads the
//! canvas `#workbook-canvas` and its `data-args` attribute (`--variant
//! pcss --width 720 --height 405`, the window's flags). The window then
//! writes what it shows, once a frame, to the canvas's `data-figure`
//! attribute: the `--window-log` line (variant, cost, error figure and the
//! view it is of), which the book's check reads (`.ci/web-check`). An
//! error stops the lesson with one line in the page's `#workbook-error`
//! element and the console.

use anyhow::{anyhow, Result};
use clap::Parser;

use crate::gpu::web::page_error;
use crate::run::cli::Args;
use crate::run::instruments::Instruments;
use crate::run::lesson::{all_variants, select_variants, variant_name};
use crate::run::window::page::{canvas, show_error};

/// Runs lesson `L` in the page: what a lesson's `main` does on the web.
pub fn start<L: Instruments>() {
    // The page's reference worker runs the same module: there the lesson
    // serves the window's reference jobs (`window::live_worker`).
    if crate::run::window::live_worker::in_worker() {
        crate::run::window::live_worker::serve::<L>();
        return;
    }
    if let Err(e) = try_start::<L>() {
        show_error::<L>(&e);
    }
}

fn try_start<L: Instruments>() -> Result<()> {
    let canvas = canvas()?;
    let flags = canvas.get_attribute("data-args").unwrap_or_default();
    let argv = std::iter::once(L::NAME).chain(flags.split_whitespace());
    let args = Args::try_parse_from(argv).map_err(|e| {
        let msg = e.to_string();
        anyhow!("data-args: {}", msg.lines().next().unwrap_or("bad flags"))
    })?;
    let mut variants = select_variants::<L>(&args.variants)?;
    // A page starts at the variant it names, with the lesson's others a
    // key away (V), in the lesson's order.
    if let [one] = variants[..] {
        let mut all = all_variants::<L>();
        if let Some(i) = all
            .iter()
            .position(|&v| variant_name(v) == variant_name(one))
        {
            all.rotate_left(i);
            variants = all;
        }
    }
    let scene = crate::run::app::load_scene::<L>(&args)?;
    crate::run::window::run_window::<L>(&args, scene, variants)
}

/// A panic becomes the page's error line (the console has the rest).
pub fn catch_panics() {
    std::panic::set_hook(Box::new(|info| {
        page_error(&format!("error: the lesson panicked: {info}"));
    }));
}
