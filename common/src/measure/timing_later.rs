//! Pass timestamps read back frames later, without waiting: how a web page
//! times its GPU (a page may not wait for it). Each frame resolves its
//! timestamps into one of a ring of buffers and asks for its mapping; a
//! later frame reads every buffer that came back and keeps the newest
//! frame's times. While every buffer is on its way back, a frame goes
//! untimed rather than wait.
//!
//! The browser may round what it reports: Chromium quantizes timestamps
//! unless its WebGPU developer features are on. [`LateTimes::quantum_ns`]
//! is the largest step every stamp read so far is a multiple of, which the
//! overlay shows beside the times.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

use anyhow::{anyhow, Result};

use crate::gpu::readback::QueryReadback;
use crate::gpu::Gpu;

/// How many frames' timestamps may be on their way back at once.
pub const RING: usize = 4;

/// The GPU's times of an earlier frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LateTimes {
    /// Each pass's milliseconds, and `total`.
    pub ms: BTreeMap<String, f64>,
    /// The frame they are of (the timer's count, from 1).
    pub frame: u64,
    /// How many frames later they were read.
    pub frames_late: u64,
    /// The largest step, in nanoseconds, that every stamp read so far is
    /// a multiple of: 1 where the adapter does not round them.
    pub quantum_ns: u64,
}

type MapState = Arc<Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>;

struct Slot {
    readback: QueryReadback,
    names: Vec<String>,
    frame: u64,
    /// `Some` while the slot's stamps are on their way back.
    state: Option<MapState>,
}

/// The ring of readbacks, and what came back.
pub struct Later {
    slots: Vec<Slot>,
    frame: u64,
    latest: Option<LateTimes>,
    quantum_ns: u64,
}

impl Later {
    pub fn new(gpu: &Gpu, max_queries: u32) -> Later {
        let slots = (0..RING)
            .map(|_| Slot {
                readback: QueryReadback::new(gpu, max_queries, "timestamps (read later)"),
                names: Vec::new(),
                frame: 0,
                state: None,
            })
            .collect();
        Later {
            slots,
            frame: 0,
            latest: None,
            quantum_ns: 0,
        }
    }

    /// Records the resolve of this frame's stamps (two per name) into a
    /// free slot, or `None` when every slot is still on its way back.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        set: &wgpu::QuerySet,
        names: &[String],
    ) -> Option<usize> {
        self.frame += 1;
        let i = self.slots.iter().position(|s| s.state.is_none())?;
        let slot = &mut self.slots[i];
        slot.readback.resolve(encoder, set, 2 * names.len() as u32);
        slot.names = names.to_vec();
        slot.frame = self.frame;
        Some(i)
    }

    /// After the frame with slot `i` was submitted: asks for its mapping.
    pub fn submitted(&mut self, i: usize) {
        let slot = &mut self.slots[i];
        let state: MapState = Default::default();
        let done = state.clone();
        let n = 2 * slot.names.len() as u32;
        slot.readback.map(n, move |r| {
            *done.lock().expect("timestamp state") = Some(r);
        });
        slot.state = Some(state);
    }

    /// How many frames recorded their stamps so far.
    pub fn frames(&self) -> u64 {
        self.frame
    }

    /// The newest frame's times read back so far.
    pub fn latest(&self) -> Option<&LateTimes> {
        self.latest.as_ref()
    }

    /// Reads every slot that came back, and returns the newest frame's
    /// times read so far (`period_ns`: nanoseconds per tick).
    pub fn collect(&mut self, gpu: &Gpu, period_ns: f64) -> Result<Option<&LateTimes>> {
        // The desktop maps a buffer when the device is polled; a page's
        // browser maps it by itself.
        #[cfg(not(target_arch = "wasm32"))]
        gpu.device
            .poll(wgpu::PollType::Poll)
            .map_err(|e| anyhow!("GPU poll failed: {e}"))?;
        #[cfg(target_arch = "wasm32")]
        let _ = gpu;
        for slot in &mut self.slots {
            let done = match &slot.state {
                Some(state) => state.lock().expect("timestamp state").take(),
                None => continue,
            };
            let Some(done) = done else { continue };
            slot.state = None;
            done.map_err(|e| anyhow!("timestamps: {e}"))?;
            let n = 2 * slot.names.len() as u32;
            let stamps = slot.readback.take_mapped(n)?;
            for &s in &stamps {
                self.quantum_ns = gcd(self.quantum_ns, (s as f64 * period_ns).round() as u64);
            }
            if self.latest.as_ref().is_some_and(|l| l.frame > slot.frame) {
                continue;
            }
            self.latest = Some(LateTimes {
                ms: pass_times(&slot.names, &stamps, period_ns),
                frame: slot.frame,
                frames_late: self.frame - slot.frame,
                quantum_ns: self.quantum_ns.max(1),
            });
        }
        Ok(self.latest.as_ref())
    }
}

/// Each pass's milliseconds from its two stamps (`names[i]`'s at `2i` and
/// `2i + 1`; a name used twice adds up), and `total`, first stamp to last.
pub fn pass_times(names: &[String], stamps: &[u64], period_ns: f64) -> BTreeMap<String, f64> {
    let to_ms = period_ns / 1e6;
    let (mut first, mut last) = (u64::MAX, 0u64);
    let mut ms: BTreeMap<String, f64> = BTreeMap::new();
    for (i, name) in names.iter().enumerate() {
        let (a, b) = (stamps[2 * i], stamps[2 * i + 1]);
        first = first.min(a);
        last = last.max(b);
        *ms.entry(name.clone()).or_default() += b.saturating_sub(a) as f64 * to_ms;
    }
    // `timing::TOTAL` (this module may not import `timing`, which imports it).
    ms.insert("total".into(), last.saturating_sub(first) as f64 * to_ms);
    ms
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::gcd;

    #[test]
    fn the_quantum_is_the_step_every_stamp_is_a_multiple_of() {
        let q = [300_000u64, 1_200_000, 900_000].into_iter().fold(0, gcd);
        assert_eq!(q, 300_000);
        assert_eq!([656_123u64, 1_000_000].into_iter().fold(0, gcd), 1);
    }
}
