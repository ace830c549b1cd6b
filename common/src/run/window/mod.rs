//! The interactive window (winit), a workbench: it renders with the same
//! `Lesson::render` as the headless runner, shows which variant runs, what
//! it costs and how wrong it is against the exact reference, live, and
//! lets the reader turn the technique's knobs.
//!
//! - [`controls`]: the camera, the light, the keys, and the command line
//!   that reproduces what the window shows.
//! - [`event_loop`]: winit's event loop, opened and run.
//! - [`frame`]: one frame, in steps: render, measure, overlay, present, capture.
//! - [`panel`]: the frame's overlay step: the panel built and tessellated.
//! - [`frame_log`]: `--window-log`, a JSON line a frame.
//! - [`live`]: the exact reference on low-priority worker threads.
//! - [`live_job`]: its jobs, the frames read back for them, and its answers.
//! - [`overlay`]: the egui overlay (and [`overlay::KEYS`], every key).
//! - [`present`]: the window's picture (view + overlay) and its capture.
//! - [`views`]: the diff and buffer views' pictures.
//! - [`live_server`]: a reference job's coarse and full passes, wherever
//!   they run (the desktop's worker thread, the page's Web Worker).
//! - [`page`], [`live_page`], [`live_worker`], [`live_message`]: the
//!   window in a web page, its live reference in a Web Worker, the worker's
//!   side, and what the two send each other (the web build).
//!
//! The same window runs in a web page (the web build, [`crate::run::web`]):
//! winit draws into the page's canvas, the device comes from the
//! browser's WebGPU, and the live reference works in a Web Worker
//! ([`live_page`]).

pub mod controls;
pub mod event_loop;
pub mod frame;
pub mod frame_log;
pub mod live;
pub mod live_job;
pub mod live_message;
#[cfg(target_arch = "wasm32")]
pub mod live_page;
pub mod live_server;
#[cfg(target_arch = "wasm32")]
pub mod live_worker;
pub mod overlay;
#[cfg(target_arch = "wasm32")]
pub mod page;
pub mod panel;
pub mod present;
pub mod views;

use std::sync::Arc;

use web_time::Instant;

use anyhow::{anyhow, Context, Result};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::window::{Window, WindowId};

use crate::gpu::render::SceneGpu;
use crate::gpu::targets::FrameTargets;
use crate::gpu::Gpu;
use crate::measure::timing::Timer;
use crate::run::cli::Args;
use crate::run::instruments::{apply_cli_knobs, Instruments};
use crate::scene::Scene;

use crate::run::view::View;
use event_loop::open_event_loop;
#[cfg(not(target_arch = "wasm32"))]
use event_loop::run_native;
use live::{Answer, LiveReference, PendingJob, Stamp};
use overlay::Cost;
use present::Present;
use views::Picture;

/// Whether the window reads the GPU back as a web page must: its counters,
/// its buffer view and its GPU times a frame or more later, never waiting
/// (`common::gpu::read_later`, `common::measure::timing_later`). Always
/// in a page; on the desktop with `WORKBOOK_AS_PAGE=1`, which the window's
/// tests use to check the page's path (the pipeline statistics, which
/// WebGPU lacks, are still waited for there).
pub fn as_page() -> bool {
    cfg!(target_arch = "wasm32") || std::env::var("WORKBOOK_AS_PAGE").is_ok_and(|v| v == "1")
}

/// Frames drawn before `--capture` when `--capture-after` is not given.
pub const DEFAULT_CAPTURE_AFTER: u32 = 30;

/// The window and what draws into it.
struct Running<L: Instruments> {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    gpu: Gpu,
    scene: SceneGpu,
    targets: FrameTargets,
    lesson: L,
    timer: Timer,
    present: Present,
    egui: egui_winit::State,
    live: Option<LiveReference>,
}

