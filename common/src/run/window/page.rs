//! The window in a web page: winit draws into the page's canvas, and the
//! device opens asynchronously (a page may not block), so the window
//! starts in two steps: [`App::start`] makes the window and asks the
//! browser for the device; the first redraw after it came
//! ([`App::page_opened`]) builds the scene and the lesson, as the
//! desktop's `start` does.

use std::sync::Arc;

use anyhow::{anyhow, Result};
use winit::event_loop::ActiveEventLoop;
use winit::platform::web::WindowAttributesExtWebSys;
use winit::window::Window;

use super::App;
use crate::gpu::Gpu;
use crate::run::lesson::Lesson;

impl<L: Lesson> App<L> {
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
