//! One frame of the window: render the variant, feed and read the live
//! reference, build the overlay, put the picture on screen, and capture or
//! log it when asked.

use std::io::Write;
use std::time::Duration;

use web_time::Instant;

use anyhow::{Context, Result};
use winit::event_loop::ActiveEventLoop;

use super::live::{Level, PendingJob};
use super::overlay::{self, Panel, ShownError};
use super::present::Overlay;
use super::views;
use super::{App, DEFAULT_CAPTURE_AFTER};
use crate::gpu::read_later::later;
use crate::run::lesson::apply_knob;
use crate::run::lesson::{variant_doc, Lesson};
use crate::run::view::View;

/// The longest `--capture` waits for the live reference's full figure.
const CAPTURE_WAIT: Duration = Duration::from_secs(60);

/// The least time between two jobs of the live reference: while the
/// camera moves, each job reads the frame back and keeps the worker busy,
/// and more than a few figures a second cost the window frames for
/// nothing a reader sees.
const JOB_EVERY: Duration = Duration::from_millis(300);

/// On a CPU adapter, the longest between two frames while the live
/// reference works on the view on screen: the window's frames and the ray
/// casts share the same cores, and redrawing an unchanged view as fast as
/// it can kept the full figure waiting 4–5 s at 1280×720 on 2 cores.
const STILL_FRAME_EVERY: Duration = Duration::from_millis(500);

/// How often a waiting window looks for the live reference's answer.
const ANSWER_POLL: Duration = Duration::from_millis(20);

/// How often the buffer view reads the lesson's buffer back.
const BUFFER_EVERY: Duration = Duration::from_millis(500);

impl<L: Lesson> App<L> {
    /// When the next frame is due: `None` for at once. Only a CPU adapter
    /// with the live reference at work on a still view waits, until an
    /// answer comes or [`STILL_FRAME_EVERY`] has passed; a GPU draws
    /// without a pause, so that its clock and the cost it shows hold.
    pub(super) fn frame_due(&mut self) -> Option<Instant> {
        let r = self.running.as_mut()?;
        let live = r.live.as_mut()?;
        let s = &self.state;
        let orbiting = self.args.orbit.is_some()
            && self
                .args
                .orbit_seconds
                .is_none_or(|t| self.started.elapsed().as_secs_f64() < t);
        // Still, and the coarse figure of this view shown: the full one is under way.
        let coarse_shown = s.answer.as_ref().is_some_and(|a| a.stamp == s.stamp);
        let still = !orbiting && !self.dragging && s.sent == Some(s.stamp) && coarse_shown;
        // A count on its way back (a page's) comes with the next frames.
        let counting = crate::gpu::read_later::waiting();
        if r.gpu.info.device_type != wgpu::DeviceType::Cpu || !live.busy() || !still || counting {
            return None;
        }
        let last = self.last_frame?;
        if live.ready() || last.elapsed() >= STILL_FRAME_EVERY {
            return None;
        }
        Some((Instant::now() + ANSWER_POLL).min(last + STILL_FRAME_EVERY))
    }

