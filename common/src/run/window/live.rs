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

#[cfg(not(target_arch = "wasm32"))]
use anyhow::Result;
#[cfg(not(target_arch = "wasm32"))]
use web_time::Instant;

#[cfg(not(target_arch = "wasm32"))]
use super::live_server::Server;

pub use super::live_job::{Answer, Job, Level, PendingJob, Stamp, COARSE};

/// In a web page, one thread: the reference works between frames.
#[cfg(target_arch = "wasm32")]
pub use super::live_page::LiveReference;

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
