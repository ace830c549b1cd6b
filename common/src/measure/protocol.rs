//! The timing protocol: how a run times its variants so that the times hold
//! on a real GPU as well as on lavapipe.
//!
//! A GPU lowers its clock within seconds of idling (an H100 fell from 1980
//! to 345 MHz while the CPU computed references and wrote PNGs between
//! variants), and a few frames of work do not bring it back. So:
//!
//! 1. Every timed block comes first in the run, back to back, before any
//!    CPU-only work (the reference, the comparison, the PNGs).
//! 2. Each block is warmed up right before it is timed, until its frame
//!    times settle ([`WarmUp`], [`Settling`]), not for a fixed count.
//! 3. The no-shadow baseline is timed between the variants
//!    ([`block_order`]), not once at the end.
//! 4. The base pass is the same work in every block, so its time must agree
//!    across them ([`check_base`]). Where it does not, the block's times are
//!    reported as unstable instead of as a number.
//!
//! The functions here are pure: they take frame times and return verdicts,
//! so they are unit-tested on synthetic series (below), including the
//! H100's step from 0.788 ms to 4.655 ms on identical work.

use anyhow::Result;

use crate::gpu::Gpu;
use crate::measure::report::{TimingCheck, TimingProtocolReport};
use crate::measure::timing::{quantile, Frame, FrameTimes, Timer, FRAME, TOTAL};

/// How each block is warmed up before it is timed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WarmUp {
    /// Untimed rendering of each block, at least (wall-clock ms); the
    /// first block of a run renders [`WarmUp::FIRST_BLOCK_FACTOR`] times
    /// as long, to bring an idle GPU up to its working clock (and a fresh
    /// lavapipe process to its steady speed, which took it 1 to 3 s).
    pub min_ms: f64,
    /// Frames compared to decide that times have settled: the median of
    /// the last `window` frames against the median of the `window` before.
    pub window: usize,
    /// Settled when those two medians differ by at most this fraction of
    /// the later one (or by at most [`WarmUp::ABS_MS`]).
    pub tolerance: f64,
    /// Give up settling after this long (wall-clock ms) and after
    /// [`WarmUp::MAX_FRAMES_FLOOR`] frames; the block is timed anyway and
    /// reported as not settled.
    pub max_ms: f64,
}

impl WarmUp {
    pub const FIRST_BLOCK_FACTOR: f64 = 10.0;
    /// Frame-to-frame differences below this are noise at any clock.
    pub const ABS_MS: f64 = 0.02;
    /// Giving up needs at least this many frames, however slow they are.
    pub const MAX_FRAMES_FLOOR: usize = 12;

    /// The protocol with a minimum warm-up of `min_ms` per block.
    pub fn with_min_ms(min_ms: f64) -> WarmUp {
        WarmUp {
            min_ms,
            window: 3,
            tolerance: 0.10,
            max_ms: (8.0 * min_ms).max(200.0),
        }
    }
}

impl Default for WarmUp {
    fn default() -> WarmUp {
        WarmUp::with_min_ms(DEFAULT_WARM_UP_MS)
    }
}

/// `--warm-up-ms`'s default.
pub const DEFAULT_WARM_UP_MS: f64 = 300.0;

/// Where a block's warm-up stands after a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Settle {
    /// Render another untimed frame.
    More,
    /// Frame times have settled: time the block now.
    Settled,
    /// They did not settle within the limits: time it, and say so.
    GaveUp,
}

/// One block's warm-up: fed each untimed frame's wall-clock and GPU
/// milliseconds, it says when to start timing.
#[derive(Clone, Debug)]
pub struct Settling {
    rule: WarmUp,
    min_ms: f64,
    elapsed_ms: f64,
    totals: Vec<f64>,
}

// ANCHOR: settling
impl Settling {
    /// A block's warm-up; `first` is the run's first block.
    pub fn new(rule: WarmUp, first: bool) -> Settling {
        let factor = if first {
            WarmUp::FIRST_BLOCK_FACTOR
        } else {
            1.0
        };
        Settling {
            rule,
            min_ms: rule.min_ms * factor,
            elapsed_ms: 0.0,
            totals: Vec::new(),
        }
    }

    /// After one untimed frame that took `wall_ms` and whose GPU total was
    /// `total_ms`: keep warming up, or time the block.
    pub fn push(&mut self, wall_ms: f64, total_ms: f64) -> Settle {
        self.elapsed_ms += wall_ms;
        self.totals.push(total_ms);
        let w = self.rule.window.max(1);
        let enough_time = self.elapsed_ms >= self.min_ms;
        if enough_time && self.totals.len() >= 2 * w {
            let n = self.totals.len();
            let before = median(&self.totals[n - 2 * w..n - w]);
            let last = median(&self.totals[n - w..]);
            let gap = (last - before).abs();
            if gap <= self.rule.tolerance * last || gap <= WarmUp::ABS_MS {
                return Settle::Settled;
            }
        }
        let out_of_time = self.elapsed_ms >= self.rule.max_ms.max(self.min_ms);
        if out_of_time && self.totals.len() >= WarmUp::MAX_FRAMES_FLOOR.max(2 * w) {
            return Settle::GaveUp;
        }
        Settle::More
    }