    pub(super) fn redraw(&mut self, el: &ActiveEventLoop) -> Result<()> {
        if self.running.is_none() {
            return Ok(());
        }
        let now = Instant::now();
        let dt = self.last_frame.map_or(0.0, |t| (now - t).as_secs_f64());
        self.last_frame = Some(now);
        let orbiting = self
            .args
            .orbit_seconds
            .is_none_or(|s| self.started.elapsed().as_secs_f64() < s);
        if let (Some(deg_per_s), true) = (self.args.orbit, orbiting) {
            // A steady drag: 0.01 radian per pixel.
            self.orbit(deg_per_s.to_radians() * dt / 0.01, 0.0);
        }
        let variant = self.variants[self.state.current];
        let r = self.running.as_mut().expect("checked above");
        let s = &mut self.state;
        // The view this frame draws: a job of an older one stops after
        // its coarse pass.
        if let Some(live) = r.live.as_mut() {
            live.note_view(s.stamp.scene_gen);
        }

        // 1. The variant's frame, timed as the headless runner times it.
        let mut frame = r.timer.frame(&r.gpu);
        r.lesson.render(&mut frame, &r.scene, &r.targets, variant)?;
        s.cost.ms = frame.finish()?.ms;
        // The GPU's times: this frame's (waited for), or in a web page
        // the newest earlier frame's that came back, each frame once.
        match r.timer.late() {
            Some(late) => {
                // Frames from before the variant or a knob changed are the old one's.
                let new = late.frame > s.gpu_frame.max(s.gpu_since);
                s.gpu_frame = late.frame;
                s.cost.late = Some((late.frames_late, late.quantum_ns));
                if new {
                    s.cost.push_gpu(&late.ms);
                }
            }
            None if r.timer.times_gpu() => s.cost.push_gpu(&s.cost.ms.clone()),
            None => {}
        }
        s.variant_frames += 1;
        s.frame_times.push_back(now);
        while s
            .frame_times
            .front()
            .is_some_and(|&t| now - t > Duration::from_secs(1))
        {
            s.frame_times.pop_front();
        }
        s.cost.fps = s.frame_times.len() as f64;

        // 2. The live reference: read what it answered, send the next job.
        let ctx = r.egui.egui_ctx().clone();
        if let Some(live) = r.live.as_mut() {
            for a in live.answers()? {
                let current = a.stamp == s.stamp;
                s.answer_latency = current.then(|| (Instant::now() - s.view_since).as_secs_f64());
                s.diff = Some((diff_title(&a), (a.stamp.scene_gen, a.stamp.image_gen)));
                s.answer = Some(a);
                s.error_image = None;
            }
            let due = s.sent_at.is_none_or(|t| now - t >= JOB_EVERY);
            // The frame comes back without the window waiting for it: the
            // job goes out on a later frame, once its images are mapped.
            let mapped = match &s.reading {
                Some(job) => job.ready(&r.gpu)?,
                None => false,
            };
            if mapped {
                live.send(s.reading.take().expect("mapped above"));
            }
            let reading = s.reading.is_some();
            if !live.busy() && !reading && s.sent != Some(s.stamp) && s.variant_frames >= 2 && due {
                s.sent_at = Some(now);
                let scene = r.scene.scene.clone();
                let view_proj = r.scene.camera.view_proj;
                s.reading = Some(PendingJob::start(
                    &r.gpu, &r.targets, s.stamp, scene, view_proj,
                ));
                s.sent = Some(s.stamp);
            }
        }

        // The diff and dv views share one texture: it holds the shown one's,
        // uploaded only while one of them is shown (a coarse answer's image
        // is scaled to the frame's size first: 17-21 ms at 1280×720 on 2
        // cores, at every answer, for a view the reader may never open).
        let error_view = match s.view {
            View::Dv | View::Diff => Some(s.view),
            _ => None,
        };
        if let Some(error_view) = error_view.filter(|&v| s.error_image != Some(v)) {
            if let Some(a) = &s.answer {
                let image = if error_view == View::Dv {
                    &a.dv
                } else {
                    &a.diff
                };
                r.present.set_diff(&r.gpu, image);
                s.error_image = Some(error_view);
            }
        }

        // 3. The buffer view, a few times a second while it is shown (in a
        // web page it comes back a frame or more later: asked again each
        // frame until it has).
        let buffer_due = s.buffer_at.is_none_or(|t| now - t > BUFFER_EVERY);
        if s.view == View::Buffer && (buffer_due || s.buffer_coming) {
            s.buffer_at = Some(now);
            let read = later(|| r.lesson.buffer_view(&r.gpu, &r.scene, variant))?;
            s.buffer_coming = read.is_none();
            match read {
                Some(Some(b)) => {
                    let stamp = (s.stamp.scene_gen, s.stamp.image_gen);
                    views::upload(&ctx, &mut s.buffer, "buffer", &b.image, b.title, stamp);
                    s.buffer_note = None;
                }
                Some(None) => {
                    s.buffer = None;
                    s.buffer_note = Some(format!("{} has no buffer to show", L::NAME));
                }
                None => {}
            }
        }

        // 4. The overlay.
        let input = r.egui.take_egui_input(&r.window);
        let knobs = r.lesson.knobs(variant);
        let shown = s.answer.as_ref().map(|a| ShownError {
            error: a.error.clone(),
            level: a.level,
            stale: a.stamp != s.stamp,
            latency_s: s.answer_latency,
        });
        let picture = match s.view {
            View::Buffer => s.buffer.as_ref(),
            _ => None,
        };
        let now_stamp = (s.stamp.scene_gen, s.stamp.image_gen);
        let titled = |title: &str, stamp| match stamp == now_stamp {
            true => title.to_string(),
            false => format!("{title} (of an earlier view; updating)"),
        };
        let view_note = match s.view {
            View::Frame => None,
            View::Visibility => Some("white lit, black shadowed (light 0)".to_string()),
            View::Diff if r.live.is_none() => {
                Some("no diff: the live reference is off".to_string())
            }
            View::Diff => Some(match &s.diff {
                Some((title, stamp)) => titled(title, *stamp),
                None => "computing…".to_string(),
            }),
            View::Dv if r.live.is_none() => Some("no dv: the live reference is off".to_string()),
            View::Dv => Some(match &s.diff {
                Some((title, stamp)) => titled(&dv_title(title), *stamp),
                None => "computing…".to_string(),
            }),
            View::Buffer => match picture {
                Some(p) => Some(titled(&p.title, p.stamp)),
                None => s.buffer_note.clone().or(Some("computing…".to_string())),
            },
        };
        let doc = variant_doc(variant);
        let counters = r.lesson.counters(variant);
        let adapter = format!("{} ({})", r.gpu.adapter_name(), r.gpu.backend_name());
        if self.adapter_line.is_empty() {
            self.adapter_line = adapter.clone();
        }
        let mut actions = overlay::Actions::default();
        let out = ctx.run_ui(input, |ui| {
            let ctx = ui.ctx().clone();
            if let Some(p) = picture {
                views::paint_behind(&ctx, p, ctx.content_rect());
            }
            if s.show_overlay {
                let panel = Panel {
                    lesson: L::NAME,
                    adapter: &adapter,
                    variants: &s.variants,
                    current: s.current,
                    doc: &doc,
                    cost: &s.cost,
                    error: shown.as_ref(),
                    no_reference: r.live.is_none(),
                    view: s.view,
                    view_note: view_note.as_deref(),
                    knobs: &knobs,
                    settings_line: s.settings_line.as_deref(),
                    lights: r.scene.scene.lights.len(),
                    counters: &counters,
                };
                actions = overlay::show(&ctx, &panel);
            }
        });
        r.egui
            .handle_platform_output(&r.window, out.platform_output);
        let out_ppp = out.pixels_per_point;
        let primitives = ctx.tessellate(out.shapes, out.pixels_per_point);
        let overlay = Overlay {
            primitives,
            textures: out.textures_delta,
            pixels_per_point: out.pixels_per_point,
        };

        // 5. On screen.
        let surface_tex = match r.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            _ => {
                r.surface.configure(&r.gpu.device, &r.config);
                return Ok(());
            }
        };
        let view = surface_tex
            .texture
            .create_view(&wgpu::TextureViewDescriptor {
                format: r.config.view_formats.first().copied(),
                ..Default::default()
            });
        r.present.draw(&r.gpu, s.view, overlay, &view);
        r.gpu.queue.present(surface_tex);
        self.frames += 1;
        let rect = actions.rect.map(|r| {
            let ppp = out_ppp;
            [r.min.x * ppp, r.min.y * ppp, r.max.x * ppp, r.max.y * ppp]
        });
        self.write_log(&shown, rect)?;

