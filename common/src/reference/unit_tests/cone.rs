//! Unit tests of `common::reference::cone`: the cone query never calls a
//! cone empty that a ray can cross, and culls the receiver's own floor.

use super::*;
use crate::reference::area::{visibility, AreaSampling, Emitter, LightAt, Query};
use crate::reference::bvh::Bvh;
use crate::scene::LightSize;

/// A tiny deterministic generator (xorshift), so tests need no crate.
struct Rng(u64);
impl Rng {
    fn f(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f()
    }
    fn unit(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(self.f(), self.f(), self.f()) * 2.0 - 1.0;
            if v.length_squared() > 0.01 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }
}

/// Two unit vectors across `w`.
fn across(w: Vec3) -> (Vec3, Vec3) {
    let u = w.any_orthonormal_vector();
    (u, w.cross(u))
}

/// A random receiver and emitter: the apex, the normal, the emitter, the
/// axis and the cone (a disk light at a position, or a cone of directions).
struct Case {
    q: Query,
    emitter: Emitter,
    cone: RayCone,
}

fn random_case(rng: &mut Rng, pixel: u32) -> Case {
    let from = Vec3::new(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    );
    let w = rng.unit();
    // The normal: mostly toward the light, sometimes tilted past its rim.
    let normal = (w + rng.range(0.0, 1.5) * rng.unit()).normalize();
    let lift = 1e-4;
    let (emitter, light) = if rng.f() < 0.5 {
        let dist = rng.range(0.5, 4.0);
        let radius = dist * rng.range(0.02, 0.6);
        (Emitter::Disk { radius }, LightAt::Position(from + dist * w))
    } else {
        let deg = rng.range(0.5, 20.0) as f64;
        (
            Emitter::of(LightSize::AngularRadiusDeg(deg)).unwrap(),
            LightAt::Direction(w),
        )
    };
    let q = Query {
        from,
        normal,
        lift,
        pixel,
        light,
    };
    let cone = q.cone(emitter);
    Case { q, emitter, cone }
}

/// The true half-angle's tangent and length of a case's cone (the query's
/// is widened): rays are spread over it.
fn true_cone(c: &Case) -> (f32, f32) {
    match (c.emitter, &c.q.light) {
        (Emitter::Disk { radius }, LightAt::Position(p)) => {
            let l = (*p - c.q.from).length();
            (radius / l, l.hypot(radius))
        }
        (Emitter::Cone { one_minus_cos }, _) => {
            let cos = 1.0 - one_minus_cos;
            ((1.0 - cos * cos).sqrt() / cos, f32::INFINITY)
        }
        _ => unreachable!(),
    }
}

/// A triangle near the cone's side: around a point at a random distance
/// along a direction at 0.7 to 1.4 times the half-angle, of a random size
/// (from a hundredth of that distance to its double), so that many are
/// near misses. Some reach behind the apex or below the horizon.
fn triangle_near(rng: &mut Rng, c: &Case) -> [Vec3; 3] {
    let (tan, length) = true_cone(c);
    let w = c.cone.axis;
    let (u, v) = across(w);
    let phi = rng.range(0.0, std::f32::consts::TAU);
    let tan_k = tan * rng.range(0.7, 1.4);
    let dir = (w + tan_k * (phi.cos() * u + phi.sin() * v)).normalize();
    let s = length.min(6.0) * rng.range(-0.05, 1.1);
    let centre = c.q.from + s * dir;
    let size = s.abs().max(0.05) * 10f32.powf(rng.range(-2.0, 0.3));
    [0; 3].map(|_| centre + size * rng.unit())
}

/// Rays the sampler could cast for a case: to random points of the emitter
/// and of its rim (uniform directions within the cone and on its edge for
/// a cone of directions), only those leaving above the horizon.
fn brute_rays(rng: &mut Rng, c: &Case, n: usize) -> Vec<(Vec3, f32)> {
    let (tan, length) = true_cone(c);
    let w = c.cone.axis;
    let (u, v) = across(w);
    (0..n)
        .map(|k| {
            let rho = if k % 4 == 0 { 1.0 } else { rng.f().sqrt() };
            let phi = rng.range(0.0, std::f32::consts::TAU);
            let off = rho * tan * (phi.cos() * u + phi.sin() * v);
            match length.is_finite() {
                // To the disk's point: length up to the disk.
                true => {
                    let to = (w + off) * (length / (1.0 + tan * tan).sqrt());
                    (to.normalize(), to.length())
                }
                false => ((w + off).normalize(), f32::INFINITY),
            }
        })
        .filter(|(d, _)| d.dot(c.q.normal) > 0.0)
        .collect()
}