/// What the overlay shows and the user changed.
struct State {
    variants: Vec<String>,
    current: usize,
    view: View,
    show_overlay: bool,
    /// Camera or light changes (the reference's key) and changes of what
    /// the variant draws on the same view (variant, knobs, resize).
    stamp: Stamp,
    /// When the current `scene_gen` began.
    view_since: Instant,
    /// Frames drawn since the variant or a knob last changed: the live
    /// reference reads the second on (some lessons set a variant up on its
    /// first frame, as the headless runner knows).
    variant_frames: u32,
    /// When the last job went to the live reference.
    sent_at: Option<Instant>,
    /// The last stamp sent to the live reference.
    sent: Option<Stamp>,
    /// The job whose frame is on its way back.
    reading: Option<PendingJob>,
    answer: Option<Answer>,
    /// Seconds from the view change to the answer, when it is for the current view.
    answer_latency: Option<f64>,
    /// The diff view's title and the stamp it was computed for (its image
    /// is in [`Present`]).
    diff: Option<(String, (u64, u64))>,
    /// Which answer image (the diff's or the dv's) the shared texture
    /// holds; `None` after a new answer.
    error_image: Option<View>,
    buffer: Option<Picture>,
    buffer_note: Option<String>,
    buffer_at: Option<Instant>,
    /// The buffer view's readback is on its way (a web page's).
    buffer_coming: bool,
    cost: Cost,
    /// The frame (the timer's count) of the newest GPU times read late,
    /// and the last frame before the variant or a knob last changed.
    gpu_frame: u64,
    gpu_since: u64,
    frame_times: std::collections::VecDeque<Instant>,
    settings_line: Option<String>,
}

struct App<L: Instruments> {
    args: Args,
    scene: Option<Scene>,
    variants: Vec<L::Variant>,
    running: Option<Running<L>>,
    state: State,
    error: Option<anyhow::Error>,
    dragging: bool,
    last_cursor: Option<(f64, f64)>,
    frames: u64,
    started: Instant,
    last_frame: Option<Instant>,
    /// The adapter and backend, for the log.
    adapter_line: String,
    /// When `--capture` began to wait for the full figure.
    capture_wait: Option<Instant>,
    log: Option<std::io::BufWriter<std::fs::File>>,
    /// The page's canvas and the device it is opening (the web build).
    #[cfg(target_arch = "wasm32")]
    page: page::Page,
}

pub fn run_window<L: Instruments>(
    args: &Args,
    scene: Scene,
    variants: Vec<L::Variant>,
) -> Result<()> {
    let event_loop = open_event_loop()?;
    let log = match &args.window_log {
        Some(p) => Some(std::io::BufWriter::new(
            std::fs::File::create(p)
                .with_context(|| format!("--window-log: cannot create {}", p.display()))?,
        )),
        None => None,
    };
    if let Some(p) = &args.capture {
        check_capture_path(p)?;
    }
    let names = variants
        .iter()
        .map(|&v| crate::run::lesson::variant_name(v));
    let now = Instant::now();
    #[allow(unused_mut)]
    let mut app: App<L> = App {
        args: args.clone(),
        scene: Some(scene),
        state: State {
            variants: names.collect(),
            current: 0,
            view: args.view.unwrap_or(View::Frame),
            show_overlay: true,
            stamp: Stamp {
                scene_gen: 1,
                image_gen: 1,
            },
            view_since: now,
            variant_frames: 0,
            sent_at: None,
            sent: None,
            reading: None,
            answer: None,
            answer_latency: None,
            diff: None,
            error_image: None,
            buffer: None,
            buffer_note: None,
            buffer_at: None,
            buffer_coming: false,
            cost: Cost::default(),
            gpu_frame: 0,
            gpu_since: 0,
            frame_times: Default::default(),
            settings_line: None,
        },
        variants,
        running: None,
        error: None,
        dragging: false,
        last_cursor: None,
        frames: 0,
        started: now,
        last_frame: None,
        capture_wait: None,
        adapter_line: String::new(),
        log,
        #[cfg(target_arch = "wasm32")]
        page: Default::default(),
    };
    #[cfg(target_arch = "wasm32")]
    {
        // A page's event loop returns at once and runs from the browser's.
        use winit::platform::web::EventLoopExtWebSys;
        event_loop.spawn_app(app);
        Ok(())
    }
    #[cfg(not(target_arch = "wasm32"))]
    run_native(event_loop, app)
}

