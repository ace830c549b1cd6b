//! The cone of an area light's shadow rays, and conservative tests of
//! whether a box or a triangle could block one of them (lesson 10).
//!
//! Every shadow ray toward an emitter leaves the same point (the receiver,
//! lifted by the shadow offset) inside one cone: toward a disk of radius
//! `R` at distance `L`, half-angle `atan(R / L)` and length at most
//! `√(L² + R²)`; toward a cone of directions, its half-angle and no end.
//! A test here answers "no" only where no ray of the cone can cross the
//! box or triangle, up to `f32` rounding with a wide margin:
//!
//! - the cone is widened a hair ([`ANGLE_SLACK`]) and made longer
//!   ([`LENGTH_SLACK`]) than any ray the sampler casts;
//! - a ball (centre `q`, radius `r`; `v = q − apex`, `t = v·w`,
//!   `d = |v − t w|`) can touch the cone only if `d cos θ − t sin θ ≤ r`
//!   (its distance to the cone's side) and `t + r ≥ 0` and `t − r ≤ length`;
//! - a triangle is also ruled out when the whole cone lies on one side of
//!   its plane, or outside one side of the pyramid from the apex over it
//!   (a ray hits the triangle only through that pyramid);
//! - what lies wholly beneath the receiver's horizon is ruled out: a ray
//!   the sampler casts leaves above the tangent plane (a ray below it is
//!   counted blocked without a cast), so every point it reaches is at or
//!   above the plane through its start. Anything at least
//!   [`HORIZON_SLACK`] of the shadow offset below that start is out of
//!   reach; the receiver's own surface is a whole offset below it.

use glam::Vec3;

/// What lies this fraction of the shadow offset (or more) below the rays'
/// start is culled as beneath the receiver's horizon. Half the offset: the
/// receiver's surface and everything coplanar with it (a whole offset down)
/// are culled, and the gap to the rays (half an offset, 5e-6 of the scene's
/// diagonal) is some 80 times the `f32` rounding at the scene's size.
pub const HORIZON_SLACK: f32 = 0.5;

/// The cone's half-angle is widened by this fraction (and by as many
/// radians): more than the rounding of a sampled ray's direction.
pub const ANGLE_SLACK: f32 = 1e-4;

/// Lengths and radii are lengthened by this fraction: more than the
/// rounding of a ray's length, or of a box or triangle (the triangle test
/// widens triangles by [`crate::reference::bvh::EDGE_EPSILON`]).
pub const LENGTH_SLACK: f32 = 1e-5;

/// Every shadow ray from one receiver toward one emitter: rays from
/// `apex` within the half-angle of `axis`, of length at most `length`.
#[derive(Clone, Copy, Debug)]
pub struct RayCone {
    /// Where every ray starts: the receiver, lifted by the shadow offset.
    pub apex: Vec3,
    /// Unit axis, toward the emitter's centre.
    pub axis: Vec3,
    /// Cosine and sine of the half-angle (widened by [`ANGLE_SLACK`]).
    pub cos: f32,
    pub sin: f32,
    /// The longest ray (lengthened by [`LENGTH_SLACK`]); infinite toward
    /// a direction.
    pub length: f32,
    /// The receiver's unit normal (its tangent plane: the horizon).
    pub normal: Vec3,
    /// What lies at least this far below the apex along `normal` is out of
    /// the rays' reach: [`HORIZON_SLACK`] times the shadow offset.
    pub below: f32,
}

impl RayCone {
    /// The cone from `apex` (`lift` off a surface of unit `normal`) around
    /// unit `axis`, of half-angle `half_angle` (radians) and rays up to
    /// `length` long, widened and lengthened by the slacks.
    pub fn new(
        apex: Vec3,
        normal: Vec3,
        lift: f32,
        axis: Vec3,
        half_angle: f32,
        length: f32,
    ) -> RayCone {
        let half_angle = (half_angle * (1.0 + ANGLE_SLACK) + ANGLE_SLACK)
            .clamp(0.0, std::f32::consts::FRAC_PI_2);
        RayCone {
            apex,
            axis,
            cos: half_angle.cos(),
            sin: half_angle.sin(),
            length: length * (1.0 + LENGTH_SLACK),
            normal,
            below: HORIZON_SLACK * lift,
        }
    }

    /// Whether some of the cone is at or below the receiver's tangent
    /// plane (the emitter partly beneath its horizon): unless the axis is
    /// above the plane by more than the half-angle, `w·n > sin θ` (the
    /// widened one: an emitter within a hair of the horizon counts).
    pub fn horizon_clipped(&self) -> bool {
        // Written so that a NaN counts as clipped.
        let above = self.axis.dot(self.normal) > self.sin;
        !above
    }

