//! Unit tests of `common::reference::area`: the sampled visible fraction
//! against the exact area of a disk cut by a plane.

use super::*;

/// The share of the unit disk beyond the chord at signed distance `t` from
/// its centre: (acos t − t √(1 − t²)) / π, 0 beyond 1, 1 below −1.
fn cap_fraction(t: f32) -> f32 {
    let t = t.clamp(-1.0, 1.0) as f64;
    ((t.acos() - t * (1.0 - t * t).sqrt()) / std::f64::consts::PI) as f32
}

/// A disk light of radius 0.5 at (0, 2, 0), seen from points on the floor;
/// an occluding half-space through the point, tilted by `tilt` (radians)
/// out of the plane that holds the direction to the light: its exact
/// visible fraction, and the sampled one with `sampling`.
fn half_space_case(x: f32, tilt: f32, pixel: u32, sampling: AreaSampling) -> (f32, f32, u64) {
    let (c, r) = (Vec3::new(0.0, 2.0, 0.0), 0.5);
    let p = Vec3::new(x, 0.0, 0.3);
    let w = (c - p).normalize();
    let side = w.cross(Vec3::Z).normalize();
    // The occluder's normal: across the direction to the light, tilted toward it.
    let m = (side * tilt.cos() + w * tilt.sin()).normalize();
    let blocked = |dir: Vec3, _t: f32| dir.dot(m) > 0.0;
    let q = Query {
        from: p,
        normal: Vec3::Y,
        pixel,
        light: LightAt::Position(c),
    };
    let (v, rays) = visibility(Emitter::Disk { radius: r }, &q, sampling, 0.0, blocked);
    // Exact: disk point c + r(a u + b v) is hidden where (c − p)·m + r (a, b)·m⊥ > 0.
    let m_perp = m - m.dot(w) * w;
    let t = -(c - p).dot(m) / (r * m_perp.length());
    (1.0 - cap_fraction(t), v, rays)
}

#[test]
fn a_half_space_hides_the_exact_share_of_a_disk() {
    let mut worst = 0.0f32;
    let mut sum = 0.0f32;
    let mut n = 0;
    for (i, x) in [-0.4f32, 0.0, 0.25, 0.6].into_iter().enumerate() {
        for (j, tilt) in [-0.15f32, -0.05, 0.0, 0.08, 0.2].into_iter().enumerate() {
            let (exact, v, _) = half_space_case(x, tilt, (i * 7 + j) as u32, AreaSampling::DEFAULT);
            worst = worst.max((v - exact).abs());
            sum += (v - exact).abs();
            n += 1;
        }
    }
    // 256 stratified rays: a straight edge crosses about 2·16 strata, each
    // off by at most its area (1/256), in both directions at random.
    assert!(worst < 0.02, "worst |V − exact| = {worst}");
    assert!(
        sum / (n as f32) < 0.008,
        "mean |V − exact| = {}",
        sum / n as f32
    );
}

#[test]
fn four_times_the_rays_brings_the_answer_closer() {
    let err = |s: AreaSampling| {
        (0..40)
            .map(|k| {
                let (exact, v, _) = half_space_case(0.1, -0.2 + 0.01 * k as f32, k, s);
                (v - exact).abs()
            })
            .sum::<f32>()
            / 40.0
    };
    let (n, n4) = (
        err(AreaSampling::DEFAULT),
        err(AreaSampling::DEFAULT.times_four()),
    );
    assert!(n4 < 0.6 * n, "N: {n}, 4N: {n4}");
}

#[test]
fn the_tangent_plane_hides_what_is_below_it() {
    // Nothing blocks; the receiver's normal is across the direction to the
    // light, so half the disk is below its tangent plane.
    let c = Vec3::new(0.0, 2.0, 0.0);
    let q = Query {
        from: Vec3::ZERO,
        normal: Vec3::X,
        pixel: 3,
        light: LightAt::Position(c),
    };
    let (v, _) = visibility(
        Emitter::Disk { radius: 0.5 },
        &q,
        AreaSampling::DEFAULT,
        0.0,
        |_, _| false,
    );
    assert!((v - 0.5).abs() < 0.02, "v = {v}");
}

#[test]
fn rays_go_only_where_the_pilot_disagrees() {
    let s = AreaSampling::DEFAULT;
    let pilot = s.pilot_rays();
    let full = pilot + (s.side * s.side) as u64;
    // Far outside the occluder: lit by every pilot ray.
    let (exact, v, rays) = half_space_case(0.0, -1.2, 1, s);
    assert_eq!((exact, v, rays), (1.0, 1.0, pilot));
    // On the edge: the full pattern.
    let (_, v, rays) = half_space_case(0.0, 0.0, 1, s);
    assert!(v > 0.3 && v < 0.7, "v = {v}");
    assert_eq!(rays, full);
}

#[test]
fn a_cone_of_directions_is_cut_in_half_by_a_plane_along_its_axis() {
    let w = Vec3::new(0.3, 1.0, -0.2).normalize();
    let m = w.cross(Vec3::X).normalize();
    let emitter = Emitter::of(LightSize::AngularRadiusDeg(5.0)).unwrap();
    let (mut sum, n) = (0.0, 32);
    for pixel in 0..n {
        let q = Query {
            from: Vec3::ZERO,
            normal: Vec3::Y,
            pixel,
            light: LightAt::Direction(w),
        };
        let (v, _) = visibility(emitter, &q, AreaSampling::DEFAULT, 0.0, |d, t| {
            assert!(t.is_infinite());
            // Every ray is inside the cone.
            assert!(d.dot(w) >= 5f32.to_radians().cos() - 1e-6);
            d.dot(m) > 0.0
        });
        sum += v;
    }
    let mean = sum / n as f32;
    assert!((mean - 0.5).abs() < 0.01, "mean v = {mean}");
}

#[test]
fn a_hard_light_has_no_emitter() {
    assert!(Emitter::of(LightSize::HARD).is_none());
    assert!(Emitter::of(LightSize::AngularRadiusDeg(0.0)).is_none());
    assert!(Emitter::of(LightSize::Radius(0.1)).is_some());
}
