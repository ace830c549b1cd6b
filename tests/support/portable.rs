//! Which of a snapshot's figures are portable: compared within their
//! bound on another adapter (`tolerance`), or, where the bound covers
//! most of what the figure could be, marked and compared by the side of a
//! power of ten they lie on ([`Side`]). `report.rs` marks them when it
//! prints a bound ([`crate::report::bound`]); `tolerance::compare` reads the
//! marks.

/// A figure whose bound is more than this share of itself is not portable
/// (and more than [`PORTABLE_FLOOR`]): the bound then reaches 0, so the
/// comparison passes the figure gone as well as doubled: neither that the
/// technique errs there nor by how much is tested. 1, not less: the moves
/// bound a mean |ΔV| by every pixel's largest change, so a soft shadow's
/// penumbra error moves by half of itself and more (lesson 10's `pcss`,
/// 3.2 % ±1.7) and is still told from none and from a cruder penumbra's
/// (22.2 %); acne's figures, which every move draws anew, lie beyond it
/// (48.93 % ±91.13, 23.09 % ±47.34).
pub const PORTABLE_SHARE: f64 = 1.0;

/// A bound of this many percentage points or less leaves its figure
/// portable whatever their ratio: a figure near 0 (`0.00% ±0.40`, a
/// technique without error) is then tested as "under 0.41 points", which
/// a broken technique misses by more (`tests/snapshot_tolerance.rs`,
/// `broken_techniques_fail`).
pub const PORTABLE_FLOOR: f64 = 1.0;

/// Whether a figure `figure` (percent) moves within its bound `bound` on
/// another adapter in a way worth comparing ([`PORTABLE_SHARE`],
/// [`PORTABLE_FLOOR`]).
pub fn portable(figure: f64, bound: f64) -> bool {
    bound <= PORTABLE_SHARE * figure.abs() || bound <= PORTABLE_FLOOR || figure.is_nan()
}

/// What a figure that is not portable is tested by: which side of a power
/// of ten (percent) it lies on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Side {
    Above(f64),
    Below(f64),
}

impl Side {
    /// Whether `value` lies on this side.
    pub fn holds(self, value: f64) -> bool {
        match self {
            Side::Above(t) => value > t,
            Side::Below(t) => value < t,
        }
    }
}

impl std::fmt::Display for Side {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Side::Above(t) => write!(f, "above {t}%"),
            Side::Below(t) => write!(f, "below {t}%"),
        }
    }
}

/// The powers of ten a [`Side`] is drawn at, percent.
const SIDES: [f64; 4] = [0.01, 0.1, 1.0, 10.0];

/// The side a figure that is not portable keeps on every adapter: a
/// figure of [`PORTABLE_FLOOR`] points or more lies above the largest
/// power of ten at most half of it (48.93 %: above 10 %), a smaller one
/// below the smallest at least twice it (0.02 %: below 0.1 %). A factor 2:
/// what the figure moved by, adapter to adapter, where the bounds failed
/// (0.1578 against 0.2826 % false shadow, lesson 10's `pcss` on an H200).
pub fn portable_side(figure: f64) -> Side {
    if figure >= PORTABLE_FLOOR {
        let t = SIDES.iter().rev().find(|&&t| t <= figure / 2.0);
        Side::Above(*t.unwrap_or(&SIDES[0]))
    } else {
        let t = SIDES.iter().find(|&&t| t >= 2.0 * figure);
        Side::Below(*t.unwrap_or(&100.0))
    }
}

/// How a snapshot prints a figure that is not portable, after the figure
/// and its unit: ` (not portable: ±B, above 10%)`. `bound` is the bound as
/// printed.
pub fn not_portable(bound: &str, side: Side) -> String {
    format!("{NOT_PORTABLE}{bound}, {side})")
}

/// What opens [`not_portable`]'s mark.
pub const NOT_PORTABLE: &str = " (not portable: ±";
