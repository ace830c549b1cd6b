//! The magnitudes a scene may have, and numbers in messages.
//!
//! Everything the GPU and the reference see is `f32`, relative to
//! [`crate::scene::Scene::origin`]. `f32` keeps 24 bits, so a scene's
//! *size* (not its distance from the world origin, which cancels in `f64`)
//! decides its precision. These limits keep every supported scene well inside
//! that, and refuse the rest in one line that names the field and the range
//! (the README and the book's appendix list them).

use anyhow::{bail, Result};
use glam::{DVec3, Vec3};

/// Any coordinate (eye, target, light position, translate, a vertex after
/// its object's transform) lies within `±MAX_COORD`: 1,000 km, so a scene
/// 10 km from the origin is ordinary.
pub const MAX_COORD: f64 = 1e6;

/// Everything in a scene (its objects, the eye and the target, and point or
/// spot lights) fits in a box this wide. At 1e5 units an `f32` step is
/// 1/128 unit; a metre-sized object beside it still has millimetres.
pub const MAX_EXTENT: f64 = 1e5;

/// `|scale|` of each axis lies in `[MIN_SCALE, MAX_SCALE]`.
pub const MIN_SCALE: f64 = 1e-6;
pub const MAX_SCALE: f64 = 1e6;

/// `fov_y_deg` lies in `[MIN_FOV_DEG, MAX_FOV_DEG)`. Below 0.1° the
/// projection's `1/tan` passes 1,000 and the pixels of a 720-row image are
/// closer than the `f32` step of the positions they unproject.
pub const MIN_FOV_DEG: f64 = 0.1;
pub const MAX_FOV_DEG: f64 = 179.0;

/// A finite `far / near` is at most this: it admits lesson 07's deep range
/// (near 1e-3, far 1e5) and refuses near 1e-7 with far 100 (1e9).
pub const MAX_DEPTH_RATIO: f64 = 1e8;

/// The distance from the eye to the farthest point of the scene (or to the
/// far plane, if nearer), over `near`, is at most this. A standard depth is
/// about `1 − near/z`; at `z = 1e6·near` that is 17 `f32` steps (2⁻²⁴) below
/// 1, and past it depth runs out: with near 1e-6 and the scene 37 units away
/// (3.7e7) lesson 05 on lavapipe drew nothing, and its error read 0 %.
/// Lesson 07's deep-range scene (near 1e-3, the scene 400 away) is 4e5.
pub const MAX_REACH_OVER_NEAR: f64 = 1e6;

/// `near` is at least this.
pub const MIN_NEAR: f64 = 1e-6;

/// `camera.shift` components lie in `[-MAX_SHIFT, MAX_SHIFT]` (NDC units:
/// half-widths, half-heights). Past a few the view hardly overlaps the
/// unshifted one; 10 leaves room without inviting a typo's 1e9.
pub const MAX_SHIFT: f64 = 10.0;

