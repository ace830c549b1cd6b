//! Unit tests of `common::reference::bvh` (kept apart so the module stays short).

use super::*;

/// A tiny deterministic generator (xorshift), so tests need no crate.
struct Rng(u64);
impl Rng {
    fn f(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn v(&mut self, scale: f32) -> Vec3 {
        Vec3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5) * scale
    }
}

fn prepared(tris: &[[Vec3; 3]]) -> Vec<PreparedTri> {
    tris.iter().map(PreparedTri::new).collect()
}

fn brute_closest(tris: &[PreparedTri], o: Vec3, d: Vec3, t_max: f32) -> Option<Hit> {
    let (o, d) = (Vec3A::from(o), Vec3A::from(d));
    let mut best: Option<Hit> = None;
    for (i, t) in tris.iter().enumerate() {
        let limit = best.map_or(t_max, |b| b.t);
        if let Some(t) = t.intersect(o, d, 0.0, limit) {
            if best.is_none_or(|b| (t, i as u32) < (b.t, b.tri)) {
                best = Some(Hit { tri: i as u32, t });
            }
        }
    }
    best
}

fn brute_any(tris: &[PreparedTri], o: Vec3, d: Vec3, t0: f32, t1: f32, skip: Option<u32>) -> bool {
    let (o, d) = (Vec3A::from(o), Vec3A::from(d));
    tris.iter()
        .enumerate()
        .any(|(i, t)| Some(i as u32) != skip && t.intersect(o, d, t0, t1).is_some())
}

/// A closed UV sphere of radius `r`: every ray from inside must hit it.
pub(crate) fn sphere(r: f32, rings: u32, segments: u32) -> Vec<[Vec3; 3]> {
    let p = |i: u32, j: u32| {
        let th = std::f32::consts::PI * i as f32 / rings as f32;
        let ph = std::f32::consts::TAU * (j % segments) as f32 / segments as f32;
        Vec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()) * r
    };
    let mut out = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            if i != 0 {
                out.push([a, c, d]);
            }
            if i != rings - 1 {
                out.push([a, b, c]);
            }
        }
    }
    out
}

fn compare_with_brute_force(tris: Vec<[Vec3; 3]>, rays: &[(Vec3, Vec3)], t_max: f32) -> usize {
    let soup = prepared(&tris);
    let bvh = Bvh::build(tris);
    let mut hits = 0;
    for (k, &(o, d)) in rays.iter().enumerate() {
        let got = bvh.closest_hit(o, d, t_max);
        let want = brute_closest(&soup, o, d, t_max);
        match (got, want) {
            (Some(g), Some(w)) => {
                assert_eq!(g.tri, w.tri, "ray {k}: {o} {d}");
                assert!(
                    (g.t - w.t).abs() <= 1e-5 * w.t.abs().max(1.0),
                    "ray {k}: t {} vs {}",
                    g.t,
                    w.t
                );
                hits += 1;
            }
            (None, None) => {}
            _ => panic!("ray {k} ({o}, {d}): bvh {got:?}, brute force {want:?}"),
        }
        let skip = want.map(|w| w.tri);
        for (t0, t1) in [(0.0, t_max), (0.0, 0.7 * t_max), (1e-3, f32::INFINITY)] {
            assert_eq!(
                bvh.any_hit(o, d, t0, t1, skip),
                brute_any(&soup, o, d, t0, t1, skip),
                "ray {k}: any_hit over [{t0}, {t1}] skipping {skip:?}"
            );
        }
    }
    hits
}

#[test]
fn bvh_matches_brute_force_on_random_triangles() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut tris: Vec<[Vec3; 3]> = (0..3000)
        .map(|_| {
            let c = rng.v(20.0);
            [c + rng.v(1.5), c + rng.v(1.5), c + rng.v(1.5)]
        })
        .collect();
    // Degenerate ones too (welded corners, collinear slivers): the tree must cope.
    for _ in 0..20 {
        let (a, b) = (rng.v(20.0), rng.v(20.0));
        tris.extend([[a, a, b], [a, b, (a + b) * 0.5], [a, a, a]]);
    }
    let mut rays: Vec<(Vec3, Vec3)> = (0..3000)
        .map(|_| (rng.v(30.0), rng.v(2.0).normalize()))
        .collect();
    // Axis-aligned rays, including -0.0 components (a straight-down light).
    for k in 0..200 {
        let d = [
            Vec3::X,
            Vec3::NEG_Y,
            Vec3::Z,
            -Vec3::Y,
            Vec3::new(-0.0, 1.0, -0.0),
        ][k % 5];
        rays.push((rng.v(20.0), d));
    }
    let hits = compare_with_brute_force(tris, &rays, 100.0);
    assert!(hits > 500, "too few hits ({hits}) for a meaningful test");
}

#[test]
fn bvh_matches_brute_force_on_closed_sphere() {
    let tris = sphere(2.0, 40, 64);
    assert!(tris.len() > 4000);
    let mut rng = Rng(12345);
    let mut rays: Vec<(Vec3, Vec3)> = (0..1500)
        .map(|_| (rng.v(2.0), rng.v(2.0).normalize()))
        .collect();
    rays.extend((0..1500).map(|_| (rng.v(10.0), rng.v(2.0).normalize())));
    compare_with_brute_force(tris.clone(), &rays, 100.0);
    // Closed: every ray from inside hits, and any_hit sees the shell.
    let bvh = Bvh::build(tris);
    for &(o, d) in &rays[..1500] {
        assert!(
            bvh.closest_hit(o * 0.5, d, f32::INFINITY).is_some(),
            "escaped from {o} along {d}"
        );
        assert!(bvh.any_hit(o * 0.5, d, 0.0, f32::INFINITY, None));
    }
}