    /// Whether a ball of centre `q` and radius `r` might meet a ray.
    pub fn may_touch_ball(&self, q: Vec3, r: f32) -> bool {
        let v = q - self.apex;
        let r = r * (1.0 + LENGTH_SLACK) + LENGTH_SLACK * v.length();
        let t = v.dot(self.axis);
        let d = (v - t * self.axis).length();
        d * self.cos - t * self.sin <= r && t + r >= 0.0 && t - r <= self.length
    }

    /// Whether a point lies out of the rays' reach beneath the horizon.
    fn beneath(&self, x: Vec3) -> bool {
        self.normal.dot(x - self.apex) <= -self.below
    }

    /// Whether the box `[lo, hi]` might hold a point a ray reaches.
    pub fn may_touch_box(&self, lo: Vec3, hi: Vec3) -> bool {
        let (centre, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        // The box's highest point above the horizon.
        let top = self.normal.dot(centre - self.apex) + self.normal.abs().dot(half);
        top > -self.below && self.may_touch_ball(centre, half.length())
    }

    /// Whether a ray might cross the triangle `[a, b, c]`.
    pub fn may_hit_triangle(&self, [a, b, c]: [Vec3; 3]) -> bool {
        if self.beneath(a) && self.beneath(b) && self.beneath(c) {
            return false;
        }
        let q = (a + b + c) / 3.0;
        let r = (a - q).length().max((b - q).length()).max((c - q).length());
        if !self.may_touch_ball(q, r) {
            return false;
        }
        let m = (b - a).cross(c - a).normalize_or_zero();
        if m == Vec3::ZERO {
            return true; // degenerate: the ball alone decides
        }
        let far = (q - self.apex).length();
        let slack = LENGTH_SLACK * (r + far);
        // The apex is at least this far from any point of the triangle.
        let h = m.dot(self.apex - a);
        let near = h.abs().max(far - r);
        !self.beside_plane(m, h, slack) && !self.outside_a_side([a, b, c], near, slack)
    }

    /// The least and the most of `m·d` over the cone's unit directions `d`:
    /// cos(φ ± θ), where φ is the angle from the axis to unit `m`, clamped
    /// at 0 and π.
    fn spread(&self, m: Vec3) -> (f32, f32) {
        let cos_phi = m.dot(self.axis).clamp(-1.0, 1.0);
        let sin_phi = (1.0 - cos_phi * cos_phi).max(0.0).sqrt();
        let least = if -cos_phi >= self.cos {
            -1.0
        } else {
            cos_phi * self.cos - sin_phi * self.sin
        };
        let most = if cos_phi >= self.cos {
            1.0
        } else {
            cos_phi * self.cos + sin_phi * self.sin
        };
        (least, most)
    }

    /// Whether the whole cone lies more than `slack` to one side of the
    /// plane with unit normal `m` at signed height `h` above the apex.
    fn beside_plane(&self, m: Vec3, h: f32, slack: f32) -> bool {
        let (least, most) = self.spread(m);
        // Along a ray, the height goes from h to h + length · (m·d).
        let lo = h + if least < 0.0 {
            self.length * least
        } else {
            0.0
        };
        let hi = h + if most > 0.0 { self.length * most } else { 0.0 };
        lo > slack || hi < -slack
    }

    /// Whether every ray leaves the pyramid from the apex over the
    /// triangle through one of its sides (the plane through the apex and
    /// an edge), by more than `slack` at the distance `near` (no point of
    /// the triangle is closer).
    fn outside_a_side(&self, corners: [Vec3; 3], near: f32, slack: f32) -> bool {
        let [ua, ub, uc] = corners.map(|x| x - self.apex);
        let volume = ua.cross(ub).dot(uc);
        // The apex (nearly) in the triangle's plane: no pyramid to trust.
        let size = ua.length() * ub.length() * uc.length();
        let pyramid = volume.abs() > 1e-4 * size; // false for a NaN too
        if !pyramid {
            return false;
        }
        [(ua, ub), (ub, uc), (uc, ua)].into_iter().any(|(u, v)| {
            // The side's normal, toward the third corner; an edge seen
            // end-on (a side nearly through the apex's line) is skipped.
            let n = u.cross(v);
            let seen_across = n.length() > 1e-2 * u.length() * v.length();
            if !seen_across {
                return false;
            }
            let (_, most) = self.spread(n.normalize() * volume.signum());
            most * near < -slack
        })
    }
}

#[cfg(test)]
#[path = "unit_tests/cone.rs"]
mod tests;
