//! The window's controls: the camera (drag, scroll, `--orbit`), the first
//! light (arrows, PageUp/PageDown), the keys, and the command line that
//! reproduces what the window shows (`K`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use glam::{DQuat, DVec3};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{Key, NamedKey};

use super::App;
use crate::run::instruments::Instruments;
use crate::run::view::View;
use crate::scene::LightKind;

impl<L: Instruments> App<L> {
    /// Turns the camera around its target: `dx`, `dy` in pixels of drag
    /// (0.01 radian each).
    pub(super) fn orbit(&mut self, dx: f64, dy: f64) {
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
        self.state.view_changed();
    }

    pub(super) fn zoom(&mut self, amount: f64) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let c = &mut r.scene.scene.camera;
        c.eye = c.target + (c.eye - c.target) * (1.0 - amount * 0.1).clamp(0.5, 1.5);
        r.scene.set_camera(&r.gpu);
        self.state.view_changed();
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
        self.state.view_changed();
    }

    /// A key pressed outside the overlay's widgets.
    pub(super) fn key(&mut self, el: &ActiveEventLoop, key: &Key) -> Result<()> {
        match key {
            // A page has no window to close: Escape is for the desktop.
            Key::Named(NamedKey::Escape) if cfg!(target_arch = "wasm32") => {}
            Key::Named(NamedKey::Escape) => el.exit(),
            Key::Named(NamedKey::Space) => self.step_variant(1),
            Key::Named(NamedKey::Tab) => self.state.view = self.state.view.next(),
            Key::Character(c) if c.as_str() == "v" => self.step_variant(1),
            Key::Character(c) if c.as_str() == "V" => self.step_variant(-1),
            Key::Character(c) if c.eq_ignore_ascii_case("h") => {
                self.state.show_overlay = !self.state.show_overlay
            }
            Key::Character(c) if c.eq_ignore_ascii_case("k") => self.print_settings()?,
            Key::Character(c) => {
                if let Some(v) = View::of_key(c.as_str()) {
                    self.state.view = v;
                }
            }
            Key::Named(k) => self.move_light(k),
            _ => {}
        }
        Ok(())
    }

    /// The variant `by` places on (wrapping).
    pub(super) fn step_variant(&mut self, by: i64) {
        let n = self.variants.len() as i64;
        let next = (self.state.current as i64 + by).rem_euclid(n) as usize;
        self.select_variant(next);
    }

    pub(super) fn select_variant(&mut self, i: usize) {
        if i != self.state.current && i < self.variants.len() {
            self.state.current = i;
            self.state.buffer_at = None;
            let frames = self.running.as_ref().map_or(0, |r| r.timer.frames());
            self.state.restart_gpu_times(frames);
            self.state.image_changed();
        }
    }

    /// Prints (and shows) the command line that renders what the window
    /// shows, headless: the variant, its knobs, and the view and light as
    /// a scene file written beside the outputs when they moved.
    pub(super) fn print_settings(&mut self) -> Result<()> {
        let Some(r) = self.running.as_ref() else {
            return Ok(());
        };
        let v = self.variants[self.state.current];
        let mut line = format!(
            "cargo run --release --bin {} -- --headless --variant {}",
            L::NAME,
            self.state.variants[self.state.current]
        );
        for k in r.lesson.knobs(v) {
            line += &format!(" --knob {}={}", k.name, k.value_text());
        }
        let text = scene_text(&self.args.scene, L::DEFAULT_SCENE, &r.scene.scene)?;
        // A page has no files: the scene goes to the browser's console.
        #[cfg(target_arch = "wasm32")]
        {
            web_sys::console::log_1(&format!("window_scene.toml:\n{text}").into());
            line += " --scene window_scene.toml (the scene file is in the browser's console: save it under that name)";
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            let out = (self.args.out.clone()).unwrap_or_else(|| PathBuf::from("out").join(L::NAME));
            let path = out.join("window_scene.toml");
            if let Some(d) = path.parent() {
                std::fs::create_dir_all(d)
                    .with_context(|| format!("cannot create {}", d.display()))?;
            }
            std::fs::write(&path, text)
                .with_context(|| format!("cannot write {}", path.display()))?;
            line += &format!(" --scene {}", path.display());
        }
        if (self.args.width, self.args.height) != (r.config.width, r.config.height) {
            line += &format!(" --width {} --height {}", r.config.width, r.config.height);
        }
        println!("{line}");
        self.state.settings_line = Some(line);
        Ok(())
    }
}

/// The scene the window shows (its file, or the lesson's default, with
/// the camera and the lights as they are now), as TOML. Mesh paths become
/// absolute, so that the file works from its new folder.
/// Not generic (the lesson's default scene is an argument), so that the
/// TOML writer is compiled once, here, not in each lesson binary.
fn scene_text(
    file: &Option<PathBuf>,
    default_scene: &str,
    scene: &crate::scene::Scene,
) -> Result<String> {
    let (text, dir) = match file {
        Some(f) => (
            std::fs::read_to_string(f).with_context(|| format!("cannot read {}", f.display()))?,
            f.parent().map(Path::to_path_buf).unwrap_or_default(),
        ),
        None => (default_scene.to_string(), PathBuf::from(".")),
    };
    let mut doc: toml::Table = toml::from_str(&text).context("the scene file no longer parses")?;
    let arr = |v: DVec3| toml::Value::Array(v.to_array().map(toml::Value::Float).to_vec());
    if let Some(toml::Value::Table(cam)) = doc.get_mut("camera") {
        cam.insert("eye".into(), arr(scene.camera.eye));
        cam.insert("target".into(), arr(scene.camera.target));
    }
    if let Some(toml::Value::Array(lights)) = doc.get_mut("lights") {
        for (t, l) in lights.iter_mut().zip(&scene.lights) {
            let Some(t) = t.as_table_mut() else { continue };
            match &l.kind {
                LightKind::Directional { direction } => {
                    t.insert("direction".into(), arr(*direction))
                }
                LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
                    t.insert("position".into(), arr(*position))
                }
            };
        }
    }
    if let Some(toml::Value::Array(objects)) = doc.get_mut("objects") {
        for o in objects.iter_mut().filter_map(|o| o.as_table_mut()) {
            if let Some(toml::Value::String(m)) = o.get_mut("mesh") {
                let builtin = !m.to_ascii_lowercase().ends_with(".obj");
                if !builtin && Path::new(m.as_str()).is_relative() {
                    let abs = std::path::absolute(dir.join(m.as_str()))?;
                    *m = abs.display().to_string();
                }
            }
        }
    }
    toml::to_string(&doc).context("cannot write the scene as TOML")
}
