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

use std::cell::RefCell;
use std::rc::Rc;

use anyhow::{anyhow, Result};
use clap::Parser;
use wasm_bindgen::JsCast;

use crate::gpu::targets::PendingFrame;
use crate::gpu::Gpu;
use crate::run::cli::Args;
use crate::run::lesson::{all_variants, select_variants, variant_name, Lesson};
use crate::run::window::live::{Job, Stamp};
use crate::scene::Scene;

/// The canvas a lesson draws into.
pub const CANVAS_ID: &str = "workbook-canvas";
/// Where the page shows a lesson's error.
pub const ERROR_ID: &str = "workbook-error";

/// The page's side of the window: its canvas, the device on its way, and
/// the frame on its way back to the live reference.
pub struct Page {
    pub(crate) canvas: web_sys::HtmlCanvasElement,
    pub(crate) window: Option<std::sync::Arc<winit::window::Window>>,
    pub(crate) opened: Rc<RefCell<Option<Result<(Gpu, wgpu::Surface<'static>)>>>>,
    reading: Option<(PendingFrame, (Stamp, Scene, glam::Mat4))>,
    last_figure: String,
}

impl Default for Page {
    fn default() -> Page {
        Page {
            canvas: canvas().expect("start checked the canvas"),
            window: None,
            opened: Default::default(),
            reading: None,
            last_figure: String::new(),
        }
    }
}

impl Page {
    /// Whether a frame is on its way back.
    pub(crate) fn reading(&self) -> bool {
        self.reading.is_some()
    }

    /// Starts reading a frame back for the live reference's next job.
    pub(crate) fn start_read(&mut self, frame: PendingFrame, of: (Stamp, Scene, glam::Mat4)) {
        self.reading = Some((frame, of));
    }

    /// The job, once its frame is back.
    pub(crate) fn read_done(&mut self) -> Result<Option<Job>> {
        let Some((pending, _)) = self.reading.as_mut() else {
            return Ok(None);
        };
        let Some(frame) = pending.take() else {
            return Ok(None);
        };
        let (_, (stamp, scene, view_proj)) = self.reading.take().expect("checked above");
        Ok(Some(Job {
            stamp,
            scene,
            view_proj,
            frame: frame?,
        }))
    }

    /// The window's log line, on the canvas for the page's scripts; a new
    /// error figure also goes to the console.
    pub(crate) fn publish(&mut self, line: &serde_json::Value) {
        let _ = self.canvas.set_attribute("data-figure", &line.to_string());
        let figure = line["error"].to_string();
        if figure != self.last_figure && !line["error"].is_null() {
            web_sys::console::log_1(&format!("workbook figure: {line}").into());
            self.last_figure = figure;
        }
    }
}

fn canvas() -> Result<web_sys::HtmlCanvasElement> {
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| anyhow!("no document"))?;
    let element = document
        .get_element_by_id(CANVAS_ID)
        .ok_or_else(|| anyhow!("the page has no canvas #{CANVAS_ID}"))?;
    element
        .dyn_into::<web_sys::HtmlCanvasElement>()
        .map_err(|_| anyhow!("#{CANVAS_ID} is not a canvas"))
}

/// Runs lesson `L` in the page: what a lesson's `main` does on the web.
pub fn start<L: Lesson>() {
    if let Err(e) = try_start::<L>() {
        show_error::<L>(&e);
    }
}

fn try_start<L: Lesson>() -> Result<()> {
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

/// One line in the page (`#workbook-error`) and the console.
pub fn show_error<L: Lesson>(e: &anyhow::Error) {
    let line = format!(
        "error: {}: {}",
        L::NAME,
        format!("{e:#}").replace('\n', " ")
    );
    page_error(&line);
}

/// `line` in the page's `#workbook-error` and the console.
pub fn page_error(line: &str) {
    web_sys::console::error_1(&line.into());
    let element = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id(ERROR_ID));
    if let Some(el) = element {
        el.set_text_content(Some(line));
    }
}
