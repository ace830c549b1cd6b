//! A scene's `[camera_path]`: a slow pan, then a dolly, rendered frame by
//! frame to measure *shimmer* (chapter 09): shadow pixels that flip between
//! consecutive frames where the exact reference does not.
//!
//! Between frames i and i + 1 two things change: the view (every shadow
//! edge sweeps across the screen, and the reference's edges with it) and
//! the shadow maps' fit. Shimmer is the second alone, so it is measured
//! *world-locked*: frame i's view, rendered once with frame i's fit and
//! once with frame i + 1's (a *probe*). The pixels see the same surfaces
//! both times, so the reference cannot flip, and every pixel whose shadow
//! flips is shimmer. The screen-space flips of consecutive frames are
//! reported beside it: there, a technique whose shadow edge sits a pixel
//! from the exact one flips a frame early or late as the edge sweeps
//! past, and that counts as a mismatch even when its maps hold still.
//!
//! The path is pure camera maths ([`path_cameras`]); the headless runner
//! renders it ([`crate::run::headless`]) and [`Shimmer`] counts the flips.

use anyhow::Result;
use glam::DQuat;
use image::{GrayImage, Luma, Rgba, RgbaImage};

use crate::measure::report::CameraPathReport;
use crate::reference::metrics::PixelState;
pub use crate::scene::file::{CameraPath, MAX_PAN_DEG, MAX_PATH_FRAMES};
use crate::scene::limits::check_coord;
use crate::scene::{Camera, Scene};

impl CameraPath {
    /// How far along the pan and the dolly frame `i` is, each in [0, 1].
    pub fn progress(&self, i: u32) -> (f64, f64) {
        let (n, half) = (self.frames.max(2), self.frames.max(2) / 2);
        let pan = i.min(half) as f64 / half as f64;
        // With 2 frames the pan's end is the last frame: it dollies too.
        let dolly = match n - 1 - half {
            0 => f64::from(u8::from(i >= n - 1)),
            steps => i.saturating_sub(half).min(steps) as f64 / steps as f64,
        };
        (pan, dolly)
    }
}

/// The path's last eye and target are within the world's bounds (what
/// [`crate::scene`] checks of the scene's own camera). `Ok` without a path.
pub fn check_path(scene: &Scene) -> Result<()> {
    let Some(path) = &scene.camera_path else {
        return Ok(());
    };
    if let Some(last) = path_cameras(&scene.camera, path).last() {
        check_coord(last.eye.to_array(), "camera_path.dolly: the last eye")?;
        check_coord(last.target.to_array(), "camera_path.dolly: the last target")?;
    }
    Ok(())
}

// ANCHOR: path_cameras
/// The cameras along `path`: frame 0 is `camera`, frames up to n/2 yaw the
/// view direction about `up` (around the eye), the rest move eye and
/// target forward together. The last frame has all of `pan_deg` and `dolly`.
pub fn path_cameras(camera: &Camera, path: &CameraPath) -> Vec<Camera> {
    let view = camera.target - camera.eye;
    let yaw = |t: f64| DQuat::from_axis_angle(camera.up.normalize(), t * path.pan_deg.to_radians());
    let forward = (yaw(1.0) * view).normalize();
    (0..path.frames)
        .map(|i| {
            let (pan, dolly) = path.progress(i);
            let step = forward * (dolly * path.dolly);
            Camera {
                eye: camera.eye + step,
                target: camera.eye + yaw(pan) * view + step,
                ..camera.clone()
            }
        })
        .collect()
}
// ANCHOR_END: path_cameras

// ANCHOR: shimmer
/// Counts flips along a path, one frame at a time: for each pair of
/// consecutive frames, light and pixel that is a receiver in both (the
/// [`PixelState`]s of [`crate::reference::metrics::pixel_states`]), whether the
/// technique's lit/shadowed flips, whether the reference's does, and a
/// *shimmer* pixel where the technique flips and the reference does not.
pub struct Shimmer {
    width: u32,
    height: u32,
    /// The previous frame's states, one list per light.
    prev: Option<Vec<Vec<PixelState>>>,
    /// Per pixel: shimmer flips, summed over pairs and lights.
    count: Vec<u32>,
    pairs: u64,
    covered: u64,
    /// Screen-space: technique flips where the reference does not.
    screen_mismatch: u64,
    /// World-locked: receivers of both renders of a probe, and flips.
    locked_covered: u64,
    shimmer: u64,
    technique_flips: u64,
    reference_flips: u64,
    misclassified_pct_per_frame: Vec<f64>,
}

impl Shimmer {
    pub fn new(width: u32, height: u32) -> Shimmer {
        Shimmer {
            width,
            height,
            prev: None,
            count: vec![0; width as usize * height as usize],
            pairs: 0,
            covered: 0,
            screen_mismatch: 0,
            locked_covered: 0,
            shimmer: 0,
            technique_flips: 0,
            reference_flips: 0,
            misclassified_pct_per_frame: Vec::new(),
        }
    }

