//! Timing a frame pass by pass.
//!
//! With `TIMESTAMP_QUERY`, every pass writes a GPU timestamp at its start and
//! end; the report quotes GPU milliseconds. Without it (llvmpipe over GL, for
//! one), each pass is submitted on its own and timed by the CPU wall clock
//! around submit-and-wait: slower and noisier, and labelled `cpu_wall`.
//!
//! Beside the passes, every frame reports two more keys:
//! - `cpu_total`: the CPU's time on the frame until it is submitted
//!   (recording, uploads, the lesson's own CPU work such as silhouettes or
//!   bounds), waits on the GPU left out, and measurement work
//!   ([`Frame::untimed`]: counters, readbacks) left out too. The lesson's
//!   own CPU work is named (`cpu_<name>`, [`Frame::cpu`]), and so is
//!   recording the passes (`cpu_record`: the closures given to
//!   [`Frame::pass`], and finishing the command buffer); what no name
//!   covers ([`unnamed_cpu_ms`]) is the glue between them: uploads outside
//!   a pass, and the lesson's bookkeeping;
//! - `frame`: the wall-clock time from the start of the frame to the GPU
//!   finishing it, the frame cost a user sees when each frame is waited for
//!   (as here). It is at least `cpu_total`, and at least the GPU's `total`.

use std::collections::BTreeMap;
// std on the desktop; the browser's clock in the web build (std's panics there).
use web_time::Instant;

use anyhow::Result;

use crate::gpu::readback::QueryReadback;
use crate::gpu::Gpu;
use crate::measure::timing_later::{pass_times, LateTimes, Later};

/// Where the milliseconds came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TimingSource {
    GpuTimestamps,
    CpuWall,
}

const MAX_QUERIES: u32 = 512;

/// How the timestamps come back: waited for at the end of the frame, or
/// frames later ([`Later`]: a web page).
enum Stamps {
    Wait(QueryReadback),
    Later(Later),
}

/// Owns the query set and its readback buffers; reused frame after frame.
pub struct Timer {
    queries: Option<(wgpu::QuerySet, Stamps)>,
    period_ns: f64,
    /// Without timestamps, time each pass by the CPU wall clock (it waits
    /// for the GPU); a timer that may not wait times no pass.
    wall: bool,
}

impl Timer {
    /// GPU timestamps when the adapter has them, waited for at the end of
    /// each frame; in a web page, [`Timer::later`]. `WORKBOOK_TIMING=cpu`
    /// forces the CPU wall-clock fallback (to compare the two, and to test
    /// it).
    pub fn new(gpu: &Gpu) -> Timer {
        if cfg!(target_arch = "wasm32") {
            return Timer::later(gpu);
        }
        let forced_cpu = std::env::var("WORKBOOK_TIMING").is_ok_and(|v| v == "cpu");
        let queries = (gpu.has(wgpu::Features::TIMESTAMP_QUERY) && !forced_cpu).then(|| {
            let set = query_set(gpu);
            (
                set,
                Stamps::Wait(QueryReadback::new(gpu, MAX_QUERIES, "timestamps")),
            )
        });
        Timer {
            queries,
            period_ns: gpu.queue.get_timestamp_period() as f64,
            wall: true,
        }
    }

    /// A timer that never waits (a web page's): timestamps read back frames
    /// later ([`Timer::late`]) where the adapter has them, else no GPU time.
    pub fn later(gpu: &Gpu) -> Timer {
        let queries = (gpu.has(wgpu::Features::TIMESTAMP_QUERY))
            .then(|| (query_set(gpu), Stamps::Later(Later::new(gpu, MAX_QUERIES))));
        Timer {
            queries,
            period_ns: gpu.queue.get_timestamp_period() as f64,
            wall: false,
        }
    }

    /// Where the milliseconds come from (no report uses a [`Timer::later`]).
    pub fn source(&self) -> TimingSource {
        if self.queries.is_some() {
            TimingSource::GpuTimestamps
        } else {
            TimingSource::CpuWall
        }
    }

    /// Whether this timer gives GPU times.
    pub fn times_gpu(&self) -> bool {
        self.queries.is_some() || self.wall
    }

    /// A [`Timer::later`]'s newest GPU times read back so far.
    pub fn late(&self) -> Option<&LateTimes> {
        match &self.queries {
            Some((_, Stamps::Later(l))) => l.latest(),
            _ => None,
        }
    }

    /// How many frames a [`Timer::later`] has timed (0 for one that waits).
    pub fn frames(&self) -> u64 {
        match &self.queries {
            Some((_, Stamps::Later(l))) => l.frames(),
            _ => 0,
        }
    }

