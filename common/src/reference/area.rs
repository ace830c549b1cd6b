//! The exact soft shadow of an area light (lesson 10): the fraction of the
//! emitter a point sees, by stratified ray casting.
//!
//! An emitter is the disk of `radius` through a point or spot light's
//! position, facing the shaded point, or the cone of directions of
//! `angular_radius_deg` around a directional light's (INTERFACES.md). A
//! point's visibility is the share of rays to uniformly spread points of the
//! emitter that reach it:
//!
//! - the emitter is cut into `n × n` strata of equal area (the unit square's
//!   cells, mapped to the disk by Shirley and Chiu's concentric map, which
//!   keeps cells compact), one ray through a random point of each cell;
//! - a ray that leaves below the receiver's own tangent plane is blocked
//!   (the surface hides that part of the emitter), as the hard reference
//!   counts N·L ≤ 0 as shadow;
//! - rays go where the answer is not 0 or 1: a pilot first, the emitter's
//!   rim at [`AreaSampling::rim`] evenly spaced points and
//!   [`AreaSampling::pilot_side`]² strata inside; only a point whose pilot
//!   rays disagree gets the full [`AreaSampling::side`]². An edge that
//!   crosses the emitter crosses its rim twice, so the rim catches every cap
//!   wider than the rim's spacing (with 16 points, a cap of 0.4 % of the
//!   emitter); a blocker seen wholly inside the emitter and smaller than a
//!   pilot stratum can be missed. The convergence test (`N` against `4N`,
//!   chapter 10) measures what that and the sampling leave.
//!
//! The jitter is a hash of the pixel and the ray: a reference is the same on
//! every run and machine.

use glam::Vec3;

use crate::scene::LightSize;

// ANCHOR: sampling
/// Rays per pixel for an area light: a pilot of `rim + pilot_side²`, then
/// `side²` where the pilot's rays disagree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AreaSampling {
    pub rim: u32,
    pub pilot_side: u32,
    pub side: u32,
}

impl AreaSampling {
    /// 32 pilot rays (16 on the rim), 256 in the penumbra.
    pub const DEFAULT: AreaSampling = AreaSampling {
        rim: 16,
        pilot_side: 4,
        side: 16,
    };

    /// Four times the rays, pilot and full: the convergence check's `4N`.
    pub fn times_four(self) -> AreaSampling {
        AreaSampling {
            rim: 4 * self.rim,
            pilot_side: 2 * self.pilot_side,
            side: 2 * self.side,
        }
    }

    /// The pilot's rays.
    pub fn pilot_rays(self) -> u64 {
        (self.rim + self.pilot_side * self.pilot_side) as u64
    }
}
// ANCHOR_END: sampling

/// An emitter's shape, as the sampler needs it.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Emitter {
    /// A disk of this radius through the light's position.
    Disk { radius: f32 },
    /// A cone of directions: `1 − cos` of its half-angle.
    Cone { one_minus_cos: f32 },
}

impl Emitter {
    /// The emitter of a light with a size, `None` for a hard light.
    pub(crate) fn of(size: LightSize) -> Option<Emitter> {
        match size {
            _ if !size.is_area() => None,
            LightSize::Radius(r) => Some(Emitter::Disk { radius: r as f32 }),
            LightSize::AngularRadiusDeg(a) => Some(Emitter::Cone {
                one_minus_cos: (1.0 - a.to_radians().cos()) as f32,
            }),
        }
    }
}

/// A unit vector's two perpendicular unit vectors (Duff et al. 2017).
fn basis(w: Vec3) -> (Vec3, Vec3) {
    let sign = 1f32.copysign(w.z);
    let a = -1.0 / (sign + w.z);
    let b = w.x * w.y * a;
    (
        Vec3::new(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x),
        Vec3::new(b, sign + w.y * w.y * a, -w.y),
    )
}

/// Shirley and Chiu's concentric map: the unit square onto the unit disk,
/// area for area, cells kept compact.
fn concentric(sx: f32, sy: f32) -> (f32, f32) {
    let (a, b) = (2.0 * sx - 1.0, 2.0 * sy - 1.0);
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    let (r, phi) = if a.abs() > b.abs() {
        (a, std::f32::consts::FRAC_PI_4 * (b / a))
    } else {
        (
            b,
            std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (a / b),
        )
    };
    (r * phi.cos(), r * phi.sin())
}