    /// Adds the next frame: `states[k]` is light `k`'s per-pixel state.
    ///
    /// Panics if a light's list is not `width × height` long.
    pub fn add_frame(&mut self, states: Vec<Vec<PixelState>>) {
        let n = self.count.len();
        assert!(
            states.iter().all(|s| s.len() == n),
            "states must be {n} pixels"
        );
        let receivers = states.iter().flatten().flatten();
        let (all, wrong) = receivers.fold((0u64, 0u64), |(all, wrong), &(exact, gpu)| {
            (all + 1, wrong + u64::from(exact != gpu))
        });
        let misclassified = 100.0 * wrong as f64 / all.max(1) as f64;
        self.misclassified_pct_per_frame.push(misclassified);
        if let Some(prev) = &self.prev {
            self.pairs += 1;
            for (before, after) in prev.iter().zip(&states) {
                for (p, (b, a)) in before.iter().zip(after).enumerate() {
                    let (Some(b), Some(a)) = (b, a) else { continue };
                    let (reference, technique) = (b.0 != a.0, b.1 != a.1);
                    self.covered += 1;
                    self.reference_flips += u64::from(reference);
                    self.technique_flips += u64::from(technique);
                    let _ = p;
                    self.screen_mismatch += u64::from(technique && !reference);
                }
            }
        }
        self.prev = Some(states);
    }

    /// Adds a world-locked probe: `fitted` is a frame's own render (view i,
    /// fit i), `probe` the same view with the next frame's fit (i + 1).
    /// `seen_next[p]`: pixel p's surface is inside frame i + 1's view too
    /// (elsewhere the moving viewer never sees both). Every flip of a
    /// receiver in both renders is shimmer: the reference is the same.
    ///
    /// Panics if a list is not `width × height` long.
    pub fn add_probe(
        &mut self,
        fitted: &[Vec<PixelState>],
        probe: &[Vec<PixelState>],
        seen_next: &[bool],
    ) {
        let n = self.count.len();
        assert!(
            seen_next.len() == n && fitted.iter().chain(probe).all(|s| s.len() == n),
            "states must be {n} pixels"
        );
        for (a, b) in fitted.iter().zip(probe) {
            for (p, (a, b)) in a.iter().zip(b).enumerate() {
                let (Some(a), Some(b)) = (a, b) else { continue };
                if !seen_next[p] {
                    continue;
                }
                self.locked_covered += 1;
                if a.1 != b.1 {
                    self.shimmer += 1;
                    self.count[p] += 1;
                }
            }
        }
    }

    /// The figures so far: percentages of the receiver pixels of every
    /// pair and light together (the mean over pairs, weighted by pixels).
    pub fn report(&self) -> CameraPathReport {
        let pct = |k: u64| 100.0 * k as f64 / self.covered.max(1) as f64;
        CameraPathReport {
            frames: self.misclassified_pct_per_frame.len() as u32,
            shimmer_pct: 100.0 * self.shimmer as f64 / self.locked_covered.max(1) as f64,
            screen_mismatch_pct: pct(self.screen_mismatch),
            reference_flip_pct: pct(self.reference_flips),
            technique_flip_pct: pct(self.technique_flips),
            misclassified_pct_per_frame: self.misclassified_pct_per_frame.clone(),
        }
    }

    /// Where it shimmers: black where no pixel flipped wrongly, else from
    /// 80 (one flip) to 255 (a flip in every pair and light, `most`). The
    /// scale is fixed, so that two variants' pictures compare.
    pub fn image(&self, lights: usize) -> GrayImage {
        let most = (self.pairs * lights as u64).max(2) as f64;
        GrayImage::from_fn(self.width, self.height, |x, y| {
            let c = self.count[(y * self.width + x) as usize];
            let gray = if c == 0 {
                0.0
            } else {
                80.0 + 175.0 * (c as f64 - 1.0).min(most - 1.0) / (most - 1.0)
            };
            Luma([gray.round() as u8])
        })
    }

    /// [`Self::image`] drawn over the frame it was measured on: the frame
    /// in dim grey, so that the scene shows where nothing flipped, and each
    /// pixel that flipped in orange to yellow on the same fixed scale.
    pub fn image_over(&self, lights: usize, frame: &RgbaImage) -> RgbaImage {
        let flips = self.image(lights);
        RgbaImage::from_fn(self.width, self.height, |x, y| {
            let f = frame.get_pixel(x, y).0;
            let c = flips.get_pixel(x, y).0[0];
            if c > 0 {
                let t = (c as f32 - 80.0) / 175.0;
                Rgba([255, (140.0 + 115.0 * t) as u8, (40.0 * t) as u8, 255])
            } else {
                let luma = 0.299 * f[0] as f32 + 0.587 * f[1] as f32 + 0.114 * f[2] as f32;
                let g = (30.0 + 0.45 * luma) as u8;
                Rgba([g, g, g, 255])
            }
        })
    }
}
// ANCHOR_END: shimmer

#[cfg(test)]
#[path = "unit_tests/camera_path.rs"]
mod tests;
