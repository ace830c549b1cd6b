//! Lesson 03's knobs ([`common::run::knobs`]): the size of a filter's
//! kernel, on top of the named variants. The N×N grids (with and without
//! the receiver plane) and the depth average take `kernel_radius`, N = 2r + 1
//! (odd: the grid is centred on the receiver); the Poisson disk takes its
//! radius in texels. The renderers' defaults and the exercises have none:
//! those are someone else's settings and the student's code.

use anyhow::{bail, Result};
use common::run::knobs::{Knob, KnobRange};

use super::pcf::Filter;

/// The largest grid radius: 15×15, 225 taps.
pub const MAX_KERNEL_RADIUS: u32 = 7;

/// The knobs of `filter`, with its values now.
pub fn filter_knobs(filter: Filter) -> Vec<Knob> {
    let radius = |n: u32, doc| Knob {
        name: "kernel_radius",
        doc,
        range: KnobRange::Int {
            min: 0,
            max: MAX_KERNEL_RADIUS as i64,
        },
        value: (n / 2) as f64,
    };
    match filter {
        Filter::Grid { n, .. } => vec![radius(
            n,
            "an N×N grid of comparisons, N = 2 × kernel_radius + 1: the penumbra is N texels wide",
        )],
        Filter::DepthAverage { n } => vec![radius(
            n,
            "the N×N depths averaged, N = 2 × kernel_radius + 1: the shadow grows by the radius",
        )],
        Filter::Poisson { radius, .. } => vec![Knob {
            name: "disk_radius_texels",
            doc: "the rotated disk's radius, in texels: its 16 bilinear taps spread over it",
            range: KnobRange::Float {
                min: 0.5,
                max: 8.0,
                log: false,
            },
            value: radius.to_string().parse().unwrap_or(radius as f64),
        }],
        _ => Vec::new(),
    }
}

/// Sets knob `name` of `filter` to `value` (checked by `apply_knob`).
pub fn set_filter_knob(filter: &mut Filter, name: &str, value: f64) -> Result<()> {
    match (filter, name) {
        (Filter::Grid { n, .. } | Filter::DepthAverage { n }, "kernel_radius") => {
            *n = 2 * value as u32 + 1;
        }
        (Filter::Poisson { radius, .. }, "disk_radius_texels") => *radius = value as f32,
        (f, _) => bail!("--knob {name}: the filter {f:?} has no such knob"),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_radius_makes_an_odd_grid() {
        let mut f = Filter::Grid {
            n: 3,
            receiver_plane: true,
        };
        assert_eq!(filter_knobs(f)[0].value, 1.0);
        set_filter_knob(&mut f, "kernel_radius", 3.0).unwrap();
        assert_eq!(f.taps(), (49, 49));
        assert!(set_filter_knob(&mut f, "disk_radius_texels", 1.0).is_err());
        assert!(filter_knobs(Filter::Hardware2x2).is_empty());
    }
}
