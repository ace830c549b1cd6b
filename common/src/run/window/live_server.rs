//! The live reference's side of a job, wherever it runs: on the desktop's
//! worker thread ([`super::live`]) and in the web page's Web Worker
//! ([`super::live_worker`]). A new view is ray cast coarse first
//! ([`Server::take`]); its full pass ([`Server::full`]) follows only if
//! the window still shows that view, which the caller judges between the
//! two. The reference of the last view is kept, so that a new variant or
//! knob on the same view costs a comparison, not a ray cast.

use anyhow::{anyhow, Result};
use web_time::Instant;

use super::live_job::{measure, measure_coarse, Answer, Job, Level};
use crate::reference::{try_render_reference, Reference};

/// The job under way and the reference of the last view.
#[derive(Default)]
pub struct Server {
    /// The job whose coarse answer was given, waiting for [`Server::full`].
    waiting: Option<(Job, Instant)>,
    cached: Option<(u64, Reference)>,
}

impl Server {
    /// Answers a new job: coarse for a view it has no reference of (the
    /// job then waits for [`Server::full`] or the next job), full for the
    /// view it has (the job ends).
    pub fn take(&mut self, job: Job) -> Result<Answer> {
        let start = Instant::now();
        let ms = || start.elapsed().as_secs_f64() * 1e3;
        self.waiting = None;
        let gen = job.stamp.scene_gen;
        match &self.cached {
            Some((g, reference)) if *g == gen => {
                let measured = measure(reference, &job.frame);
                Ok(Answer::new(&job, Level::Full, measured, ms(), true))
            }
            _ => {
                let measured = measure_coarse(&job)?;
                let answer = Answer::new(&job, Level::Coarse, measured, ms(), false);
                self.waiting = Some((job, start));
                Ok(answer)
            }
        }
    }

    /// The full pass of the job [`Server::take`] answered coarse: every
    /// pixel ray cast, then compared. The job ends.
    pub fn full(&mut self) -> Result<Answer> {
        let (job, start) = (self.waiting.take()).ok_or_else(|| {
            anyhow!("the live reference was asked for a full pass with no job waiting")
        })?;
        let (w, h) = (job.frame.width, job.frame.height);
        let reference = try_render_reference(&job.scene, job.view_proj, w, h)?;
        let measured = measure(&reference, &job.frame);
        self.cached = Some((job.stamp.scene_gen, reference));
        let ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(Answer::new(&job, Level::Full, measured, ms, true))
    }

    /// Ends the job waiting for its full pass (the view moved on).
    pub fn drop_waiting(&mut self) {
        self.waiting = None;
    }
}
