//! The GPU watchdog: a frame the GPU does not finish in time ends the run
//! with one line and exit code [`EXIT_CODE`], instead of a hang.
//!
//! A shader loop that never ends (an exercise's WGSL, say) keeps the GPU
//! busy for ever where the driver does not cut it short. lavapipe does,
//! after 65535 iterations of all its loops in an invocation (Mesa's
//! `LP_MAX_TGSI_LOOP_ITERATIONS`), so there the frame is only slow:
//! seconds where an honest one takes milliseconds.
//! Every wait of the lessons for the GPU goes through
//! [`crate::gpu::Gpu::wait`], which waits here at most [`limit`]
//! (`WORKBOOK_GPU_TIMEOUT_S`, default [`DEFAULT_S`] s).

use std::sync::OnceLock;
use std::time::Duration;

use anyhow::{anyhow, Result};

/// The variable that sets the limit, in seconds.
pub const ENV: &str = "WORKBOOK_GPU_TIMEOUT_S";

/// The default limit: far above any honest frame of the workbook on a
/// software rasteriser (a few seconds at most).
pub const DEFAULT_S: f64 = 120.0;

/// The exit code of a run the watchdog ended (1 is a lesson's own error,
/// 2 a bad command line, 3 a wgpu validation error).
pub const EXIT_CODE: i32 = 4;

/// How long one wait for the GPU may take: `WORKBOOK_GPU_TIMEOUT_S`, else
/// [`DEFAULT_S`]. A value that is not a number of seconds above 0 is an
/// error naming the variable.
pub fn limit() -> Result<Duration> {
    static LIMIT: OnceLock<Result<Duration, String>> = OnceLock::new();
    LIMIT
        .get_or_init(|| parse(std::env::var(ENV).ok().as_deref()))
        .clone()
        .map_err(|e| anyhow!(e))
}

fn parse(value: Option<&str>) -> Result<Duration, String> {
    let Some(v) = value.filter(|v| !v.trim().is_empty()) else {
        return Ok(Duration::from_secs_f64(DEFAULT_S));
    };
    match v.trim().parse::<f64>() {
        Ok(s) if s > 0.0 && s.is_finite() && s < 1e9 => Ok(Duration::from_secs_f64(s)),
        _ => Err(format!(
            "{ENV} = {v:?}: give the seconds a GPU frame may take, a number above 0 (default {DEFAULT_S})"
        )),
    }
}

/// Waits for everything submitted to `device`, at most [`limit`]; past
/// it, ends the process ([`did_not_finish`]).
pub fn wait(device: &wgpu::Device) -> Result<()> {
    let limit = limit()?;
    let poll = wgpu::PollType::Wait {
        submission_index: None,
        timeout: Some(limit),
    };
    match device.poll(poll) {
        Ok(_) => Ok(()),
        Err(wgpu::PollError::Timeout) => did_not_finish(limit),
        Err(e) => Err(anyhow!("GPU wait failed: {e}")),
    }
}

/// Prints the one line and exits with [`EXIT_CODE`] at once.
pub fn did_not_finish(limit: Duration) -> ! {
    let lesson = std::env::current_exe()
        .ok()
        .and_then(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "lesson".into());
    eprintln!(
        "error: {lesson}: the GPU did not finish a frame within {} s (a shader loop that \
         never ends? {ENV} sets the limit)",
        limit.as_secs_f64()
    );
    exit_now(EXIT_CODE)
}

/// Exits without running the exit handlers: a driver's may wait for a
/// device that never goes idle; the kernel frees the GPU's work instead.
fn exit_now(code: i32) -> ! {
    use std::io::Write;
    let _ = std::io::stdout().flush();
    #[cfg(target_os = "linux")]
    // SAFETY: `_exit` ends the process; nothing after it runs.
    unsafe {
        libc::_exit(code)
    }
    #[cfg(not(target_os = "linux"))]
    std::process::exit(code)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limit_is_a_number_of_seconds_above_zero() {
        assert_eq!(parse(None), Ok(Duration::from_secs(120)));
        assert_eq!(parse(Some(" ")), Ok(Duration::from_secs(120)));
        assert_eq!(parse(Some("2.5")), Ok(Duration::from_millis(2500)));
        for bad in ["0", "-3", "ten", "inf", "NaN"] {
            let e = parse(Some(bad)).unwrap_err();
            assert!(e.starts_with(ENV), "{bad}: {e}");
        }
    }
}
