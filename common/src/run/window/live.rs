//! The window's error figure, live: the exact reference follows the camera
//! and the light, recomputed on worker threads so that the window never
//! waits for it.
//!
//! The window sends a [`Job`] (the scene as it is now, and the variant's
//! frame read back at that moment) whenever the view, the light, the
//! variant or a knob changed and the worker is idle. A new view is ray cast
//! twice: coarse first (a quarter of the width and height, so 1/16 of the
//! rays, compared with the frame's matching pixels) and then at full size.
//! A job whose view has moved on by the window's first frame after its
//! coarse pass stops there: while the camera moves, the figure is coarse
//! and follows it; once it stops, the full one comes (and on a CPU
//! adapter the window draws its still view slowly meanwhile, so that the
//! rays get the cores: `frame::STILL_FRAME_EVERY`). The
//! worker threads run at the lowest priority the system gives (`nice` 19
//! on Linux), so that they take what the renderer leaves idle rather than
//! slow it down.

#[cfg(not(target_arch = "wasm32"))]
use std::sync::atomic::{AtomicU64, Ordering};
#[cfg(not(target_arch = "wasm32"))]
use std::sync::mpsc::{channel, Receiver, Sender, TryRecvError};
#[cfg(not(target_arch = "wasm32"))]
use std::sync::Arc;
#[cfg(not(target_arch = "wasm32"))]
use std::thread::JoinHandle;

use anyhow::Result;
use image::RgbaImage;
#[cfg(not(target_arch = "wasm32"))]
use web_time::Instant;

#[cfg(not(target_arch = "wasm32"))]
use super::live_server::Server;
use crate::gpu::targets::{FrameImages, FrameTargets, PendingFrame};
use crate::gpu::Gpu;
use crate::measure::report::combine;
use crate::reference::dv_view::dv_image;
use crate::reference::metrics::{compare, ErrorStats};
use crate::reference::{try_render_reference, Reference};
use crate::scene::Scene;

/// In a web page, one thread: the reference works between frames.
#[cfg(target_arch = "wasm32")]
pub use super::live_page::LiveReference;

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

#[cfg(not(target_arch = "wasm32"))]
/// The worker thread and its channels.
pub struct LiveReference {
    jobs: Option<Sender<PendingJob>>,
    answers: Receiver<Result<Answer, String>>,
    /// Answers received by [`LiveReference::ready`] and not yet read.
    arrived: Vec<Result<Answer, String>>,
    worker: Option<JoinHandle<()>>,
    busy: bool,
    /// The window's view now, read by the worker.
    latest: Arc<Shown>,
}

#[cfg(not(target_arch = "wasm32"))]
impl LiveReference {
    /// Starts the worker (a thread that owns a low-priority thread pool).
    pub fn start() -> Result<Self> {
        // One core is left to the window (and, on a software rasteriser,
        // to its GPU).
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let threads = cores.saturating_sub(1).max(1);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("reference-{i}"))
            .start_handler(|_| lower_priority())
            .build()?;
        let (job_tx, job_rx) = channel::<PendingJob>();
        let (ans_tx, answers) = channel();
        let latest = Arc::new(Shown::default());
        let now = latest.clone();
        let worker = std::thread::Builder::new()
            .name("reference".into())
            .spawn(move || {
                lower_priority();
                serve(&pool, &job_rx, &ans_tx, &now);
            })?;
        Ok(LiveReference {
            jobs: Some(job_tx),
            answers,
            arrived: Vec::new(),
            worker: Some(worker),
            busy: false,
            latest,
        })
    }

    /// Whether a job is under way (the window sends the next one only when not).
    pub fn busy(&self) -> bool {
        self.busy
    }

    /// Tells the worker which view the window's next frame draws.
    pub fn note_view(&self, scene_gen: u64) {
        self.latest.scene_gen.store(scene_gen, Ordering::Relaxed);
        self.latest.frames.fetch_add(1, Ordering::Relaxed);
    }

    /// Sends a job (only when not [`LiveReference::busy`]), once
    /// [`PendingJob::ready`].
    pub fn send(&mut self, job: PendingJob) {
        if let Some(tx) = &self.jobs {
            self.busy = tx.send(job).is_ok();
        }
    }

    /// Whether an answer (or the worker's failure) is waiting to be read.
    pub fn ready(&mut self) -> bool {
        while let Ok(a) = self.answers.try_recv() {
            self.arrived.push(a);
        }
        !self.arrived.is_empty()
    }

    /// The answers that arrived since the last call, oldest first.
    pub fn answers(&mut self) -> Result<Vec<Answer>> {
        self.ready();
        let mut out = Vec::new();
        for a in self.arrived.drain(..) {
            match a {
                Ok(a) => {
                    if a.last {
                        self.busy = false;
                    }
                    out.push(a);
                }
                Err(e) => anyhow::bail!("the live reference failed: {e}"),
            }
        }
        match self.answers.try_recv() {
            // Came after `ready`: read with the next call.
            Ok(a) => self.arrived.push(a),
            Err(TryRecvError::Disconnected) => {
                anyhow::bail!("the live reference's worker stopped")
            }
            Err(TryRecvError::Empty) => {}
        }
        Ok(out)
    }
}