    /// Starts recording a frame.
    pub fn frame<'a>(&'a mut self, gpu: &'a Gpu) -> Frame<'a> {
        Frame {
            encoder: new_encoder(gpu),
            gpu,
            timer: self,
            names: Vec::new(),
            wall: Vec::new(),
            cpu: Vec::new(),
            start: Instant::now(),
            waited_ms: 0.0,
            untimed_ms: 0.0,
            record_ms: 0.0,
        }
    }
}

fn query_set(gpu: &Gpu) -> wgpu::QuerySet {
    gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
        label: Some("pass timestamps"),
        ty: wgpu::QueryType::Timestamp,
        count: MAX_QUERIES,
    })
}

fn new_encoder(gpu: &Gpu) -> wgpu::CommandEncoder {
    gpu.device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("frame"),
        })
}

/// The timestamp slots of one pass; hand them to the pass descriptor.
pub struct PassTimestamps<'q> {
    slot: Option<(&'q wgpu::QuerySet, u32)>,
}

impl<'q> PassTimestamps<'q> {
    pub fn render(&self) -> Option<wgpu::RenderPassTimestampWrites<'q>> {
        self.slot
            .map(|(query_set, i)| wgpu::RenderPassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: Some(i),
                end_of_pass_write_index: Some(i + 1),
            })
    }

    pub fn compute(&self) -> Option<wgpu::ComputePassTimestampWrites<'q>> {
        self.slot
            .map(|(query_set, i)| wgpu::ComputePassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: Some(i),
                end_of_pass_write_index: Some(i + 1),
            })
    }
}

/// One frame being recorded. Passes are named; a name used twice (one
/// "lighting" pass per light) adds up.
pub struct Frame<'a> {
    pub gpu: &'a Gpu,
    encoder: wgpu::CommandEncoder,
    timer: &'a mut Timer,
    names: Vec<String>,
    wall: Vec<(String, f64)>,
    cpu: Vec<(String, f64)>,
    /// When recording began, and the time spent waiting on the GPU since.
    start: Instant,
    waited_ms: f64,
    /// The time spent in [`Frame::untimed`] (also in `waited_ms`).
    untimed_ms: f64,
    /// The CPU time spent recording passes ([`RECORD`]).
    record_ms: f64,
}

/// The key of a frame's CPU time until submission.
pub const CPU_TOTAL: &str = "cpu_total";
/// The key of the CPU time spent recording a frame's passes: inside the
/// closures given to [`Frame::pass`], and finishing the command buffer.
pub const RECORD: &str = "cpu_record";
/// The key of a frame's wall-clock cost, start to GPU completion.
pub const FRAME: &str = "frame";
/// The key of the GPU's time for the whole frame.
pub const TOTAL: &str = "total";

/// Milliseconds of one frame: `total` (GPU), `frame` (wall clock),
/// `cpu_total`, and one entry per pass name.
#[derive(Clone, Debug, Default)]
pub struct FrameTimes {
    pub ms: BTreeMap<String, f64>,
}

impl<'a> Frame<'a> {
    /// Records one pass. `f` gets the encoder and the pass's timestamp slots.
    pub fn pass<R>(
        &mut self,
        name: &str,
        f: impl FnOnce(&mut wgpu::CommandEncoder, &PassTimestamps) -> R,
    ) -> R {
        match &self.timer.queries {
            Some((set, _)) if (self.names.len() as u32 + 1) * 2 <= MAX_QUERIES => {
                let ts = PassTimestamps {
                    slot: Some((set, self.names.len() as u32 * 2)),
                };
                self.names.push(name.to_string());
                let t = Instant::now();
                let r = f(&mut self.encoder, &ts);
                self.record_ms += t.elapsed().as_secs_f64() * 1e3;
                r
            }
            Some(_) => {
                let t = Instant::now();
                let r = f(&mut self.encoder, &PassTimestamps { slot: None });
                self.record_ms += t.elapsed().as_secs_f64() * 1e3;
                r
            }
            None if !self.timer.wall => {
                let t = Instant::now();
                let r = f(&mut self.encoder, &PassTimestamps { slot: None });
                self.record_ms += t.elapsed().as_secs_f64() * 1e3;
                r
            }
            None => {
                // CPU wall clock: submit what came before, then time this pass
                // alone. These submits and waits are the measurement's, not
                // the frame's: out of `cpu_total`, as waits are.
                self.submit_and_wait();
                let t = Instant::now();
                let r = f(&mut self.encoder, &PassTimestamps { slot: None });
                self.record_ms += t.elapsed().as_secs_f64() * 1e3;
                self.submit_and_wait();
                self.wall
                    .push((name.to_string(), t.elapsed().as_secs_f64() * 1e3));
                r
            }
        }
    }

