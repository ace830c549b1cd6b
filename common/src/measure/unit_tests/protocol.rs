//! The protocol on synthetic time series.

use super::*;

/// Feeds frames of `wall_ms` each with the given GPU totals until the
/// warm-up stops; returns the verdict and the frames it took.
fn warm(rule: WarmUp, first: bool, wall_ms: f64, totals: &[f64]) -> (Settle, usize) {
    let mut s = Settling::new(rule, first);
    for &t in totals {
        match s.push(wall_ms, t) {
            Settle::More => continue,
            verdict => return (verdict, s.frames()),
        }
    }
    (Settle::More, s.frames())
}

#[test]
fn steady_frames_settle_once_the_minimum_time_has_passed() {
    let rule = WarmUp::with_min_ms(100.0);
    // 10 ms frames: 100 ms is 10 frames; the frame times never move.
    let (v, n) = warm(rule, false, 10.0, &[1.0; 50]);
    assert_eq!((v, n), (Settle::Settled, 10));
    // The first block of a run warms up ten times as long.
    let (v, n) = warm(rule, true, 10.0, &[1.0; 500]);
    assert_eq!((v, n), (Settle::Settled, 100));
}

#[test]
fn a_clock_coming_back_up_is_not_settled_until_it_is_flat() {
    // The H100's GPU clock coming back from 345 to 1980 MHz: the same work
    // takes 4.655 ms, then falls step by step to 0.788 ms over 20 frames.
    let mut totals: Vec<f64> = (0..20)
        .map(|i| 4.655 - (4.655 - 0.788) * i as f64 / 19.0)
        .collect();
    totals.extend([0.788; 30]);
    let rule = WarmUp::with_min_ms(0.0);
    let (v, n) = warm(rule, false, 1.0, &totals);
    assert_eq!(v, Settle::Settled);
    // Settled only once the last window is on the flat part and the one
    // before it is within the tolerance of it.
    let w = rule.window;
    assert!(n >= 20 + w, "settled after {n} frames");
    assert!(median(&totals[n - 2 * w..n - w]) <= 0.788 * 1.1);
    // A fixed two warm-up frames (the old protocol) would have timed 4.25 ms.
    assert!(totals[2] > 4.0);
}

#[test]
fn noise_within_the_tolerance_settles_and_a_trend_beyond_it_does_not() {
    let rule = WarmUp::with_min_ms(0.0);
    let noisy = [2.0, 2.1, 1.95, 2.05, 2.0, 2.1, 1.9];
    assert_eq!(warm(rule, false, 2.0, &noisy).0, Settle::Settled);
    // +20 % per window: never settles, and gives up after max_ms (200 ms)
    // and at least MAX_FRAMES_FLOOR frames.
    let trend: Vec<f64> = (0..500).map(|i| 1.0 * 1.07f64.powi(i)).collect();
    let (v, n) = warm(rule, false, 2.0, &trend);
    assert_eq!(v, Settle::GaveUp);
    assert_eq!(n, 100, "200 ms of 2 ms frames");
    // Slow frames: the floor of frames holds even past max_ms.
    let (v, n) = warm(rule, false, 1000.0, &trend);
    assert_eq!((v, n), (Settle::GaveUp, WarmUp::MAX_FRAMES_FLOOR));
}

#[test]
fn blocks_interleave_the_baseline() {
    assert_eq!(block_order(0), vec![None]);
    assert_eq!(
        block_order(3),
        vec![None, Some(0), None, Some(1), None, Some(2), None]
    );
}

/// A block's base-pass samples: `n` frames at `ms`, with a little noise.
fn block(is_baseline: bool, ms: f64) -> (bool, Vec<f64>) {
    let noise = [0.0, 0.001, -0.001, 0.002, 0.0];
    (is_baseline, noise.iter().map(|e| ms + e).collect())
}