/// A number in short form, to 6 significant digits: `1e308` (not 309
/// digits), `1e-300`, `0.25`, `50`, `45.5522`, `4.55522e7`.
pub fn short(x: f64) -> String {
    let x = format!("{x:.5e}").parse::<f64>().unwrap_or(x);
    if x == 0.0 || !x.is_finite() || (1e-4..1e5).contains(&x.abs()) {
        // `{}` is the shortest text that reads back to the same f64.
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `[x, y, z]` in short form.
pub fn short3(v: impl Into<DVec3>) -> String {
    let v = v.into();
    format!("[{}, {}, {}]", short(v.x), short(v.y), short(v.z))
}

/// `what`: every component finite and within `±MAX_COORD`.
pub fn check_coord(v: [f64; 3], what: &str) -> anyhow::Result<DVec3> {
    if v.iter().any(|c| !c.is_finite()) {
        anyhow::bail!("{what}: must be finite, got {}", short3(v));
    }
    if v.iter().any(|c| c.abs() > MAX_COORD) {
        anyhow::bail!(
            "{what}: components must be within ±{} (the world bound), got {}",
            short(MAX_COORD),
            short3(v)
        );
    }
    Ok(DVec3::from(v))
}

/// A direction, normalised whatever its length (1e200 or 1e-200); only an
/// exact zero or a non-finite component is refused.
pub fn check_direction(v: [f64; 3], what: &str) -> anyhow::Result<DVec3> {
    if v.iter().any(|c| !c.is_finite()) {
        anyhow::bail!("{what}: must be finite, got {}", short3(v));
    }
    let d = DVec3::from(v);
    let big = d.abs().max_element();
    if big == 0.0 {
        anyhow::bail!("{what}: zero-length vector {}", short3(v));
    }
    // Divide by the largest component first, so that squaring cannot overflow
    // (1e200² is infinite) or underflow (1e-200² is 0).
    Ok((d / big).normalize())
}

/// A growing bounding box that says which entry first made it too big.
#[derive(Clone, Copy, Debug)]
pub struct Extent {
    pub lo: DVec3,
    pub hi: DVec3,
}

impl Default for Extent {
    fn default() -> Self {
        Extent {
            lo: DVec3::splat(f64::INFINITY),
            hi: DVec3::splat(f64::NEG_INFINITY),
        }
    }
}

impl Extent {
    /// Adds points; fails, naming `what`, when the box passes `MAX_EXTENT`.
    pub fn add(
        &mut self,
        points: impl IntoIterator<Item = DVec3>,
        what: &str,
    ) -> anyhow::Result<()> {
        for p in points {
            if !p.is_finite() || p.abs().max_element() > MAX_COORD {
                anyhow::bail!(
                    "{what}: reaches {}, outside the world bound ±{}",
                    short3(p),
                    short(MAX_COORD)
                );
            }
            self.lo = self.lo.min(p);
            self.hi = self.hi.max(p);
            let size = (self.hi - self.lo).max_element();
            if size > MAX_EXTENT {
                anyhow::bail!(
                    "{what}: makes the scene {} units wide (from {} to {}); a scene must fit in {} units, the f32 precision limit",
                    short(size),
                    short3(self.lo),
                    short3(self.hi),
                    short(MAX_EXTENT)
                );
            }
        }
        Ok(())
    }
}

/// A colour: components in [0, 1e6].
pub(crate) fn color3(v: [f32; 3], what: &str) -> Result<Vec3> {
    if v.iter().any(|c| !c.is_finite() || *c < 0.0 || *c > 1e6) {
        bail!(
            "{what}: colour components must be in [0, 1e6], got {}",
            short3(Vec3::from(v).as_dvec3())
        );
    }
    Ok(Vec3::from(v))
}

/// A positive number up to `max`.
pub(crate) fn positive(x: f64, max: f64, what: &str) -> Result<f64> {
    if !(x.is_finite() && x > 0.0 && x <= max) {
        bail!("{what}: must be in (0, {}], got {}", short(max), short(x));
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_form() {
        assert_eq!(short(1e308), "1e308");
        assert_eq!(short(1e-300), "1e-300");
        assert_eq!(short(-2.5e20), "-2.5e20");
        assert_eq!(short(0.1), "0.1");
        assert_eq!(short(50.0), "50");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(45.552167895721496), "45.5522");
        assert_eq!(short(4.5552167895721495e7), "4.55522e7");
        assert_eq!(short(f64::NAN), "NaN");
        assert_eq!(short3([1e300, 3.0, 6.0]), "[1e300, 3, 6]");
    }

    #[test]
    fn directions_of_any_length_normalise() {
        for s in [1e-200, 1.0, 1e200, f64::MAX] {
            let d = check_direction([0.0, -s, 0.0], "d").unwrap();
            assert_eq!(d, DVec3::NEG_Y, "length {s}");
        }
        assert!(check_direction([0.0; 3], "d").is_err());
        assert!(check_direction([f64::INFINITY, 0.0, 0.0], "d").is_err());
    }

    #[test]
    fn extent_names_the_entry_that_breaks_it() {
        let mut e = Extent::default();
        e.add([DVec3::ZERO, DVec3::ONE], "a").unwrap();
        let err = e.add([DVec3::new(2e5, 0.0, 0.0)], "b").unwrap_err();
        assert!(
            err.to_string()
                .starts_with("b: makes the scene 2e5 units wide"),
            "{err}"
        );
        let err = e.add([DVec3::new(0.0, 1e20, 0.0)], "c").unwrap_err();
        assert!(
            err.to_string().contains("outside the world bound ±1e6"),
            "{err}"
        );
    }
}