    /// Times CPU-side work (silhouette extraction, ...) as `cpu_<name>`.
    pub fn cpu<R>(&mut self, name: &str, f: impl FnOnce() -> R) -> R {
        let t = Instant::now();
        let r = f();
        self.cpu
            .push((format!("cpu_{name}"), t.elapsed().as_secs_f64() * 1e3));
        r
    }

    /// Measurement work inside a frame (counting a variant's costs, reading
    /// back a count), in submits of its own: left out of the frame's
    /// times. What it takes, CPU and waits, is counted out of both
    /// `cpu_total` and `frame`, so a frame that counts is timed like one
    /// that does not.
    pub fn untimed<R>(&mut self, f: impl FnOnce(&Gpu) -> R) -> R {
        let t = Instant::now();
        let r = f(self.gpu);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        self.waited_ms += ms;
        self.untimed_ms += ms;
        r
    }

    /// Submits what is recorded and waits for the GPU, both counted out
    /// of the frame's CPU time (the wall-clock path's measurement).
    fn submit_and_wait(&mut self) {
        let t = Instant::now();
        let done = std::mem::replace(&mut self.encoder, new_encoder(self.gpu));
        self.gpu.queue.submit([done.finish()]);
        let _ = self.gpu.wait();
        self.waited_ms += t.elapsed().as_secs_f64() * 1e3;
    }

    /// Before a compute pass that reads what a render pass of this frame
    /// drew (lesson 10's variance map and min/max chain read the shadow
    /// map). WebGPU orders the two and every backend's barrier holds on
    /// Vulkan, Metal and D3D12; on GL, Mesa's llvmpipe (22.3) can start
    /// the dispatch while the render pass's last tiles are still being
    /// rasterised, so the compute pass reads part of the map the frame
    /// before drew (`vsm_bleed_cut` after `vsm`'s moved frames: 7 runs in
    /// 16 read a stale map with four runs side by side; a submit alone
    /// did not help, a wait did, 20 in 20). So on GL, and only there,
    /// the frame submits what it has recorded and waits, a wait counted
    /// out of the frame's CPU time as the wall-clock path's are.
    pub fn render_output_ready_for_compute(&mut self) {
        if self.gpu.info.backend == wgpu::Backend::Gl {
            self.submit_and_wait();
        }
    }

    /// Direct access for copies outside any timed pass.
    pub fn encoder(&mut self) -> &mut wgpu::CommandEncoder {
        &mut self.encoder
    }

    /// Submits, waits, and returns the frame's milliseconds. A
    /// [`Timer::later`] waits for nothing: its GPU times are the newest
    /// earlier frame's that came back ([`Timer::late`]).
    pub fn finish(mut self) -> Result<FrameTimes> {
        let n = self.names.len() as u32 * 2;
        let t = Instant::now();
        let mut later_slot = None;
        match (&mut self.timer.queries, n > 0) {
            (Some((set, Stamps::Wait(readback))), true) => {
                readback.resolve(&mut self.encoder, set, n)
            }
            (Some((set, Stamps::Later(later))), true) => {
                later_slot = later.record(&mut self.encoder, set, &self.names);
            }
            _ => {}
        }
        let command_buffer = self.encoder.finish();
        self.record_ms += t.elapsed().as_secs_f64() * 1e3;
        let cpu_total = self.start.elapsed().as_secs_f64() * 1e3 - self.waited_ms;
        self.gpu.queue.submit([command_buffer]);
        if let (Some((_, Stamps::Later(later))), Some(i)) = (&mut self.timer.queries, later_slot) {
            later.submitted(i);
        }
        self.gpu.wait()?;
        let wall = self.start.elapsed().as_secs_f64() * 1e3 - self.untimed_ms;
        let mut ms: BTreeMap<String, f64> = BTreeMap::new();
        ms.insert(CPU_TOTAL.into(), cpu_total);
        ms.insert(FRAME.into(), wall);
        ms.insert(RECORD.into(), self.record_ms);
        for (k, v) in self.cpu {
            *ms.entry(k).or_default() += v;
        }
        let period_ns = self.timer.period_ns;
        match (&mut self.timer.queries, n > 0) {
            (Some((_, Stamps::Wait(readback))), true) => {
                let stamps = readback.read(self.gpu, n)?;
                ms.extend(pass_times(&self.names, &stamps, period_ns));
            }
            (Some((_, Stamps::Later(later))), _) => {
                if let Some(late) = later.collect(self.gpu, period_ns)? {
                    ms.extend(late.ms.clone());
                }
            }
            // No pass timed (none recorded, or the wall clock's passes).
            _ => {
                let mut total = 0.0;
                for (k, v) in self.wall {
                    total += v;
                    *ms.entry(k).or_default() += v;
                }
                if self.timer.wall {
                    ms.insert(TOTAL.into(), total);
                }
            }
        }
        Ok(FrameTimes { ms })
    }
}

