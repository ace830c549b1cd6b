//! The window in a web page: winit draws into the page's canvas, and the
//! device opens asynchronously (a page may not block), so the window
//! starts in two steps: [`App::start`] makes the window and asks the
//! browser for the device; the first redraw after it came
//! ([`App::page_opened`]) builds the scene and the lesson, as the
//! desktop's `start` does.

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::Arc;

use anyhow::{anyhow, Result};
use wasm_bindgen::JsCast;
use winit::event_loop::ActiveEventLoop;
use winit::platform::web::WindowAttributesExtWebSys;
use winit::window::Window;

use super::App;
use crate::gpu::web::page_error;
use crate::gpu::Gpu;
use crate::run::instruments::Instruments;

impl<L: Instruments> App<L> {
    pub(super) fn start(&mut self, el: &ActiveEventLoop) -> Result<()> {
        if self.page.window.is_some() {
            return Ok(());
        }
        let canvas = self.page.canvas.clone();
        // The size in the page's own pixels (CSS), as the book lays it out;
        // the frame is drawn at the screen's pixels under it.
        let attrs = Window::default_attributes()
            .with_title(L::NAME)
            .with_canvas(Some(canvas.clone()))
            .with_inner_size(winit::dpi::LogicalSize::new(
                self.args.width,
                self.args.height,
            ))
            .with_focusable(true)
            .with_prevent_default(true);
        let window = Arc::new(
            el.create_window(attrs)
                .map_err(|e| anyhow!("cannot draw into the page's canvas: {e}"))?,
        );
        let opened = self.page.opened.clone();
        let wake = window.clone();
        wasm_bindgen_futures::spawn_local(async move {
            let result = Gpu::open_web(canvas).await;
            *opened.borrow_mut() = Some(result);
            wake.request_redraw();
        });
        self.page.window = Some(window);
        Ok(())
    }

    /// The device came: the rest of the start. Until it comes, a redraw
    /// does nothing.
    pub(super) fn page_opened(&mut self) -> Result<()> {
        let Some(result) = self.page.opened.borrow_mut().take() else {
            return Ok(());
        };
        let (gpu, surface) = result?;
        let window = (self.page.window.clone()).ok_or_else(|| anyhow!("no canvas window"))?;
        self.started_on(window.clone(), gpu, surface)?;
        window.request_redraw();
        Ok(())
    }
}

/// The canvas a lesson draws into.
pub const CANVAS_ID: &str = "workbook-canvas";

/// The device and surface the browser is opening: filled by the future
/// that asks for them, taken by the first redraw after.
pub(crate) type Opening = Rc<RefCell<Option<Result<(Gpu, wgpu::Surface<'static>)>>>>;

/// The page's side of the window: its canvas and the device on its way.
pub struct Page {
    pub(crate) canvas: web_sys::HtmlCanvasElement,
    pub(crate) window: Option<std::sync::Arc<winit::window::Window>>,
    pub(crate) opened: Opening,
    last_figure: String,
}

impl Default for Page {
    fn default() -> Page {
        Page {
            canvas: canvas().expect("start checked the canvas"),
            window: None,
            opened: Default::default(),
            last_figure: String::new(),
        }
    }
}

impl Page {
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

pub(crate) fn canvas() -> Result<web_sys::HtmlCanvasElement> {
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

/// One line in the page (`#workbook-error`) and the console.
pub fn show_error<L: Instruments>(e: &anyhow::Error) {
    let line = format!(
        "error: {}: {}",
        L::NAME,
        format!("{e:#}").replace('\n', " ")
    );
    page_error(&line);
}