        // 6. What the overlay asked for, for the next frame.
        if let Some(i) = actions.variant {
            self.select_variant(i);
        }
        if let Some(v) = actions.view {
            self.state.view = v;
        }
        for (name, value) in actions.knobs {
            let r = self.running.as_mut().expect("checked above");
            apply_knob(&mut r.lesson, &r.gpu, &r.scene, variant, name, value)?;
            self.state.restart_gpu_times(r.timer.frames());
            self.state.buffer_at = None;
            self.state.image_changed();
        }
        if actions.print_settings {
            self.print_settings()?;
        }
        self.finish_if_done(el)
    }

    /// `--capture` after `--capture-after` frames (and the full figure of
    /// the view, when the live reference runs), `--window-seconds`.
    fn finish_if_done(&mut self, el: &ActiveEventLoop) -> Result<()> {
        let after = self.args.capture_after.unwrap_or(DEFAULT_CAPTURE_AFTER) as u64;
        let s = &self.state;
        let full = s
            .answer
            .as_ref()
            .is_some_and(|a| a.stamp == s.stamp && a.level == Level::Full);
        let live = self.running.as_ref().is_some_and(|r| r.live.is_some());
        let frames_done = (self.args.capture.is_some() || self.args.capture_after.is_some())
            && self.frames >= after;
        // The counters read back later (a page's, `WORKBOOK_AS_PAGE`) too.
        let counting = crate::gpu::read_later::waiting();
        if frames_done && live && (!full || counting) && self.args.capture.is_some() {
            let waited = self.capture_wait.get_or_insert_with(Instant::now);
            if waited.elapsed() < CAPTURE_WAIT {
                return Ok(());
            }
            if counting {
                anyhow::bail!(
                    "--capture: the lesson's counts did not come back within {} s of frame {after}",
                    CAPTURE_WAIT.as_secs()
                );
            }
            anyhow::bail!(
                "--capture: the live reference gave no full figure for the view within {} s of frame {after}; capture with --no-live-reference, or keep the camera still (--orbit-seconds)",
                CAPTURE_WAIT.as_secs()
            );
        }
        let time_done = self
            .args
            .window_seconds
            .is_some_and(|s| self.started.elapsed().as_secs_f64() >= s);
        if !(frames_done || time_done) {
            return Ok(());
        }
        if let (Some(path), Some(r)) = (&self.args.capture, &self.running) {
            save_capture(&r.present.read_picture(&r.gpu)?, path)?;
        }
        el.exit();
        Ok(())
    }

    /// One `--window-log` line: the frame's time and cost, the view it
    /// shows, and the error figure with the view it was computed for.
    fn write_log(&mut self, shown: &Option<ShownError>, overlay: Option<[f32; 4]>) -> Result<()> {
        #[cfg(not(target_arch = "wasm32"))]
        if self.log.is_none() {
            return Ok(());
        }
        let s = &self.state;
        let answer = s.answer.as_ref().map(|a| {
            serde_json::json!({
                "scene_gen": a.stamp.scene_gen,
                "image_gen": a.stamp.image_gen,
                "level": match a.level { Level::Coarse => "coarse", Level::Full => "full" },
                "worker_ms": a.ms,
                "misclassified_pct": a.error.misclassified_pct,
                "false_shadow_pct": a.error.false_shadow_pct,
                "false_lit_pct": a.error.false_lit_pct,
                // An area light's: the error inside the penumbra.
                "penumbra_mean_abs": a.error.soft.as_ref().map(|x| x.penumbra_mean_abs),
                "light_bleeding_pct": a.error.soft.as_ref().map(|x| x.light_bleeding_pct),
            })
        });
        let line = serde_json::json!({
            "frame": self.frames,
            "width": self.running.as_ref().map(|r| r.targets.width),
            "height": self.running.as_ref().map(|r| r.targets.height),
            "t_s": self.started.elapsed().as_secs_f64(),
            "variant": s.variants[s.current],
            "scene_gen": s.stamp.scene_gen,
            "image_gen": s.stamp.image_gen,
            "cost_ms": s.cost.ms,
            // The GPU's total and passes over the last frames timed:
            // [q25, median, q75] ms; in a page, how late they were read.
            "gpu_ms": gpu_spreads(&s.cost),
            // The lesson's counters for the variant shown, as the report's.
            "counters": self.running.as_ref().map(|r| r.lesson.counters(self.variants[s.current])),
            "gpu_frames": s.cost.gpu.len(),
            "gpu_read_late": s.cost.late.map(|(late, _)| late),
            "timestamp_quantum_ns": s.cost.late.map(|(_, q)| q),
            "fps": s.cost.fps,
            "error": answer,
            "error_current": shown.as_ref().is_some_and(|e| !e.stale),
            "adapter": self.adapter_line,
            "rss_kb": rss_kb(),
            "overlay_px": overlay,
        });
        // A page shows the line to its scripts (the web check reads it).
        #[cfg(target_arch = "wasm32")]
        self.page.publish(&line);
        let Some(log) = self.log.as_mut() else {
            return Ok(());
        };
        writeln!(log, "{line}").context("--window-log: cannot write")
    }
}