/// `--capture`: a `.png` in a folder that exists (checked before the window opens).
fn check_capture_path(p: &std::path::Path) -> Result<()> {
    let png = p.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        anyhow::bail!("--capture {}: the file must end in .png", p.display());
    }
    let dir = p.parent().filter(|d| !d.as_os_str().is_empty());
    if let Some(d) = dir.filter(|d| !d.is_dir()) {
        anyhow::bail!(
            "--capture {}: the folder {} does not exist",
            p.display(),
            d.display()
        );
    }
    Ok(())
}

impl<L: Instruments> App<L> {
    #[cfg(not(target_arch = "wasm32"))]
    fn start(&mut self, el: &ActiveEventLoop) -> Result<()> {
        let attrs = Window::default_attributes()
            .with_title(L::NAME)
            .with_inner_size(winit::dpi::PhysicalSize::new(
                self.args.width,
                self.args.height,
            ));
        let window = Arc::new(
            el.create_window(attrs)
                .map_err(|e| anyhow!("cannot create a window: {e}"))?,
        );
        let gpu = Gpu::open(
            self.args.backend.as_deref(),
            self.args.adapter.as_deref(),
            self.args.depth_format.as_deref(),
            // GL (EGL) draws to a window only through the display it was opened on.
            Some(Box::new(el.owned_display_handle())),
        )?;
        let surface = gpu
            .instance
            .create_surface(window.clone())
            .map_err(|e| anyhow!("cannot create a surface: {e}"))?;
        self.started_on(window, gpu, surface)
    }

    /// The window has a device and a surface: the scene, the lesson and
    /// the overlay.
    fn started_on(
        &mut self,
        window: Arc<Window>,
        gpu: Gpu,
        surface: wgpu::Surface<'static>,
    ) -> Result<()> {
        let scene = self.scene.take().ok_or_else(|| anyhow!("no scene"))?;
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&gpu.adapter, size.width.max(1), size.height.max(1))
            .ok_or_else(|| {
                anyhow!(
                    "the adapter {} cannot present to this window",
                    gpu.info.name
                )
            })?;
        let caps = surface.get_capabilities(&gpu.adapter);
        if let Some(f) = caps.formats.iter().find(|f| f.is_srgb()) {
            config.format = *f;
        }
        // A web page's canvas has no sRGB format: an sRGB view of it draws
        // the same picture as the desktop's sRGB surface.
        if !config.format.is_srgb() {
            config.view_formats = vec![config.format.add_srgb_suffix()];
        }
        let picture_format = config.view_formats.first().copied();
        let picture_format = picture_format.unwrap_or(config.format);
        surface.configure(&gpu.device, &config);
        let scene = SceneGpu::new(&gpu, scene, config.width, config.height)?;
        let targets = scene.frame_targets(&gpu);
        let mut lesson = L::new(&gpu, &scene)?;
        apply_cli_knobs(&mut lesson, &gpu, &scene, &self.variants, &self.args.knobs)?;
        let timer = match as_page() {
            true => {
                crate::gpu::read_later::never_wait_here();
                Timer::later(&gpu)
            }
            false => Timer::new(&gpu),
        };
        let present = Present::new(&gpu, picture_format, &targets);
        let ctx = egui::Context::default();
        let egui = egui_winit::State::new(
            ctx,
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let live = match self.args.no_live_reference {
            true => None,
            false => Some(LiveReference::start()?),
        };
        self.running = Some(Running {
            window,
            surface,
            config,
            gpu,
            scene,
            targets,
            lesson,
            timer,
            present,
            egui,
            live,
        });
        Ok(())
    }

