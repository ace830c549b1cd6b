//! Measuring a frame's cost and reporting it.
//!
//! - [`timing`]: GPU timestamp queries per pass, with a labelled CPU fallback;
//!   a frame's GPU, CPU and wall-clock milliseconds.
//! - [`timing_later`]: the timestamps read back frames later, without
//!   waiting (the web page's GPU times).
//! - [`protocol`]: the timing protocol: warm up until frame times settle,
//!   time the variants interleaved with the no-shadow baseline, and tell a
//!   stable measurement from one whose GPU clock moved.
//! - [`counters`]: every counter a lesson reports (name, unit, legend),
//!   and [`counters::Counts`], what a lesson counted.
//! - [`fragment_counter`]: fragments rasterised, counted by the GPU's
//!   pipeline statistics.
//! - [`baseline`]: the no-shadow baseline frame every lesson is timed against.
//! - [`report`]: `report.json` and the terminal table.

pub mod baseline;
pub mod counters;
pub mod fragment_counter;
pub mod protocol;
pub mod report;
pub mod timing;
pub mod timing_later;
