//! The interactive window (winit). It renders with the same `Lesson::render`
//! as the headless runner, into offscreen targets, then copies the colour
//! target to the window.
//!
//! Controls: drag with the left mouse button to orbit, scroll to zoom, arrow
//! keys move the first light (PageUp/PageDown: up and down for point and spot
//! lights), `V` or Space cycles the variants, Escape quits. The title shows
//! the variant and its milliseconds.

use std::sync::Arc;

use anyhow::{anyhow, Result};
use glam::{DQuat, DVec3};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::gpu::bindings::{self, float_texture_entry};
use crate::gpu::fullscreen::{draw_fullscreen, Fullscreen};
use crate::gpu::render::SceneGpu;
use crate::gpu::targets::FrameTargets;
use crate::gpu::Gpu;
use crate::measure::timing::{Timer, FRAME, TOTAL};
use crate::run::cli::Args;
use crate::run::lesson::{variant_name, Lesson};
use crate::scene::{LightKind, Scene};

const BLIT_WGSL: &str = r#"
@group(0) @binding(0) var src: texture_2d<f32>;
@fragment fn fs(in: FullscreenOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(src));
    return textureLoad(src, vec2<i32>(in.uv * size), 0);
}
"#;

struct Running<L: Lesson> {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    gpu: Gpu,
    scene: SceneGpu,
    targets: FrameTargets,
    lesson: L,
    timer: Timer,
    blit: wgpu::RenderPipeline,
    blit_layout: wgpu::BindGroupLayout,
    blit_group: wgpu::BindGroup,
}

struct App<L: Lesson> {
    args: Args,
    scene: Option<Scene>,
    variants: Vec<L::Variant>,
    current: usize,
    running: Option<Running<L>>,
    error: Option<anyhow::Error>,
    dragging: bool,
    last_cursor: Option<(f64, f64)>,
    /// The last frame's cost and GPU time (ms).
    last_ms: (f64, f64),
}