    fn resize(&mut self, w: u32, h: u32) -> Result<()> {
        let Some(r) = self.running.as_mut() else {
            return Ok(());
        };
        if w == 0 || h == 0 || (w == r.config.width && h == r.config.height) {
            return Ok(());
        }
        r.config.width = w;
        r.config.height = h;
        r.surface.configure(&r.gpu.device, &r.config);
        let scene = r.scene.scene.clone();
        r.scene = SceneGpu::new(&r.gpu, scene, w, h)?;
        r.targets = r.scene.frame_targets(&r.gpu);
        // The lesson's knobs live in the lesson: carry them over.
        let mut knobs = Vec::new();
        for &v in &self.variants {
            for k in r.lesson.knobs(v) {
                knobs.push((v, k.name, k.value));
            }
        }
        r.lesson = L::new(&r.gpu, &r.scene)?;
        for (v, name, value) in knobs {
            crate::run::instruments::apply_knob(&mut r.lesson, &r.gpu, &r.scene, v, name, value)?;
        }
        r.present.resize(&r.gpu, &r.targets);
        self.state.view_changed();
        Ok(())
    }

    fn fail(&mut self, el: &ActiveEventLoop, e: anyhow::Error) {
        #[cfg(target_arch = "wasm32")]
        page::show_error::<L>(&e);
        self.error = Some(e);
        el.exit();
    }
}

impl State {
    /// The camera or a light moved (or the window changed size).
    fn view_changed(&mut self) {
        self.stamp.scene_gen += 1;
        self.stamp.image_gen += 1;
        self.view_since = Instant::now();
        // A count on its way back (a web page's) is of the old view.
        crate::gpu::read_later::forget();
    }

    /// The variant draws differently on the same view (variant, knob).
    fn image_changed(&mut self) {
        crate::gpu::read_later::forget();
        self.stamp.image_gen += 1;
        self.variant_frames = 0;
        self.view_since = Instant::now();
    }

    /// Forgets the GPU times kept (the variant or a knob changed); in a
    /// web page, times of frames up to `frames` (the timer's count) are
    /// the old setting's, still on their way back.
    fn restart_gpu_times(&mut self, frames: u64) {
        self.cost.gpu.clear();
        self.gpu_since = frames;
    }
}

impl<L: Instruments> ApplicationHandler for App<L> {
    fn resumed(&mut self, el: &ActiveEventLoop) {
        if self.running.is_none() {
            if let Err(e) = self.start(el) {
                self.fail(el, e);
            }
        }
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        // The overlay sees every event first; what it uses, the scene does not.
        let used = match self.running.as_mut() {
            Some(r) if self.state.show_overlay => {
                r.egui.on_window_event(&r.window, &event).consumed
            }
            _ => false,
        };
        let result = match event {
            WindowEvent::CloseRequested => {
                el.exit();
                Ok(())
            }
            WindowEvent::Resized(s) => self.resize(s.width, s.height),
            #[cfg(target_arch = "wasm32")]
            WindowEvent::RedrawRequested if self.running.is_none() => self.page_opened(),
            WindowEvent::RedrawRequested => self.redraw(el),
            _ if used => Ok(()),
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                self.dragging = state == ElementState::Pressed;
                Ok(())
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let (true, Some((x, y))) = (self.dragging, self.last_cursor) {
                    self.orbit(position.x - x, position.y - y);
                }
                self.last_cursor = Some((position.x, position.y));
                Ok(())
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let a = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y as f64,
                    MouseScrollDelta::PixelDelta(p) => p.y / 50.0,
                };
                self.zoom(a);
                Ok(())
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                self.key(el, &event.logical_key)
            }
            _ => Ok(()),
        };
        if let Err(e) = result {
            self.fail(el, e);
        }
    }

    fn about_to_wait(&mut self, el: &ActiveEventLoop) {
        match self.frame_due() {
            Some(at) => el.set_control_flow(ControlFlow::WaitUntil(at)),
            None => {
                el.set_control_flow(ControlFlow::Wait);
                if let Some(r) = &self.running {
                    r.window.request_redraw();
                }
            }
        }
    }
}