    /// Untimed frames so far.
    pub fn frames(&self) -> usize {
        self.totals.len()
    }

    /// Wall-clock milliseconds of warm-up so far.
    pub fn elapsed_ms(&self) -> f64 {
        self.elapsed_ms
    }
}
// ANCHOR_END: settling

/// A timed block: one variant (`Some(index)`) or the baseline (`None`).
pub type BlockId = Option<usize>;

// ANCHOR: block_order
/// The order of the timed blocks for `n` variants: the baseline before
/// the first variant, between every two and after the last, so that a
/// drift in the GPU's speed shows in the baseline as well as in the
/// variants next to it.
pub fn block_order(n: usize) -> Vec<BlockId> {
    let mut order = vec![None];
    for i in 0..n {
        order.push(Some(i));
        order.push(None);
    }
    order
}
// ANCHOR_END: block_order

/// How far a block's base pass may be from the run's before its times are
/// called unstable: this factor either way (a GPU idling down from 1980 to
/// 345 MHz is 5.7× slower; lavapipe's base pass varies by up to 1.7×
/// between blocks of one run, its rasteriser sharing the CPU)...
pub const BASE_RATIO_LIMIT: f64 = 2.0;
/// ...or this many times the run's own frame-to-frame spread of the base
/// pass within a block (its median interquartile range), whichever is larger.
pub const BASE_TOLERANCE_SPREADS: f64 = 4.0;

/// The verdict on one block's base pass.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BaseCheck {
    /// The block's median base-pass time (ms).
    pub base_ms: f64,
    /// Whether it agrees with the run's reference within the tolerance.
    pub stable: bool,
}

/// The run's reference for the base pass and how far a block may stray.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BaseReference {
    /// The median of the baseline blocks' median base-pass times (ms).
    pub reference_ms: f64,
    /// A block whose median base pass is more than [`BASE_RATIO_LIMIT`]
    /// times off the reference, and further than this from it, is unstable (ms).
    pub tolerance_ms: f64,
}

// ANCHOR: check_base
/// Checks that the base pass, identical work in every block, took the same
/// time in each. `blocks` holds, per block, whether it is a baseline block
/// and its base-pass samples (ms). The reference is the median of the
/// baseline blocks' medians (all blocks' when there is no baseline block);
/// a block is stable when its median is within [`BASE_RATIO_LIMIT`] of it
/// either way, or within the spread-based tolerance.
pub fn check_base(blocks: &[(bool, Vec<f64>)]) -> (BaseReference, Vec<BaseCheck>) {
    let medians: Vec<f64> = blocks.iter().map(|(_, s)| median(s)).collect();
    let baseline: Vec<f64> = blocks
        .iter()
        .zip(&medians)
        .filter(|((is_base, _), m)| *is_base && m.is_finite())
        .map(|(_, &m)| m)
        .collect();
    let all: Vec<f64> = medians.iter().copied().filter(|m| m.is_finite()).collect();
    let reference_ms = median(if baseline.is_empty() { &all } else { &baseline });
    let spreads: Vec<f64> = blocks
        .iter()
        .filter(|(_, s)| s.len() >= 2)
        .map(|(_, s)| quantile(s, 0.75) - quantile(s, 0.25))
        .collect();
    let spread = if spreads.is_empty() {
        0.0
    } else {
        median(&spreads)
    };
    let tolerance_ms = (BASE_TOLERANCE_SPREADS * spread).max(WarmUp::ABS_MS);
    let agrees = |m: f64| {
        let ratio = (m / reference_ms).max(reference_ms / m);
        ratio <= BASE_RATIO_LIMIT || (m - reference_ms).abs() <= tolerance_ms
    };
    let checks = medians
        .iter()
        .map(|&m| BaseCheck {
            base_ms: m,
            stable: m.is_finite() && agrees(m),
        })
        .collect();
    let reference = BaseReference {
        reference_ms,
        tolerance_ms,
    };
    (reference, checks)
}
// ANCHOR_END: check_base

/// One timed block as it ran.
#[derive(Clone, Debug)]
pub struct TimedBlock {
    pub id: BlockId,
    /// Untimed frames and their wall-clock milliseconds before timing.
    pub warm_up_frames: usize,
    pub warm_up_ms: f64,
    /// Whether the frame times settled (else the warm-up gave up).
    pub settled: bool,
    pub frames: Vec<FrameTimes>,
}

