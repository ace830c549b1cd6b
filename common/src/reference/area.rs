//! The exact soft shadow of an area light (lesson 10): the fraction of the
//! emitter a point sees, by stratified ray casting.
//!
//! An emitter is the disk of `radius` through a point or spot light's
//! position, facing the shaded point, or the cone of directions of
//! `angular_radius_deg` around a directional light's direction (the book's
//! appendix "Interfaces", "Scene files"). A point's visibility is the share
//! of rays to uniformly spread points of the emitter that reach it:
//!
//! - the emitter is cut into `n × n` strata of equal area (the unit square's
//!   cells, mapped to the disk by Shirley and Chiu's concentric map, which
//!   keeps cells compact), one ray through a random point of each cell;
//! - a ray that leaves below the receiver's own tangent plane is blocked
//!   (the surface hides that part of the emitter), as the hard reference
//!   counts N·L ≤ 0 as shadow;
//! - rays go only where something might block them. Every ray lies in one
//!   cone, from the point to the emitter ([`RayCone`]); a conservative query
//!   of the scene's BVH ([`crate::reference::bvh::Bvh::may_block`]) says
//!   whether any caster above the point's horizon reaches into it. Where
//!   none does and the whole cone is above the horizon, V = 1 exactly, with
//!   no ray. Anywhere else (a caster in the cone, however thin or small, or
//!   part of the emitter below the horizon: "horizon-clipped") the point
//!   gets the full [`AreaSampling::side`]² strata. What is left is the
//!   strata's own sampling error, which the convergence test (`N` against
//!   `4N`, chapter 10) measures.
//!
//! The jitter is a hash of the pixel and the ray: a reference is the same on
//! every run and machine.

use glam::Vec3;

use crate::reference::cone::RayCone;
use crate::scene::LightSize;

// ANCHOR: sampling
/// Rays per pixel for an area light: none where its cone toward the emitter
/// is empty and above the horizon (V = 1 exactly), else `side²`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AreaSampling {
    pub side: u32,
}

impl AreaSampling {
    /// 256 rays (16 × 16 strata) wherever something might block one.
    pub const DEFAULT: AreaSampling = AreaSampling { side: 16 };

    /// Four times the rays (side doubled): the convergence check's `4N`.
    pub fn times_four(self) -> AreaSampling {
        AreaSampling {
            side: 2 * self.side,
        }
    }

    /// The rays a pixel that is sampled gets: `side²`.
    pub fn rays(self) -> u64 {
        (self.side * self.side) as u64
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
    /// Where the rays start: the surface point, `lift` along `normal`.
    pub from: Vec3,
    pub normal: Vec3,
    /// How far `from` is off the surface (the shadow offset).
    pub lift: f32,
    pub pixel: u32,
    /// Toward the light: a point or spot light's position, or a
    /// directional light's unit vector toward it.
    pub light: LightAt,
}

pub(crate) enum LightAt {
    Position(Vec3),
    Direction(Vec3),
}

impl Query {
    /// The unit direction toward the emitter's centre, and the centre
    /// itself for a light with a position.
    fn axis(&self) -> (Vec3, Option<Vec3>) {
        match self.light {
            LightAt::Position(p) => ((p - self.from).normalize_or_zero(), Some(p)),
            LightAt::Direction(d) => (d, None),
        }
    }

    /// The cone that holds every ray toward `emitter`.
    pub(crate) fn cone(&self, emitter: Emitter) -> RayCone {
        let (w, centre) = self.axis();
        let (half_angle, length) = match (emitter, centre) {
            (Emitter::Disk { radius }, Some(c)) => {
                let l = (c - self.from).length();
                (radius.atan2(l), l.hypot(radius))
            }
            (Emitter::Cone { one_minus_cos }, _) => {
                // The widest ray [`Query::ray`] makes: its cosine, rounded
                // in f32 (a few ulps lower, for a tiny sun's sake).
                let cos = 1.0 - one_minus_cos * (1.0 + 4.0 * f32::EPSILON) - 2.0 * f32::EPSILON;
                (cos.clamp(-1.0, 1.0).acos(), f32::INFINITY)
            }
            (Emitter::Disk { .. }, None) => (0.0, f32::INFINITY),
        };
        RayCone::new(self.from, self.normal, self.lift, w, half_angle, length)
    }

    /// The ray to the emitter's point `(dx, dy)` of the unit disk: unit
    /// direction and length, `margin` short of a light with a position.
    fn ray(&self, emitter: Emitter, dx: f32, dy: f32, margin: f32) -> (Vec3, f32) {
        let (w, centre) = self.axis();
        let (u, v) = basis(w);
        match (emitter, centre) {
            (Emitter::Disk { radius }, Some(c)) => {
                let to = c + radius * (dx * u + dy * v) - self.from;
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
        }
    }
}

/// What [`visibility`] found at one point for one light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Seen {
    /// The fraction of the emitter the point sees.
    pub visibility: f32,
    /// The shadow rays cast.
    pub rays: u64,
    /// Whether part of the emitter is below the point's horizon.
    pub horizon_clipped: bool,
}

impl Seen {
    /// An empty cone above the horizon: the whole emitter, no ray.
    pub const OPEN: Seen = Seen {
        visibility: 1.0,
        rays: 0,
        horizon_clipped: false,
    };
}

// ANCHOR: area_visibility
/// The fraction of `emitter` that `q.from` sees. `may_block(cone)` is a
/// conservative query: `false` only where no caster can cross a ray of
/// `cone`. `blocked(dir, t_max)` casts one shadow ray (unit `dir`, length
/// `t_max`, infinite for a direction); `margin` keeps a ray short of the
/// light. V = 1 with no ray exactly where the cone is empty and above the
/// horizon; any other point, whatever is in its cone, gets all `side²`
/// strata.
pub(crate) fn visibility(
    emitter: Emitter,
    q: &Query,
    sampling: AreaSampling,
    margin: f32,
    may_block: impl Fn(&RayCone) -> bool,
    blocked: impl Fn(Vec3, f32) -> bool,
) -> Seen {
    let cone = q.cone(emitter);
    let horizon_clipped = cone.horizon_clipped();
    if !horizon_clipped && !may_block(&cone) {
        return Seen::OPEN;
    }
    // One ray through a jittered point of each cell of the n × n strata.
    let n = sampling.side;
    let seen = |k: u32| {
        let (jx, jy) = jitter(q.pixel, k, 1);
        let (sx, sy) = ((k % n) as f32 + jx, (k / n) as f32 + jy);
        let (dx, dy) = concentric(sx / n as f32, sy / n as f32);
        let (dir, t_max) = q.ray(emitter, dx, dy, margin);
        // Below the tangent plane the receiver itself hides the emitter.
        dir.dot(q.normal) > 0.0 && !(t_max > 0.0 && blocked(dir, t_max))
    };
    let lit = (0..n * n).filter(|&k| seen(k)).count();
    Seen {
        visibility: lit as f32 / (n * n) as f32,
        rays: sampling.rays(),
        horizon_clipped,
    }
}
// ANCHOR_END: area_visibility

#[cfg(test)]
#[path = "unit_tests/area.rs"]
mod tests;