/// Random triangles near random cones: wherever the query says that no
/// ray can cross a triangle (or a whole soup, through the BVH), thousands
/// of rays over the emitter and its rim find none that does.
#[test]
fn the_query_is_conservative() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut empty, mut maybe, mut wrong, mut maybe_hit) = (0, 0, 0, 0);
    let (mut soups_empty, mut soups_wrong) = (0, 0);
    for case in 0..300 {
        let c = random_case(&mut rng, case);
        let rays = brute_rays(&mut rng, &c, 2000);
        let tris: Vec<[Vec3; 3]> = (0..24).map(|_| triangle_near(&mut rng, &c)).collect();
        for &t in &tris {
            let one = Bvh::build(vec![t]);
            let hit = rays
                .iter()
                .any(|&(d, l)| one.any_hit(c.q.from, d, 0.0, l, None));
            match c.cone.may_hit_triangle(t) {
                true => {
                    maybe += 1;
                    maybe_hit += u32::from(hit);
                }
                false => {
                    empty += 1;
                    wrong += u32::from(hit);
                }
            }
        }
        // The whole soup through the BVH, then its first few triangles
        // (some soups are empty to the query).
        for k in [24, 4, 2, 1] {
            let bvh = Bvh::build(tris[..k].to_vec());
            if !bvh.may_block(&c.cone, None) {
                soups_empty += 1;
                let hit = rays
                    .iter()
                    .any(|&(d, l)| bvh.any_hit(c.q.from, d, 0.0, l, None));
                soups_wrong += u32::from(hit);
            }
        }
    }
    println!(
        "triangles: {empty} empty ({wrong} hit by a ray), {maybe} maybe ({maybe_hit} hit); soups: {soups_empty} empty ({soups_wrong} hit)"
    );
    assert_eq!((wrong, soups_wrong), (0, 0));
    // Not vacuous: the query rules many out.
    assert!(empty > 1000 && soups_empty > 50, "{empty} {soups_empty}");
}

/// A receiver on a floor of two triangles, a disk light or a sun above.
fn floor_query(normal: Vec3, light: LightAt) -> (Bvh, Query) {
    let p = |x: f32, z: f32| Vec3::new(x, 0.0, z);
    let bvh = Bvh::build(vec![
        [p(-5.0, -5.0), p(5.0, 5.0), p(5.0, -5.0)],
        [p(-5.0, -5.0), p(-5.0, 5.0), p(5.0, 5.0)],
    ]);
    let lift = 1e-4;
    let q = Query {
        from: Vec3::new(0.5, 0.0, -0.5) + lift * normal,
        normal,
        lift,
        pixel: 7,
        light,
    };
    (bvh, q)
}

/// V, rays and the horizon flag through the BVH, the receiver on
/// triangle 0.
fn through(bvh: &Bvh, q: &Query, emitter: Emitter) -> crate::reference::area::Seen {
    let may_block = |cone: &RayCone| bvh.may_block(cone, Some(0));
    let blocked = |d: Vec3, t: f32| bvh.any_hit(q.from, d, 0.0, t, Some(0));
    visibility(
        emitter,
        q,
        AreaSampling::DEFAULT,
        q.lift,
        may_block,
        blocked,
    )
}

