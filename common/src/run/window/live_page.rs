//! The live reference in a web page: the page has one thread, so the
//! reference works between the window's frames instead of beside them.
//! It answers as the desktop's worker does ([`super::live`]): a new view
//! is ray cast coarse first, and the coarse figure is on screen for a frame
//! before the full pass, which stops there if the view has moved on. The
//! full pass holds that frame back for as long as it casts (a second or
//! two at 720×405 on a laptop's CPU).

use anyhow::Result;
use web_time::Instant;

use super::live::{measure, measure_coarse, Answer, Job, Level, PendingJob};
use crate::reference::{try_render_reference, Reference};

/// The job under way and the reference of the last view.
#[derive(Default)]
pub struct LiveReference {
    job: Option<(Job, Instant)>,
    /// The coarse answer of the job under way was given.
    coarse_given: bool,
    /// The view the window's latest frame draws.
    view_now: std::cell::Cell<u64>,
    cached: Option<(u64, Reference)>,
    arrived: Vec<Answer>,
    failed: Option<anyhow::Error>,
}

impl LiveReference {
    pub fn start() -> Result<Self> {
        Ok(LiveReference::default())
    }

    pub fn busy(&self) -> bool {
        self.job.is_some()
    }

    pub fn note_view(&self, scene_gen: u64) {
        self.view_now.set(scene_gen);
    }

    /// Takes a job once [`PendingJob::ready`], its images copied out here.
    pub fn send(&mut self, job: PendingJob) {
        let start = Instant::now();
        match job.into_job() {
            Ok(job) => self.job = Some((job, start)),
            Err(e) => self.failed = Some(e),
        }
        self.coarse_given = false;
    }

    /// Does the job's next step (one per call: the coarse pass, then the
    /// full one) and says whether an answer is waiting.
    pub fn ready(&mut self) -> bool {
        if self.arrived.is_empty() {
            if let Err(e) = self.step() {
                // Kept for `answers`, which fails with it.
                self.job = None;
                self.failed = Some(e);
            }
        }
        !self.arrived.is_empty() || self.failed.is_some()
    }

    pub fn answers(&mut self) -> Result<Vec<Answer>> {
        self.ready();
        if let Some(e) = self.failed.take() {
            anyhow::bail!("the live reference failed: {e:#}");
        }
        Ok(self.arrived.drain(..).collect())
    }

    fn step(&mut self) -> Result<()> {
        let Some((job, start)) = &self.job else {
            return Ok(());
        };
        let ms = || start.elapsed().as_secs_f64() * 1e3;
        let (w, h) = (job.frame.width, job.frame.height);
        let gen = job.stamp.scene_gen;
        let fresh = self.cached.as_ref().is_none_or(|(g, _)| *g != gen);
        if fresh && !self.coarse_given {
            let measured = measure_coarse(job)?;
            self.arrived
                .push(Answer::new(job, Level::Coarse, measured, ms(), false));
            self.coarse_given = true;
            return Ok(());
        }
        if fresh && self.view_now.get() != gen {
            // The camera moved on: the next job brings the next view.
            self.job = None;
            return Ok(());
        }
        if fresh {
            let full = try_render_reference(&job.scene, job.view_proj, w, h)?;
            self.cached = Some((gen, full));
        }
        let (_, reference) = self.cached.as_ref().expect("a reference was made above");
        let measured = measure(reference, &job.frame);
        self.arrived
            .push(Answer::new(job, Level::Full, measured, ms(), true));
        self.job = None;
        Ok(())
    }
}