#[test]
fn the_h100_step_is_unstable() {
    // The H100 under the old protocol (lesson 09, 1920x1080): the base pass
    // read 0.788 ms while the clock was up and 4.655 ms after it fell.
    let blocks = vec![
        block(true, 0.788),
        block(false, 0.788),
        block(true, 0.788),
        block(false, 4.655),
        block(true, 0.788),
        block(false, 2.91),
        block(true, 0.788),
    ];
    let (reference, checks) = check_base(&blocks);
    assert!((reference.reference_ms - 0.788).abs() < 0.002);
    let stable: Vec<bool> = checks.iter().map(|c| c.stable).collect();
    assert_eq!(stable, [true, true, true, false, true, false, true]);
    // The old protocol timed the baseline once, last, after the fall: then
    // the variants timed early are the outliers, and still caught.
    let late = vec![block(false, 0.788), block(false, 4.655), block(true, 4.655)];
    let (reference, checks) = check_base(&late);
    assert!((reference.reference_ms - 4.655).abs() < 0.002);
    assert!(!checks[0].stable && checks[1].stable && checks[2].stable);
}

#[test]
fn a_steady_run_is_stable_and_spread_widens_the_tolerance() {
    let blocks = vec![
        block(true, 1.0),
        block(false, 1.2),
        block(true, 1.05),
        block(false, 0.9),
        block(true, 1.0),
    ];
    let (reference, checks) = check_base(&blocks);
    assert!(checks.iter().all(|c| c.stable), "{checks:?}");
    assert!(
        (reference.tolerance_ms - 0.02).abs() < 1e-9,
        "{reference:?}"
    );
    // lavapipe's lesson 08: the base pass reads 1.6 ms in the baseline and
    // 2.7 ms in the variants, block after block: within the factor 2.
    let blocks = vec![block(true, 1.608), block(false, 2.727), block(true, 1.61)];
    assert!(check_base(&blocks).1.iter().all(|c| c.stable));
    // Twice that is not.
    let blocks = vec![block(true, 1.608), block(false, 3.3), block(true, 1.61)];
    assert!(!check_base(&blocks).1[1].stable);
    // A rasteriser that shares the CPU (lavapipe) jitters by a millisecond
    // from frame to frame: the tolerance grows with that spread.
    let jitter = |b: bool, ms: f64| (b, vec![ms - 1.0, ms, ms + 1.0, ms - 0.5, ms + 0.5]);
    let blocks = vec![jitter(true, 2.0), jitter(false, 5.5), jitter(true, 2.0)];
    let (reference, checks) = check_base(&blocks);
    assert!(reference.tolerance_ms > 3.5, "{reference:?}");
    assert!(checks.iter().all(|c| c.stable), "{checks:?}");
}

#[test]
fn no_samples_is_not_stable() {
    let (_, checks) = check_base(&[(true, vec![1.0, 1.0]), (false, vec![])]);
    assert!(checks[0].stable && !checks[1].stable);
}

#[test]
fn an_unstable_baseline_block_is_left_out_of_the_baseline() {
    let frames = |base: f64, total: f64| -> Vec<FrameTimes> {
        let ms = [("base".to_string(), base), ("total".to_string(), total)];
        (0..3)
            .map(|_| FrameTimes {
                ms: ms.iter().cloned().collect(),
            })
            .collect()
    };
    let block = |id: BlockId, base: f64, total: f64| TimedBlock {
        id,
        warm_up_frames: 6,
        warm_up_ms: 10.0,
        settled: true,
        frames: frames(base, total),
    };
    // lavapipe's first block of a process, 2.1× slow after 3 s of warm-up.
    let blocks = vec![
        block(None, 5.5, 8.0),
        block(Some(0), 2.6, 4.0),
        block(None, 2.6, 3.0),
        block(None, 2.5, 3.0),
    ];
    let v = verdicts(&blocks, &["k4".to_string()], 300.0);
    let stable: Vec<bool> = v.baseline.1.iter().map(|c| c.stable).collect();
    assert_eq!(stable, [false, true, true]);
    assert_eq!(v.baseline.0.len(), 6, "the two stable blocks' frames");
    assert!(v.baseline.0.iter().all(|f| f.ms["total"] == 3.0));
    assert!(v.variants[0].1.stable && v.variants[0].0.len() == 3);
    assert!(!v.protocol.stable);
    // A lone baseline block is its own reference: kept, and the variant
    // 5.5× off it is the unstable one.
    let blocks = vec![block(None, 5.5, 8.0), block(Some(0), 1.0, 2.0)];
    let v = verdicts(&blocks, &["k4".to_string()], 300.0);
    assert_eq!(v.baseline.0.len(), 3);
    assert!(v.baseline.1[0].stable && !v.variants[0].1.stable);
}
