//! Lesson 09's knobs ([`common::run::knobs`]): the cascade count and the
//! practical split's λ, on top of the named variants.
//!
//! Every cascaded variant takes `cascades` (1 to [`MAX_CASCADES`]), and
//! keeps the lesson's budget: K maps of 2048 / √K texels
//! ([`setup::per_cascade_resolution`]), so that more cascades trade the
//! size of each map for their number, as `k1` to `k4` do. The variants with
//! the practical split take `split_lambda` (λ = 0 is `k4_uniform`'s split,
//! λ = 1 `k4_log`'s); those two are the ends, and have no λ. Lesson 01's
//! `single_2048` and the exercises (the student's code) have none.

use anyhow::{bail, Result};
use common::run::knobs::{Knob, KnobRange};

use super::cascades::SplitScheme;
use super::csm::MAX_CASCADES;
use super::setup::{self, Setup};

/// The knob that sets how many cascades split the view.
pub const CASCADES_KNOB: &str = "cascades"; // not a counter: the knob

/// The knobs of a variant whose setup is `named` when named, with the
/// values of `now`.
pub fn setup_knobs(named: Setup, now: Setup) -> Vec<Knob> {
    if named.options.is_none() || named.exercise.is_some() {
        return Vec::new();
    }
    let mut knobs = vec![Knob {
        name: CASCADES_KNOB,
        doc: "K: the view frustum cut into K slices, each with its own map of 2048 / √K texels",
        range: KnobRange::Int {
            min: 1,
            max: MAX_CASCADES as i64,
        },
        value: now.count as f64,
    }];
    if let (SplitScheme::Practical { .. }, SplitScheme::Practical { lambda }) =
        (named.scheme, now.scheme)
    {
        knobs.push(Knob {
            name: "split_lambda",
            doc: "the practical split (Zhang et al.): λ × logarithmic + (1 − λ) × uniform",
            range: KnobRange::Float {
                min: 0.0,
                max: 1.0,
                log: false,
            },
            value: lambda,
        });
    }
    knobs
}

/// Sets knob `name` of `setup` to `value` (checked by `apply_knob`).
pub fn set_setup_knob(setup: &mut Setup, name: &str, value: f64) -> Result<()> {
    match (name, &mut setup.scheme) {
        (CASCADES_KNOB, _) => {
            setup.count = value as usize;
            setup.resolution = setup::per_cascade_resolution(setup.count);
        }
        ("split_lambda", SplitScheme::Practical { lambda }) => *lambda = value,
        _ => bail!("--knob {name}: this variant has no such knob"),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson_09::cascades::{Fit, FitOptions};

    #[test]
    fn more_cascades_share_the_texels() {
        let options = FitOptions {
            fit: Fit::Sphere,
            snap: true,
            extend: true,
        };
        let k4 = Setup::cascaded(4, SplitScheme::Practical { lambda: 0.9 }, options);
        let mut s = k4;
        set_setup_knob(&mut s, CASCADES_KNOB, 2.0).unwrap();
        assert_eq!((s.count, s.resolution), (2, 1448));
        set_setup_knob(&mut s, "split_lambda", 0.0).unwrap();
        let names: Vec<_> = setup_knobs(k4, s)
            .iter()
            .map(|k| (k.name, k.value))
            .collect();
        assert_eq!(names, [(CASCADES_KNOB, 2.0), ("split_lambda", 0.0)]);
        let uniform = Setup::cascaded(4, SplitScheme::Uniform, options);
        assert_eq!(setup_knobs(uniform, uniform).len(), 1);
        assert!(set_setup_knob(&mut uniform.clone(), "split_lambda", 0.5).is_err());
        assert!(setup_knobs(Setup::single(2048), Setup::single(2048)).is_empty());
    }
}
