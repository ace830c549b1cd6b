//! The window's event loop, opened (on the desktop and in a page) and,
//! on the desktop, run (a page hands its loop to the browser:
//! `spawn_app` in `mod.rs`). The code that touches winit's loop is not
//! generic over the lesson: [`open_event_loop`], and `run_event_loop`,
//! to which [`run_native`], the one generic function here and a few lines
//! long, hands the window ([`App`]) as a `dyn ApplicationHandler`. So
//! winit's event loop and its X11 and Wayland code are compiled once,
//! here, not again in each lesson binary (`common/src/run/files.rs` has
//! the measurement).

#[cfg(not(target_arch = "wasm32"))]
use std::io::Write;

use anyhow::anyhow;
#[cfg(target_arch = "wasm32")]
use anyhow::Result;
#[cfg(not(target_arch = "wasm32"))]
use anyhow::{Context, Result};
#[cfg(not(target_arch = "wasm32"))]
use winit::application::ApplicationHandler;
use winit::event_loop::EventLoop;

#[cfg(not(target_arch = "wasm32"))]
use super::App;
#[cfg(not(target_arch = "wasm32"))]
use crate::run::instruments::Instruments;

/// The event loop, or why there is none.
pub(super) fn open_event_loop() -> Result<EventLoop<()>> {
    EventLoop::new().map_err(|e| anyhow!("cannot open a window ({e}); use --headless"))
}

/// winit's loop over any handler: one instantiation, here.
#[cfg(not(target_arch = "wasm32"))]
fn run_event_loop(event_loop: EventLoop<()>, mut app: &mut dyn ApplicationHandler) -> Result<()> {
    event_loop
        .run_app(&mut app)
        .map_err(|e| anyhow!("window event loop: {e}"))
}

/// Runs the window until it closes, then flushes `--window-log` and
/// returns the error that closed it, if one did.
#[cfg(not(target_arch = "wasm32"))]
pub(super) fn run_native<L: Instruments>(event_loop: EventLoop<()>, mut app: App<L>) -> Result<()> {
    run_event_loop(event_loop, &mut app)?;
    if let Some(log) = &mut app.log {
        log.flush().context("--window-log: cannot write")?;
    }
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}