#[test]
fn a_floor_under_an_open_sky_is_lit_without_a_ray() {
    let disk = Emitter::Disk { radius: 0.5 };
    let sun = Emitter::of(LightSize::AngularRadiusDeg(3.0)).unwrap();
    let lights = [
        (disk, LightAt::Position(Vec3::new(1.0, 2.0, 0.5))),
        (disk, LightAt::Position(Vec3::new(-3.0, 1.0, 2.0))),
        (
            sun,
            LightAt::Direction(Vec3::new(0.2, 1.0, -0.4).normalize()),
        ),
    ];
    for (emitter, light) in lights {
        let (bvh, q) = floor_query(Vec3::Y, light);
        // The other floor triangle, coplanar, is culled by the horizon.
        assert!(!bvh.may_block(&q.cone(emitter), Some(0)));
        let seen = through(&bvh, &q, emitter);
        assert_eq!((seen.visibility, seen.rays), (1.0, 0));
        assert!(!seen.horizon_clipped);
    }
}

#[test]
fn an_emitter_partly_below_the_horizon_is_flagged_and_sampled() {
    // A disk of radius 0.5 whose centre is 0.2 above the floor, 3 away:
    // below the horizon by the share beyond the chord at −0.2 / 0.5 (the
    // disk faces the receiver, tilted by a hair: nearly exact).
    let (bvh, q) = floor_query(Vec3::Y, LightAt::Position(Vec3::new(3.5, 0.2, -0.5)));
    let seen = through(&bvh, &q, Emitter::Disk { radius: 0.5 });
    assert!(seen.horizon_clipped);
    assert_eq!(seen.rays, AreaSampling::DEFAULT.rays());
    let t = 0.2f32 / 0.5;
    let above = 1.0 - ((t.acos() - t * (1.0 - t * t).sqrt()) / std::f32::consts::PI);
    assert!((seen.visibility - above).abs() < 0.03, "{seen:?}, {above}");
    // Just above the horizon: not flagged, and nothing to cast.
    let (bvh, q) = floor_query(Vec3::Y, LightAt::Position(Vec3::new(3.5, 0.6, -0.5)));
    let seen = through(&bvh, &q, Emitter::Disk { radius: 0.5 });
    assert!(!seen.horizon_clipped);
    assert_eq!((seen.visibility, seen.rays), (1.0, 0));
}

#[test]
fn a_ball_touching_the_cone_is_kept_and_one_clear_of_it_is_not() {
    let cone = RayCone::new(Vec3::ZERO, Vec3::Y, 0.0, Vec3::Y, 0.1, 2.0);
    // At height 1 the cone's radius is tan 0.1 ≈ 0.1003 (its side is
    // cos 0.1 of that from a point on the axis's perpendicular).
    let side = 0.1f32.tan();
    let ball = |x: f32, y: f32, r: f32| cone.may_touch_ball(Vec3::new(x, y, 0.0), r);
    assert!(ball(side + 0.09, 1.0, 0.1));
    assert!(!ball(side + 0.11, 1.0, 0.1));
    // Behind the apex and beyond the end.
    assert!(!ball(0.0, -0.2, 0.1));
    assert!(ball(0.0, -0.09, 0.1));
    assert!(!ball(0.0, 2.2, 0.1));
    assert!(ball(0.0, 2.09, 0.1));
}

/// A sheet a hair above the rays' start (one shadow offset) hides the
/// whole emitter: the horizon cull must keep it, and it does not keep
/// what is below the start by more than half an offset.
#[test]
fn a_sheet_a_hair_above_the_receiver_is_kept() {
    let light = LightAt::Position(Vec3::new(1.0, 2.0, 0.5));
    let disk = Emitter::Disk { radius: 0.5 };
    let (_, q) = floor_query(Vec3::Y, light);
    let sheet = |y: f32| {
        let p = |x: f32, z: f32| Vec3::new(x, y, z);
        [p(-5.0, -5.0), p(5.0, -5.0), p(0.0, 5.0)]
    };
    let cone = q.cone(disk);
    let above = q.from.y + q.lift;
    assert!(cone.may_hit_triangle(sheet(above)));
    assert!(!cone.may_hit_triangle(sheet(q.from.y - 0.6 * q.lift)));
    // Through the BVH, the receiver on the floor's triangle 0: the sheet
    // blocks every ray.
    let bvh = Bvh::build(vec![sheet(0.0), sheet(above)]);
    let seen = through(&bvh, &q, disk);
    assert_eq!(
        (seen.visibility, seen.rays),
        (0.0, AreaSampling::DEFAULT.rays())
    );
}