#[cfg(not(target_arch = "wasm32"))]
impl Drop for LiveReference {
    fn drop(&mut self) {
        self.jobs = None; // the worker's loop ends when the channel closes
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
/// What the window draws: the view (`scene_gen`) of its latest frame, and
/// how many frames it began.
#[derive(Default)]
struct Shown {
    scene_gen: AtomicU64,
    frames: AtomicU64,
}

#[cfg(not(target_arch = "wasm32"))]
impl Shown {
    /// Whether the view has moved on from `scene_gen`, judged at the
    /// window's next frame: a view still on screen when a coarse pass ends
    /// may be one frame of a moving camera, and its full pass (16 times
    /// the rays) would leave the figure behind the camera for seconds.
    fn moved_on(&self, scene_gen: u64) -> bool {
        let frames = self.frames.load(Ordering::Relaxed);
        let waited = Instant::now();
        while self.frames.load(Ordering::Relaxed) == frames && waited.elapsed() < NEXT_FRAME_WAIT {
            std::thread::sleep(std::time::Duration::from_millis(2));
        }
        self.scene_gen.load(Ordering::Relaxed) != scene_gen
    }
}

#[cfg(not(target_arch = "wasm32"))]
/// The longest the worker waits for the window's next frame.
const NEXT_FRAME_WAIT: std::time::Duration = std::time::Duration::from_secs(1);

#[cfg(not(target_arch = "wasm32"))]
/// The worker's loop: one job at a time ([`Server`]: coarse for a new
/// view, then full unless the window's view moved on meanwhile).
fn serve(
    pool: &rayon::ThreadPool,
    jobs: &Receiver<PendingJob>,
    answers: &Sender<Result<Answer, String>>,
    latest: &Shown,
) {
    let mut server = Server::default();
    while let Ok(job) = jobs.recv() {
        let job = match job.into_job() {
            Ok(job) => job,
            Err(e) => {
                let _ = answers.send(Err(format!("{e:#}")));
                return;
            }
        };
        let gen = job.stamp.scene_gen;
        let result = pool.install(|| -> Result<Option<Answer>> {
            let mut a = server.take(job)?;
            if a.level == Level::Full {
                return Ok(Some(a));
            }
            let overtaken = latest.moved_on(gen);
            a.last = overtaken;
            if answers.send(Ok(a)).is_err() || overtaken {
                server.drop_waiting();
                return Ok(None);
            }
            server.full().map(Some)
        });
        match result {
            Ok(Some(a)) => {
                if answers.send(Ok(a)).is_err() {
                    return;
                }
            }
            Ok(None) => {}
            Err(e) => {
                let _ = answers.send(Err(format!("{e:#}")));
                return;
            }
        }
    }
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

#[cfg(not(target_arch = "wasm32"))]
/// Lowers the calling thread's priority to the least (Linux: `nice` 19 for
/// this thread alone). Elsewhere the threads keep the normal priority.
fn lower_priority() {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: plain system calls on the calling thread's own id.
        unsafe {
            let tid = libc::syscall(libc::SYS_gettid) as libc::id_t;
            libc::setpriority(libc::PRIO_PROCESS, tid, 19);
        }
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