// ANCHOR: time_blocks
/// Renders the blocks of `order` back to back: each warmed up until it
/// settles, then `frames` timed frames. `render` records one frame of a
/// block. Nothing else runs between the blocks, so the GPU stays busy.
pub fn time_blocks(
    timer: &mut Timer,
    gpu: &Gpu,
    rule: WarmUp,
    frames: u32,
    order: &[BlockId],
    mut render: impl FnMut(&mut Frame, BlockId) -> Result<()>,
) -> Result<Vec<TimedBlock>> {
    let mut blocks = Vec::with_capacity(order.len());
    for (i, &id) in order.iter().enumerate() {
        let mut warm_up = Settling::new(rule, i == 0);
        // `--warm-up-ms 0`, for runs whose times nobody reads (the tests,
        // the grader): one untimed frame, no settling, reported not
        // settled. Not none: lessons 05-08 count a variant's costs on its
        // second frame against the depth its first left (`count_costs`),
        // so a block's first two frames must be its own, back to back.
        let settled = loop {
            let mut frame = timer.frame(gpu);
            render(&mut frame, id)?;
            let t = frame.finish()?;
            let (wall, total) = (t.ms[FRAME], t.ms[TOTAL]);
            let settle = warm_up.push(wall, total);
            if rule.min_ms <= 0.0 {
                break false;
            }
            match settle {
                Settle::More => continue,
                Settle::Settled => break true,
                Settle::GaveUp => break false,
            }
        };
        let mut times = Vec::with_capacity(frames as usize);
        for _ in 0..frames {
            let mut frame = timer.frame(gpu);
            render(&mut frame, id)?;
            times.push(frame.finish()?);
        }
        blocks.push(TimedBlock {
            id,
            warm_up_frames: warm_up.frames(),
            warm_up_ms: warm_up.elapsed_ms(),
            settled,
            frames: times,
        });
    }
    Ok(blocks)
}
// ANCHOR_END: time_blocks

/// What the report keeps of the blocks: each variant's frames and check,
/// the baseline's frames (those of its stable blocks, or of all when none
/// is) and every baseline block's check, and the verdict.
pub struct Verdicts {
    pub variants: Vec<(Vec<FrameTimes>, TimingCheck)>,
    pub baseline: (Vec<FrameTimes>, Vec<TimingCheck>),
    pub protocol: TimingProtocolReport,
}

/// The base pass's name in every lesson and in the baseline.
pub const BASE_PASS: &str = "base";

/// Checks the blocks' base passes and sorts the blocks into variants
/// (named `names`, by [`BlockId`]) and the baseline.
pub fn verdicts(blocks: &[TimedBlock], names: &[String], warm_up_min_ms: f64) -> Verdicts {
    let base = |b: &TimedBlock| -> Vec<f64> {
        b.frames
            .iter()
            .filter_map(|f| f.ms.get(BASE_PASS).copied())
            .collect()
    };
    let input: Vec<(bool, Vec<f64>)> = blocks.iter().map(|b| (b.id.is_none(), base(b))).collect();
    let (reference, checks) = check_base(&input);
    let check = |b: &TimedBlock, c: &BaseCheck| TimingCheck {
        warm_up_frames: b.warm_up_frames as u32,
        warm_up_ms: b.warm_up_ms,
        settled: b.settled,
        base_ms: c.base_ms.is_finite().then_some(c.base_ms),
        stable: c.stable,
    };
    let mut variants: Vec<(Vec<FrameTimes>, Option<TimingCheck>)> =
        names.iter().map(|_| (Vec::new(), None)).collect();
    let mut baseline = (Vec::new(), Vec::new());
    let any_stable_baseline = blocks
        .iter()
        .zip(&checks)
        .any(|(b, c)| b.id.is_none() && c.stable);
    for (b, c) in blocks.iter().zip(&checks) {
        match b.id {
            Some(i) if i < variants.len() => {
                variants[i].0.extend(b.frames.iter().cloned());
                variants[i].1 = Some(check(b, c));
            }
            Some(_) => {}
            None => {
                // An unstable baseline block is left out of the baseline's
                // frames when another one is stable: the baseline is timed
                // many times so that one slow block does not sink it.
                if c.stable || !any_stable_baseline {
                    baseline.0.extend(b.frames.iter().cloned());
                }
                baseline.1.push(check(b, c));
            }
        }
    }
    let order = blocks
        .iter()
        .map(|b| match b.id {
            Some(i) => names.get(i).cloned().unwrap_or_default(),
            None => "baseline".to_string(),
        })
        .collect();
    let protocol = TimingProtocolReport {
        warm_up_min_ms,
        order,
        base_reference_ms: reference
            .reference_ms
            .is_finite()
            .then_some(reference.reference_ms),
        base_ratio_limit: BASE_RATIO_LIMIT,
        base_tolerance_ms: reference.tolerance_ms,
        stable: checks.iter().all(|c| c.stable),
    };
    let unchecked = TimingCheck {
        warm_up_frames: 0,
        warm_up_ms: 0.0,
        settled: false,
        base_ms: None,
        stable: false,
    };
    Verdicts {
        variants: variants
            .into_iter()
            .map(|(f, c)| (f, c.unwrap_or_else(|| unchecked.clone())))
            .collect(),
        baseline,
        protocol,
    }
}

/// The median of `v` (NaN when empty).
pub fn median(v: &[f64]) -> f64 {
    quantile(v, 0.5)
}

#[cfg(test)]
#[path = "unit_tests/protocol.rs"]
mod tests;
