//! One frame of the window: render the variant, feed and read the live
//! reference, build the overlay, put the picture on screen, and capture or
//! log it when asked.

use std::time::Duration;

use web_time::Instant;

use anyhow::{Context, Result};
use winit::event_loop::ActiveEventLoop;

use super::live::{Level, PendingJob};
use super::overlay;
use super::panel::diff_title;
use super::present::Overlay;
use super::views;
use super::{App, DEFAULT_CAPTURE_AFTER};
use crate::gpu::read_later::later;
use crate::run::instruments::{apply_knob, Instruments};
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

impl<L: Instruments> App<L> {
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

    /// One frame, in six numbered steps (the variant's frame, timed; the
    /// live reference fed and read; the buffer view; the overlay; the
    /// picture on screen; what the overlay asked for), with the orbit
    /// turned before them, and the `--window-log` line written and the
    /// run's end checked around the last.
    pub(super) fn redraw(&mut self, el: &ActiveEventLoop) -> Result<()> {
        if self.running.is_none() {
            return Ok(());
        }
        let now = Instant::now();
        self.advance_orbit(now);
        let variant = self.variants[self.state.current];
        self.render_timed(now, variant)?;
        self.feed_live_reference(now)?;
        self.read_buffer_view(now, variant)?;
        let built = self.build_overlay(variant);
        if !self.present_frame(built.overlay)? {
            return Ok(());
        }
        self.frames += 1;
        self.write_log(&built.shown, built.rect_px)?;
        self.apply_actions(built.actions, variant)?;
        self.finish_if_done(el)
    }

    /// `--orbit`: turns the camera by the time since the last frame, while
    /// `--orbit-seconds` lasts.
    fn advance_orbit(&mut self, now: Instant) {
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
    }

    /// Step 1: the variant's frame, timed as the headless runner times it, and
    /// the cost the overlay shows: this frame's, the GPU's as they come
    /// back, frames per second.
    fn render_timed(&mut self, now: Instant, variant: L::Variant) -> Result<()> {
        let r = self.running.as_mut().expect("checked by redraw");
        let s = &mut self.state;
        // The view this frame draws: a job of an older one stops after
        // its coarse pass.
        if let Some(live) = r.live.as_mut() {
            live.note_view(s.stamp.scene_gen);
        }
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
        Ok(())
    }

    /// Step 2: the live reference: read what it answered, send the next job,
    /// and upload the error image the view shows.
    fn feed_live_reference(&mut self, now: Instant) -> Result<()> {
        let r = self.running.as_mut().expect("checked by redraw");
        let s = &mut self.state;
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
        Ok(())
    }

    /// Step 3: the buffer view, a few times a second while it is shown (in a
    /// web page it comes back a frame or more later: asked again each
    /// frame until it has).
    fn read_buffer_view(&mut self, now: Instant, variant: L::Variant) -> Result<()> {
        let r = self.running.as_mut().expect("checked by redraw");
        let s = &mut self.state;
        let buffer_due = s.buffer_at.is_none_or(|t| now - t > BUFFER_EVERY);
        if s.view != View::Buffer || !(buffer_due || s.buffer_coming) {
            return Ok(());
        }
        s.buffer_at = Some(now);
        let read = later(|| r.lesson.buffer_view(&r.gpu, &r.scene, variant))?;
        s.buffer_coming = read.is_none();
        match read {
            Some(Some(b)) => {
                let stamp = (s.stamp.scene_gen, s.stamp.image_gen);
                let ctx = r.egui.egui_ctx().clone();
                views::upload(&ctx, &mut s.buffer, "buffer", &b.image, b.title, stamp);
                s.buffer_note = None;
            }
            Some(None) => {
                s.buffer = None;
                s.buffer_note = Some(format!("{} has no buffer to show", L::NAME));
            }
            None => {}
        }
        Ok(())
    }

    /// Step 5: the frame and its overlay on screen; `false` when the surface had
    /// no texture to give (it is configured again, and the frame dropped).
    fn present_frame(&mut self, overlay: Overlay) -> Result<bool> {
        let r = self.running.as_mut().expect("checked by redraw");
        let surface_tex = match r.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            _ => {
                r.surface.configure(&r.gpu.device, &r.config);
                return Ok(false);
            }
        };
        let view = surface_tex
            .texture
            .create_view(&wgpu::TextureViewDescriptor {
                format: r.config.view_formats.first().copied(),
                ..Default::default()
            });
        r.present.draw(&r.gpu, self.state.view, overlay, &view);
        r.gpu.queue.present(surface_tex);
        Ok(true)
    }

    /// Step 6: what the overlay asked for, for the next frame: a variant, a
    /// view, knobs, the settings printed.
    fn apply_actions(&mut self, actions: overlay::Actions, variant: L::Variant) -> Result<()> {
        if let Some(i) = actions.variant {
            self.select_variant(i);
        }
        if let Some(v) = actions.view {
            self.state.view = v;
        }
        for (name, value) in actions.knobs {
            let r = self.running.as_mut().expect("checked by redraw");
            apply_knob(&mut r.lesson, &r.gpu, &r.scene, variant, name, value)?;
            self.state.restart_gpu_times(r.timer.frames());
            self.state.buffer_at = None;
            self.state.image_changed();
        }
        if actions.print_settings {
            self.print_settings()?;
        }
        Ok(())
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
}

/// `--capture`'s PNG; not generic, so that its encoder is compiled once,
/// here, not in each lesson binary.
fn save_capture(picture: &image::RgbaImage, path: &std::path::Path) -> Result<()> {
    picture
        .save(path)
        .with_context(|| format!("--capture: cannot write {}", path.display()))
}
