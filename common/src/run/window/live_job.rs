//! The live reference's work, wherever it runs (the window's worker
//! threads, [`super::live`]; a web page's Web Worker, [`super::live_page`]
//! and [`super::live_server`]): a [`Job`] (the scene and the variant's
//! frame at one [`Stamp`]), the frame read back without waiting
//! ([`PendingJob`]), and the [`Answer`] its coarse or full pass gives.

use anyhow::Result;
use image::RgbaImage;

use crate::gpu::targets::{FrameImages, FrameTargets, PendingFrame};
use crate::gpu::Gpu;
use crate::measure::report::combine;
use crate::reference::dv_view::dv_image;
use crate::reference::metrics::{compare, ErrorStats};
use crate::reference::{try_render_reference, Reference};
use crate::scene::Scene;

/// The coarse pass's step: one ray per `COARSE × COARSE` pixels.
pub const COARSE: u32 = 4;

/// What a figure was computed for: the view and light (`scene_gen` counts
/// their changes), the variant and its knobs (`image_gen` counts changes
/// of either, and of the view).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Stamp {
    pub scene_gen: u64,
    pub image_gen: u64,
}

/// One request: the scene and the variant's frame, both as they were at `stamp`.
pub struct Job {
    pub stamp: Stamp,
    pub scene: Scene,
    pub view_proj: glam::Mat4,
    pub frame: FrameImages,
}

/// A job whose frame is on its way back from the GPU. The window never
/// waits for it, nor copies it: it sends the job once the images are
/// mapped ([`PendingJob::ready`], asked once a frame), and the worker
/// copies them out ([`PendingJob::into_job`]). Waiting drained the GPU's
/// queue in the middle of the window's frame, and copying 1280×720 ids and
/// visibility out of the mapped buffers took the window 14-17 ms (lavapipe
/// and llvmpipe, 2 cores), three times a second while the camera moves.
/// (A page has no worker: it copies them when the job reaches it.)
pub struct PendingJob {
    frame: PendingFrame,
    stamp: Stamp,
    scene: Scene,
    view_proj: glam::Mat4,
}

impl PendingJob {
    /// Starts reading back the frame `targets` hold, drawn at `stamp`.
    pub fn start(
        gpu: &Gpu,
        targets: &FrameTargets,
        stamp: Stamp,
        scene: Scene,
        view_proj: glam::Mat4,
    ) -> PendingJob {
        PendingJob {
            frame: targets.start_read_measured(gpu),
            stamp,
            scene,
            view_proj,
        }
    }

    /// Whether the frame's images are mapped, so that the job can go.
    pub fn ready(&self, gpu: &Gpu) -> Result<bool> {
        // The desktop maps a buffer when the device is polled; a page's
        // browser maps it by itself.
        #[cfg(not(target_arch = "wasm32"))]
        gpu.device
            .poll(wgpu::PollType::Poll)
            .map_err(|e| anyhow::anyhow!("GPU poll failed: {e}"))?;
        #[cfg(target_arch = "wasm32")]
        let _ = gpu;
        Ok(self.frame.mapped())
    }

    /// The job, its images copied out of the mapped buffers.
    pub fn into_job(mut self) -> Result<Job> {
        let frame = (self.frame.take())
            .ok_or_else(|| anyhow::anyhow!("the live reference's frame is not mapped yet"))?;
        Ok(Job {
            stamp: self.stamp,
            scene: self.scene,
            view_proj: self.view_proj,
            frame: frame?,
        })
    }
}

/// How many rays an answer rests on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Level {
    /// One ray per [`COARSE`]² pixels, against the frame's matching pixels.
    Coarse,
    /// Every pixel: the figure the headless report gives.
    Full,
}

/// An error figure against the exact reference.
pub struct Answer {
    pub stamp: Stamp,
    pub level: Level,
    /// All lights together, as the report's `error`.
    pub error: ErrorStats,
    /// The difference image of light 0 (red false shadow, green false lit).
    pub diff: RgbaImage,
    /// The signed visibility error of light 0 (`dv_view::dv_image`).
    pub dv: RgbaImage,
    /// Milliseconds from the job's start to this answer.
    pub ms: f64,
    /// Whether this ends the job (the worker is idle after it).
    pub last: bool,
}