pub fn run_window<L: Lesson>(args: &Args, scene: Scene, variants: Vec<L::Variant>) -> Result<()> {
    let event_loop =
        EventLoop::new().map_err(|e| anyhow!("cannot open a window ({e}); use --headless"))?;
    let mut app: App<L> = App {
        args: args.clone(),
        scene: Some(scene),
        variants,
        current: 0,
        running: None,
        error: None,
        dragging: false,
        last_cursor: None,
        last_ms: (0.0, 0.0),
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| anyhow!("window event loop: {e}"))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

impl<L: Lesson> App<L> {
    fn start(&mut self, el: &ActiveEventLoop) -> Result<()> {
        let scene = self.scene.take().ok_or_else(|| anyhow!("no scene"))?;
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
            None,
        )?;
        let surface = gpu
            .instance
            .create_surface(window.clone())
            .map_err(|e| anyhow!("cannot create a surface: {e}"))?;
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
        surface.configure(&gpu.device, &config);
        let scene = SceneGpu::new(&gpu, scene, config.width, config.height)?;
        let targets = scene.frame_targets(&gpu);
        let lesson = L::new(&gpu, &scene)?;
        let timer = Timer::new(&gpu);
        let blit_layout = bindings::layout(&gpu, "blit", &[float_texture_entry(0)]);
        let blit = Fullscreen::image("blit", BLIT_WGSL, "fs", &[&blit_layout], config.format)
            .pipeline(&gpu);
        let blit_group = blit_group(&gpu, &blit_layout, &targets);
        self.running = Some(Running {
            window,
            surface,
            config,
            gpu,
            scene,
            targets,
            lesson,
            timer,
            blit,
            blit_layout,
            blit_group,
        });
        Ok(())
    }

    fn redraw(&mut self) -> Result<()> {
        let variant = self.variants[self.current];
        let Some(r) = self.running.as_mut() else {
            return Ok(());
        };
        let mut frame = r.timer.frame(&r.gpu);
        r.lesson.render(&mut frame, &r.scene, &r.targets, variant)?;
        let t = frame.finish()?;
        let ms = |k: &str| t.ms.get(k).copied().unwrap_or(0.0);
        self.last_ms = (ms(FRAME), ms(TOTAL));
        let surface_tex = match r.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            _ => {
                r.surface.configure(&r.gpu.device, &r.config);
                return Ok(());
            }
        };
        let view = surface_tex.texture.create_view(&Default::default());
        let mut enc = r.gpu.device.create_command_encoder(&Default::default());
        draw_fullscreen(&mut enc, &view, &r.blit, &r.blit_group);
        r.gpu.queue.submit([enc.finish()]);
        r.gpu.queue.present(surface_tex);
        r.window.set_title(&format!(
            "{} - {} - frame {:.2} ms, GPU {:.2} ms  [V: next variant, drag: orbit, arrows: light]",
            L::NAME,
            variant_name(variant),
            self.last_ms.0,
            self.last_ms.1
        ));
        Ok(())
    }

    fn resize(&mut self, w: u32, h: u32) -> Result<()> {
        let Some(r) = self.running.as_mut() else {
            return Ok(());
        };
        if w == 0 || h == 0 {
            return Ok(());
        }
        r.config.width = w;
        r.config.height = h;
        r.surface.configure(&r.gpu.device, &r.config);
        let scene = r.scene.scene.clone();
        r.scene = SceneGpu::new(&r.gpu, scene, w, h)?;
        r.targets = r.scene.frame_targets(&r.gpu);
        r.lesson = L::new(&r.gpu, &r.scene)?;
        r.blit_group = blit_group(&r.gpu, &r.blit_layout, &r.targets);
        Ok(())
    }

    fn orbit(&mut self, dx: f64, dy: f64) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let c = &mut r.scene.scene.camera;
        let arm = c.eye - c.target;
        let right = arm.cross(c.up).normalize();
        let yaw = DQuat::from_axis_angle(c.up, -dx * 0.01);
        let pitch = DQuat::from_axis_angle(right, dy * 0.01);
        let next = pitch * yaw * arm;
        // Stay away from the poles, where `up` and the view direction align.
        if next.normalize().dot(c.up).abs() < 0.98 {
            c.eye = c.target + next;
        } else {
            c.eye = c.target + yaw * arm;
        }
        r.scene.set_camera(&r.gpu);
    }

    fn zoom(&mut self, amount: f64) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let c = &mut r.scene.scene.camera;
        c.eye = c.target + (c.eye - c.target) * (1.0 - amount * 0.1).clamp(0.5, 1.5);
        r.scene.set_camera(&r.gpu);
    }

    fn move_light(&mut self, key: &NamedKey) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let Some(light) = r.scene.scene.lights.first_mut() else {
            return;
        };
        let step = 0.05;
        let turn = |d: DVec3, yaw: f64, pitch: f64| {
            let q = DQuat::from_rotation_y(yaw);
            let right = d.cross(DVec3::Y).normalize_or(DVec3::X);
            (DQuat::from_axis_angle(right, pitch) * q * d).normalize()
        };
        let (dx, dy, dz) = match key {
            NamedKey::ArrowLeft => (-1.0, 0.0, 0.0),
            NamedKey::ArrowRight => (1.0, 0.0, 0.0),
            NamedKey::ArrowUp => (0.0, 0.0, -1.0),
            NamedKey::ArrowDown => (0.0, 0.0, 1.0),
            NamedKey::PageUp => (0.0, 1.0, 0.0),
            NamedKey::PageDown => (0.0, -1.0, 0.0),
            _ => return,
        };
        match &mut light.kind {
            LightKind::Directional { direction } => {
                *direction = turn(*direction, dx * step, dz * step)
            }
            LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
                *position += DVec3::new(dx, dy, dz) * 0.1;
            }
        }
        r.scene.upload_uniforms(&r.gpu);
    }

    fn fail(&mut self, el: &ActiveEventLoop, e: anyhow::Error) {
        self.error = Some(e);
        el.exit();
    }
}

fn blit_group(gpu: &Gpu, layout: &wgpu::BindGroupLayout, t: &FrameTargets) -> wgpu::BindGroup {
    let color = wgpu::BindingResource::TextureView(&t.color_view);
    bindings::group(gpu, "blit", layout, &[color])
}

impl<L: Lesson> ApplicationHandler for App<L> {
    fn resumed(&mut self, el: &ActiveEventLoop) {
        if self.running.is_none() {
            if let Err(e) = self.start(el) {
                self.fail(el, e);
            }
        }
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let result = match event {
            WindowEvent::CloseRequested => {
                el.exit();
                Ok(())
            }
            WindowEvent::Resized(s) => self.resize(s.width, s.height),
            WindowEvent::RedrawRequested => self.redraw(),
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
                match &event.logical_key {
                    Key::Named(NamedKey::Escape) => el.exit(),
                    Key::Named(NamedKey::Space) => {
                        self.current = (self.current + 1) % self.variants.len()
                    }
                    Key::Character(c) if c.eq_ignore_ascii_case("v") => {
                        self.current = (self.current + 1) % self.variants.len()
                    }
                    Key::Named(k) => self.move_light(k),
                    _ => {}
                }
                Ok(())
            }
            _ => Ok(()),
        };
        if let Err(e) = result {
            self.fail(el, e);
        }
    }

    fn about_to_wait(&mut self, _el: &ActiveEventLoop) {
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }
}