/// The CPU time of a frame (or of a report's medians) that no `cpu_*`
/// pass names: `cpu_total` minus the named CPU passes, recording
/// ([`RECORD`]) among them. Uploads outside a pass and the lesson's
/// bookkeeping between passes, and nothing a lesson computes per frame.
pub fn unnamed_cpu_ms(ms: &BTreeMap<String, f64>) -> f64 {
    let named: f64 = (ms.iter())
        .filter(|(k, _)| k.starts_with("cpu_") && k.as_str() != CPU_TOTAL)
        .map(|(_, v)| v)
        .sum();
    ms.get(CPU_TOTAL).copied().unwrap_or(0.0) - named
}

/// Every frame's milliseconds, key by key (a pass a frame skipped is 0).
pub fn samples(frames: &[FrameTimes]) -> BTreeMap<String, Vec<f64>> {
    let mut keys: Vec<&String> = frames.iter().flat_map(|f| f.ms.keys()).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .map(|k| {
            let v = frames
                .iter()
                .map(|f| f.ms.get(k).copied().unwrap_or(0.0))
                .collect();
            (k.clone(), v)
        })
        .collect()
}

/// The `q`-quantile (0 to 1) of `v`, interpolated linearly between the
/// sorted samples (the median is `quantile(v, 0.5)`). NaN for no samples.
pub fn quantile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.total_cmp(b));
    let x = q.clamp(0.0, 1.0) * (s.len() - 1) as f64;
    let (i, f) = (x.floor() as usize, x.fract());
    let j = (i + 1).min(s.len() - 1);
    s[i] + f * (s[j] - s[i])
}

// ANCHOR: timing_protocol
/// The median of each key over several frames (the report's figure).
pub fn median_times(frames: &[FrameTimes]) -> BTreeMap<String, f64> {
    samples(frames)
        .into_iter()
        .map(|(k, v)| (k, quantile(&v, 0.5)))
        .collect()
}

/// The spread of each key: its interquartile range `[q25, q75]`.
pub fn spread_times(frames: &[FrameTimes]) -> BTreeMap<String, [f64; 2]> {
    samples(frames)
        .into_iter()
        .map(|(k, v)| (k, [quantile(&v, 0.25), quantile(&v, 0.75)]))
        .collect()
}
// ANCHOR_END: timing_protocol

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        let f = |t: f64| FrameTimes {
            ms: [("total".to_string(), t)].into_iter().collect(),
        };
        assert_eq!(median_times(&[f(3.0), f(1.0), f(2.0)])["total"], 2.0);
        assert_eq!(
            median_times(&[f(4.0), f(1.0), f(2.0), f(3.0)])["total"],
            2.5
        );
    }

    #[test]
    fn unnamed_cpu_is_cpu_total_less_the_named_cpu_passes() {
        let ms: BTreeMap<String, f64> = [
            (CPU_TOTAL, 1.5),
            ("cpu_silhouette", 0.75),
            ("cpu_bounds", 0.5),
            (TOTAL, 9.0),
            (FRAME, 11.0),
            ("volume", 3.0),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        assert_eq!(unnamed_cpu_ms(&ms), 0.25);
        assert_eq!(unnamed_cpu_ms(&BTreeMap::new()), 0.0);
    }

    #[test]
    fn spread_is_the_interquartile_range() {
        let f = |t: f64| FrameTimes {
            ms: [("total".to_string(), t)].into_iter().collect(),
        };
        let frames: Vec<FrameTimes> = [5.0, 1.0, 3.0, 2.0, 4.0].map(f).into();
        assert_eq!(spread_times(&frames)["total"], [2.0, 4.0]);
        assert_eq!(samples(&frames)["total"], vec![5.0, 1.0, 3.0, 2.0, 4.0]);
        assert_eq!(quantile(&[1.0, 2.0], 0.25), 1.25);
        assert!(quantile(&[], 0.5).is_nan());
    }
}