/// A 32-bit hash (PCG's output permutation): the jitter of ray `k` of pixel
/// `pixel` in round `round`, two numbers in [0, 1).
fn jitter(pixel: u32, k: u32, round: u32) -> (f32, f32) {
    let h = |x: u32| {
        let s = x.wrapping_mul(747796405).wrapping_add(2891336453);
        let w = ((s >> ((s >> 28) + 4)) ^ s).wrapping_mul(277803737);
        (w >> 22) ^ w
    };
    let a = h(pixel ^ h(k ^ h(round)));
    let b = h(a);
    let unit = |x: u32| (x >> 8) as f32 / (1u32 << 24) as f32;
    (unit(a), unit(b))
}

/// What one area-light query needs besides the rays' target: the point,
/// its normal (facing the camera), and the light's centre.
pub(crate) struct Query {
    pub from: Vec3,
    pub normal: Vec3,
    pub pixel: u32,
    /// Toward the light: a point or spot light's position, or a
    /// directional light's unit vector toward it.
    pub light: LightAt,
}

pub(crate) enum LightAt {
    Position(Vec3),
    Direction(Vec3),
}

// ANCHOR: area_visibility
/// The fraction of `emitter` that `q.from` sees, and the rays it took.
/// `blocked(dir, t_max)` casts one shadow ray (unit `dir`, length `t_max`,
/// infinite for a direction); `margin` keeps a ray short of the light.
pub(crate) fn visibility(
    emitter: Emitter,
    q: &Query,
    sampling: AreaSampling,
    margin: f32,
    blocked: impl Fn(Vec3, f32) -> bool,
) -> (f32, u64) {
    let (centre, w) = match q.light {
        LightAt::Position(p) => (Some(p), (p - q.from).normalize_or_zero()),
        LightAt::Direction(d) => (None, d),
    };
    let (u, v) = basis(w);
    // Whether the ray to the emitter's point (dx, dy) of the unit disk is
    // blocked.
    let ray = |dx: f32, dy: f32| -> bool {
        let (dir, t_max) = match (emitter, centre) {
            (Emitter::Disk { radius }, Some(c)) => {
                let target = c + radius * (dx * u + dy * v);
                let to = target - q.from;
                (to.normalize_or_zero(), to.length() - margin)
            }
            (Emitter::Cone { one_minus_cos }, _) => {
                // Uniform in solid angle: 1 − cos θ grows as ρ².
                let rho2 = dx * dx + dy * dy;
                let cos = 1.0 - rho2 * one_minus_cos;
                let sin = (1.0 - cos * cos).max(0.0).sqrt();
                let rho = rho2.sqrt();
                let across = if rho > 0.0 {
                    (dx * u + dy * v) / rho
                } else {
                    Vec3::ZERO
                };
                ((cos * w + sin * across).normalize(), f32::INFINITY)
            }
            // A disk needs a position; a cone, a direction (Emitter::of).
            (Emitter::Disk { .. }, None) => (w, f32::INFINITY),
        };
        // Below the tangent plane the receiver itself hides the emitter.
        dir.dot(q.normal) <= 0.0 || (t_max > 0.0 && blocked(dir, t_max))
    };
    // Rays through a jittered point of each cell of an n × n pattern: how
    // many reach the emitter.
    let strata = |n: u32, round: u32| {
        let seen = |k: u32| {
            let (jx, jy) = jitter(q.pixel, k, round);
            let (dx, dy) = concentric(
                ((k % n) as f32 + jx) / n as f32,
                ((k / n) as f32 + jy) / n as f32,
            );
            !ray(dx, dy)
        };
        (0..n * n).filter(|&k| seen(k)).count() as u64
    };
    // The pilot: the rim, turned by a random angle, and the strata inside.
    let turn = jitter(q.pixel, u32::MAX, 2).0;
    let rim = (0..sampling.rim)
        .filter(|&k| {
            let a = std::f32::consts::TAU * (k as f32 + turn) / sampling.rim as f32;
            !ray(a.cos(), a.sin())
        })
        .count() as u64;
    let pilot_rays = sampling.pilot_rays();
    let seen = rim + strata(sampling.pilot_side, 0);
    if seen == 0 || seen == pilot_rays {
        return (if seen == 0 { 0.0 } else { 1.0 }, pilot_rays);
    }
    let n = sampling.side;
    let seen = strata(n, 1);
    (seen as f32 / (n * n) as f32, pilot_rays + (n * n) as u64)
}
// ANCHOR_END: area_visibility

#[cfg(test)]
#[path = "unit_tests/area.rs"]
mod tests;