/// What one comparison gives: every light's figure (combined), light 0's
/// difference image and its signed ΔV image.
pub(super) type Measured = (ErrorStats, RgbaImage, RgbaImage);

impl Answer {
    /// The answer to `job` at `level`, `ms` after the job began.
    pub(super) fn new(job: &Job, level: Level, measured: Measured, ms: f64, last: bool) -> Answer {
        let (error, diff, dv) = measured;
        Answer {
            stamp: job.stamp,
            level,
            error,
            diff,
            dv,
            ms,
            last,
        }
    }
}

/// The coarse pass of a new view: a reference a [`COARSE`]th of the
/// frame's width and height, against the frame's matching pixels.
pub(super) fn measure_coarse(job: &Job) -> Result<Measured> {
    let (w, h) = (job.frame.width, job.frame.height);
    let (cw, ch) = ((w / COARSE).max(1), (h / COARSE).max(1));
    let coarse = try_render_reference(&job.scene, job.view_proj, cw, ch)?;
    Ok(measure(&coarse, &subsample(&job.frame, cw, ch)))
}

/// Every light's figure (combined), light 0's difference image and its
/// signed ΔV image.
pub(super) fn measure(reference: &Reference, frame: &FrameImages) -> Measured {
    let mut per_light = Vec::new();
    let mut diff = None;
    for (k, vis) in frame.visibility.iter().enumerate() {
        // Receivers below their own horizon for part of the emitter: apart.
        let clipped = reference.horizon_clipped.get(k).map(Vec::as_slice);
        let c = compare(reference, k, &frame.id, vis, clipped);
        per_light.push(c.stats);
        diff.get_or_insert(c.diff);
    }
    let diff = diff.unwrap_or_else(|| RgbaImage::new(frame.width, frame.height));
    let dv = match frame.visibility.first() {
        Some(vis) => dv_image(reference, 0, &frame.id, vis),
        None => RgbaImage::new(frame.width, frame.height),
    };
    (combine(&per_light), diff, dv)
}

/// The frame's pixels nearest the centres of a `cw × ch` grid over it: what
/// a reference of that size compares with.
pub fn subsample(frame: &FrameImages, cw: u32, ch: u32) -> FrameImages {
    let (w, h) = (frame.width as usize, frame.height as usize);
    let index = |i: u32, j: u32| {
        let x = ((i as f64 + 0.5) * w as f64 / cw as f64) as usize;
        let y = ((j as f64 + 0.5) * h as f64 / ch as f64) as usize;
        y.min(h - 1) * w + x.min(w - 1)
    };
    let pick = |i: u32, j: u32| index(i, j);
    let cells = (0..ch).flat_map(|j| (0..cw).map(move |i| (i, j)));
    let idx: Vec<usize> = cells.map(|(i, j)| pick(i, j)).collect();
    FrameImages {
        width: cw,
        height: ch,
        color: match frame.color.is_empty() {
            true => Vec::new(),
            false => idx
                .iter()
                .flat_map(|&p| frame.color[4 * p..4 * p + 4].iter().copied())
                .collect(),
        },
        id: idx.iter().map(|&p| frame.id[p]).collect(),
        visibility: frame
            .visibility
            .iter()
            .map(|v| idx.iter().map(|&p| v[p]).collect())
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subsample_takes_the_pixels_under_the_coarse_centres() {
        let (w, h) = (8u32, 4u32);
        let frame = FrameImages {
            width: w,
            height: h,
            color: vec![0; (w * h * 4) as usize],
            id: (0..w * h).collect(),
            visibility: vec![(0..w * h).map(|p| p as f32).collect()],
        };
        let s = subsample(&frame, 2, 1);
        // Centres at x = 2 and 6 of row 2.
        assert_eq!(s.id, vec![2 * 8 + 2, 2 * 8 + 6]);
        assert_eq!(s.visibility[0], vec![18.0, 22.0]);
    }
}