#[test]
fn rays_through_shared_edges_and_vertices_do_not_slip_through() {
    // A 2x2 quad split into triangles; aim exactly at the diagonal and the centre vertex.
    let (a, b, c, d) = (
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(-1.0, 0.0, 1.0),
    );
    let m = Vec3::ZERO;
    let bvh = Bvh::build(vec![[a, b, m], [b, c, m], [c, d, m], [d, a, m]]);
    for p in [
        Vec3::ZERO,
        Vec3::new(0.5, 0.0, 0.5),
        Vec3::new(-0.3, 0.0, 0.3),
        Vec3::new(0.0, 0.0, 0.7),
    ] {
        for dir in [Vec3::NEG_Y, Vec3::Y, Vec3::new(0.3, -1.0, 0.2).normalize()] {
            let o = p - dir * 3.0;
            let hit = bvh.closest_hit(o, dir, 10.0);
            assert!(
                hit.is_some_and(|h| (h.t - 3.0).abs() < 1e-5),
                "slipped through at {p} along {dir}"
            );
        }
    }
}

#[test]
fn out_of_range_vertices_are_refused_not_a_panic() {
    let unit = [Vec3::ZERO, Vec3::X, Vec3::Y];
    for big in [1e20, f32::INFINITY, f32::NAN, -2.0 * MAX_COORD] {
        let mut tris = sphere(1.0, 8, 16);
        let at = tris.len();
        tris.push([Vec3::ZERO, Vec3::new(big, 0.0, 0.0), Vec3::Z]);
        tris.push(unit);
        let e = Bvh::try_build(tris).err().expect("refused");
        assert!(
            e.to_string().contains(&format!("triangle {at} ")),
            "{big}: {e}"
        );
    }
    // At the bound, a tiny triangle beside a huge one builds and is found.
    let tiny = unit.map(|v| v * 1e-6 + Vec3::splat(0.5));
    let big = [
        Vec3::splat(-MAX_COORD),
        Vec3::new(MAX_COORD, -MAX_COORD, -MAX_COORD),
        Vec3::new(-MAX_COORD, MAX_COORD, -MAX_COORD),
    ];
    let bvh = Bvh::try_build(vec![big, tiny]).expect("builds");
    let hit = bvh.closest_hit(Vec3::new(0.5 + 2e-7, 0.5 + 2e-7, 1.0), Vec3::NEG_Z, 10.0);
    assert_eq!(hit.map(|h| h.tri), Some(1));
}

#[test]
fn duplicate_triangles_go_in_once_and_report_the_first() {
    let t = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let mut tris = vec![[
        Vec3::new(5.0, 5.0, 5.0),
        Vec3::new(6.0, 5.0, 5.0),
        Vec3::new(5.0, 6.0, 5.0),
    ]];
    // 200k copies (some with their corners rotated): seconds, not minutes.
    tris.extend((0..200_000).map(|k| if k % 2 == 0 { t } else { [t[1], t[2], t[0]] }));
    let start = std::time::Instant::now();
    let bvh = Bvh::build(tris);
    assert!(
        start.elapsed().as_secs_f64() < 10.0,
        "{:?}",
        start.elapsed()
    );
    assert_eq!(bvh.len(), 2);
    let hit = bvh.closest_hit(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z, 10.0);
    assert_eq!(hit.map(|h| h.tri), Some(1));
    assert!(!bvh.any_hit(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z, 0.0, 10.0, Some(1)));
}

#[test]
fn empty_bvh_hits_nothing() {
    let bvh = Bvh::build(Vec::new());
    assert!(bvh.is_empty());
    assert_eq!(bvh.closest_hit(Vec3::ZERO, Vec3::X, f32::INFINITY), None);
    assert!(!bvh.any_hit(Vec3::ZERO, Vec3::X, 0.0, f32::INFINITY, None));
}

#[test]
fn single_triangle_front_back_skip_and_range() {
    let bvh = Bvh::build(vec![[
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ]]);
    assert_eq!(bvh.len(), 1);
    let p = Vec3::new(0.25, 0.25, 0.0);
    // Front face (counter-clockwise seen from +Z) and back face both hit.
    assert_eq!(
        bvh.closest_hit(p + Vec3::Z * 2.0, Vec3::NEG_Z, 5.0),
        Some(Hit { tri: 0, t: 2.0 })
    );
    assert_eq!(
        bvh.closest_hit(p - Vec3::Z * 2.0, Vec3::Z, 5.0),
        Some(Hit { tri: 0, t: 2.0 })
    );
    // A ray that stops short, starts past it, or misses the triangle.
    assert_eq!(bvh.closest_hit(p + Vec3::Z * 2.0, Vec3::NEG_Z, 1.9), None);
    assert!(!bvh.any_hit(p + Vec3::Z * 2.0, Vec3::NEG_Z, 2.1, 5.0, None));
    assert_eq!(
        bvh.closest_hit(Vec3::new(0.8, 0.8, 1.0), Vec3::NEG_Z, 5.0),
        None
    );
    // Skipping the only triangle leaves nothing to hit.
    assert!(bvh.any_hit(p + Vec3::Z, Vec3::NEG_Z, 0.0, 5.0, None));
    assert!(!bvh.any_hit(p + Vec3::Z, Vec3::NEG_Z, 0.0, 5.0, Some(0)));
    // Very close to the origin: obvhs alone would skip boxes nearer than 1e-4.
    assert!(bvh.any_hit(p + Vec3::Z * 1e-5, Vec3::NEG_Z, 0.0, 1.0, None));
}