/// Every GPU key's `[q25, median, q75]` over the frames the overlay keeps.
fn gpu_spreads(cost: &super::overlay::Cost) -> serde_json::Value {
    let keys = cost.gpu.back().into_iter().flat_map(|f| f.keys());
    let spreads = keys.filter_map(|k| Some((k.clone(), cost.gpu_spread(k)?.to_vec())));
    serde_json::json!(spreads.collect::<std::collections::BTreeMap<_, _>>())
}

/// What the diff image shows, in one line.
fn diff_title(a: &super::live::Answer) -> String {
    let level = match a.level {
        Level::Coarse => "coarse estimate",
        Level::Full => "every pixel",
    };
    format!("diff against the exact reference, light 0 ({level}): red false shadow, green false lit, gray agree, near black not a receiver")
}

/// What the dv image shows, in one line, at the diff's `level` (read from
/// its title).
fn dv_title(diff_title: &str) -> String {
    let level = match diff_title.contains("coarse") {
        true => "coarse estimate",
        false => "every pixel",
    };
    format!("signed error V − V_ref, light 0 ({level}): blue darker than exact, red lighter, white agree, dark gray not a receiver")
}

/// This process's resident memory (Linux), for the log.
fn rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find_map(|l| l.strip_prefix("VmRSS:"))?;
    line.trim().trim_end_matches("kB").trim().parse().ok()
}

/// `--capture`'s PNG; not generic, so that its encoder is compiled once,
/// here, not in each lesson binary.
fn save_capture(picture: &image::RgbaImage, path: &std::path::Path) -> Result<()> {
    picture
        .save(path)
        .with_context(|| format!("--capture: cannot write {}", path.display()))
}
