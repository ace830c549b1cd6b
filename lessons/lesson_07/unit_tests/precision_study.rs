//! Unit tests of `lesson_07::precision_study` (kept apart so the module
//! stays short).

use super::*;

const STORAGES: [DepthStorage; 2] = [DepthStorage::Unorm24, DepthStorage::Float32];

#[test]
fn unorm24_quantises_in_even_steps_and_f32_keeps_more_near_zero() {
    let (u, f) = (DepthStorage::Unorm24, DepthStorage::Float32);
    assert_eq!(quantise(u, 1.0), 16_777_215);
    assert_eq!(quantise(u, 0.5), 8_388_608);
    assert_eq!(quantise(u, 1e-9), 0);
    assert!(quantise(f, 1e-9) > quantise(f, 0.0));
}

#[test]
fn reversed_float_beats_standard_far_away() {
    let (n, f) = (1e-3, 1e5);
    let g = gaps();
    let at = |fmt, m| {
        let grid = model_cpu(fmt, m, n, f);
        min_resolvable_gap(grid.last().unwrap(), &g)
    };
    // far/2 = 5e4: standard depth is within a few ulps of 1; nothing resolves.
    assert_eq!(at(DepthStorage::Unorm24, DepthMapping::Standard), None);
    assert_eq!(at(DepthStorage::Float32, DepthMapping::Standard), None);
    let rev = at(DepthStorage::Float32, DepthMapping::Reversed).expect("reversed f32 resolves");
    assert!(rev <= 1e-6, "reversed f32 at far/2 resolves {rev}");
    let inf_rev = at(DepthStorage::Float32, DepthMapping::InfiniteReversed).expect("resolves");
    assert!(inf_rev <= 1e-6, "{inf_rev}");
}

/// Many samples per cell: no cell resolves a gap well below one storage
/// step (the analytic curve), and none needs ten times more.
#[test]
fn the_model_follows_the_analytic_curve() {
    let g = gaps();
    for ratio in [1e2, 1e4, 1e6, 1e8] {
        let (n, f) = (1e-3, 1e-3 * ratio);
        for fmt in STORAGES {
            for m in MAPPINGS {
                let grid = model_cpu(fmt, m, n, f);
                for (i, d) in distances(n, f).into_iter().enumerate() {
                    let a = analytic_gap(m, fmt, n, f, d);
                    let got = min_resolvable_gap(&grid[i], &g);
                    let ctx = format!("{fmt:?} {} far/near {ratio:e} d {d:e}", m.name());
                    if a > 0.1 {
                        continue;
                    }
                    let got = got.unwrap_or_else(|| panic!("{ctx}: none, analytic {a:e}"));
                    assert!(got >= a / 2.0 && got <= a * 10.0, "{ctx}: {got:e} vs {a:e}");
                }
            }
        }
    }
}

#[test]
fn min_gap_needs_every_larger_gap_to_resolve() {
    let g = [1.0, 2.0, 3.0, 4.0];
    assert_eq!(min_resolvable_gap(&[0.0, 1.0, 0.96, 1.0], &g), Some(2.0));
    assert_eq!(min_resolvable_gap(&[1.0, 0.9, 1.0, 1.0], &g), Some(3.0));
    assert_eq!(min_resolvable_gap(&[1.0, 1.0, 1.0, 0.5], &g), None);
}
