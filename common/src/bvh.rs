//! A triangle BVH for the exact CPU reference: closest hit and any hit.
//!
//! The tree is the `obvhs` crate's compressed wide BVH (CWBVH, eight children
//! per node, SIMD box tests); we only add the triangle test and two guards:
//!
//! - obvhs skips boxes whose exit is closer than an absolute `1e-4` along the
//!   ray. We start the traversal ray `BACK_UP` behind the real origin, so
//!   nothing near the origin is skipped; the triangle test uses the real one.
//! - obvhs clamps `1/d` to `±1/f32::EPSILON`, and a `-0.0` component gets the
//!   wrong sign (the octant says "positive", the inverse says "negative") and
//!   misses every box. A straight-down light gives exactly such a ray, so we
//!   turn `-0.0` into `+0.0` and clamp `1/d` at `±1e30` instead.
//!
//! The triangle test is double-sided Möller–Trumbore. Its barycentric bounds
//! are widened by [`EDGE_EPSILON`] (relative to the triangle), so neighbours
//! overlap a hair and a ray through a shared edge hits at least one of them.

use glam::{Vec3, Vec3A};
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;

/// The BVH refuses a vertex beyond `±MAX_COORD` (or a non-finite one): obvhs
/// computes box areas in `f32`, and past about 1e19 they overflow and its
/// build indexes out of bounds. Validated scenes stay within
/// [`crate::limits::MAX_EXTENT`] of their origin, far inside this.
pub const MAX_COORD: f32 = 1e7;

/// Barycentric slack: shared edges overlap by this fraction of the triangle.
pub const EDGE_EPSILON: f32 = 1e-6;

/// How far behind the real origin the traversal ray starts (world units).
const BACK_UP: f32 = 1e-3;

/// A closest hit: the triangle (index into the input of [`Bvh::build`]) and
/// the distance along the ray (in units of `dir`'s length).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub tri: u32,
    pub t: f32,
}

/// A triangle prepared for Möller–Trumbore: one corner and two edges.
#[derive(Clone, Copy, Debug)]
struct PreparedTri {
    v0: Vec3A,
    e1: Vec3A,
    e2: Vec3A,
}

impl PreparedTri {
    fn new(t: &[Vec3; 3]) -> Self {
        let v0 = Vec3A::from(t[0]);
        Self {
            v0,
            e1: Vec3A::from(t[1]) - v0,
            e2: Vec3A::from(t[2]) - v0,
        }
    }

    /// Distance `t` in `[t_min, t_max]` where the ray crosses either face,
    /// or `None`.
    #[inline(always)]
    fn intersect(&self, o: Vec3A, d: Vec3A, t_min: f32, t_max: f32) -> Option<f32> {
        let p = d.cross(self.e2);
        let det = self.e1.dot(p);
        // Double-sided: any sign of det is a hit; 0 is parallel or degenerate.
        if det == 0.0 {
            return None;
        }
        let inv = 1.0 / det;
        let s = o - self.v0;
        let u = s.dot(p) * inv;
        let q = s.cross(self.e1);
        let v = d.dot(q) * inv;
        if u < -EDGE_EPSILON || v < -EDGE_EPSILON || u + v > 1.0 + EDGE_EPSILON {
            return None;
        }
        let t = self.e2.dot(q) * inv;
        (t >= t_min && t <= t_max).then_some(t)
    }
}

/// A BVH over a triangle soup. Triangles keep their input index.
pub struct Bvh {
    cwbvh: CwBvh,
    /// Triangles in BVH leaf order, so a leaf reads contiguous memory.
    tris: Vec<PreparedTri>,
    /// `ids[i]`: the input index of `tris[i]`.
    ids: Vec<u32>,
}

impl Bvh {
    /// Builds the tree (obvhs' "medium" preset: PLOC plus reinsertion).
    ///
    /// Panics with the message of [`Bvh::try_build`] for a vertex that is not
    /// finite or lies beyond [`MAX_COORD`]; a validated scene has none.
    pub fn build(tris: Vec<[Vec3; 3]>) -> Bvh {
        Bvh::try_build(tris).unwrap_or_else(|e| panic!("{e}"))
    }

    /// Builds the tree, or says which triangle has a vertex that is not
    /// finite or lies beyond [`MAX_COORD`] (obvhs would panic on it).
    pub fn try_build(tris: Vec<[Vec3; 3]>) -> anyhow::Result<Bvh> {
        let bad = |v: &Vec3| !(v.is_finite() && v.abs().max_element() <= MAX_COORD);
        if let Some(i) = tris.iter().position(|t| t.iter().any(bad)) {
            anyhow::bail!(
                "BVH: triangle {i} has a vertex that is not finite or lies beyond ±{MAX_COORD:e} ({:?}); the scene's limits should have refused it",
                tris[i]
            );
        }
        if tris.is_empty() {
            return Ok(Bvh {
                cwbvh: CwBvh::default(),
                tris: Vec::new(),
                ids: Vec::new(),
            });
        }
        let soup: Vec<Triangle> = tris
            .iter()
            .map(|t| Triangle {
                v0: t[0].into(),
                v1: t[1].into(),
                v2: t[2].into(),
            })
            .collect();
        let params = BvhBuildParams::medium_build();
        let mut cwbvh = build_cwbvh_from_tris(&soup, params, &mut Default::default());
        // Reorder so that leaf primitive i is triangle i.
        let ids = std::mem::take(&mut cwbvh.primitive_indices);
        let prepared = ids
            .iter()
            .map(|&i| PreparedTri::new(&tris[i as usize]))
            .collect();
        cwbvh.primitive_indices = (0..ids.len() as u32).collect();
        Ok(Bvh {
            cwbvh,
            tris: prepared,
            ids,
        })
    }

    /// Number of triangles in the tree.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// The traversal ray, backed up by `BACK_UP` and with a safe inverse,
    /// and how far it was backed up (in units of `d`); `None` for a
    /// non-finite or zero ray.
    fn traversal_ray(o: Vec3A, d: Vec3A, t_max: f32) -> Option<(Ray, f32)> {
        let back = BACK_UP / d.length();
        if !(o.is_finite() && d.is_finite() && back.is_finite()) {
            return None;
        }
        let mut ray = Ray::new(o - d * back, d, 0.0, t_max + back);
        let inv = |c: f32| {
            if c.abs() < 1e-30 {
                1e30_f32.copysign(c)
            } else {
                1.0 / c
            }
        };
        ray.inv_direction = Vec3A::new(inv(d.x), inv(d.y), inv(d.z));
        Some((ray, back))
    }

    /// The nearest triangle the ray crosses with `0 <= t <= t_max`.
    /// Equal distances go to the lower triangle index, so the answer does not
    /// depend on the tree's shape.
    pub fn closest_hit(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<Hit> {
        let (o, d) = (Vec3A::from(origin), sanitize(dir));
        let (ray, back) = Self::traversal_ray(o, d, t_max)?;
        let mut best: Option<Hit> = None;
        self.cwbvh.ray_traverse(ray, &mut RayHit::none(), |_, i| {
            let limit = best.map_or(t_max, |b| b.t);
            let Some(t) = self.tris[i].intersect(o, d, 0.0, limit) else {
                return f32::INFINITY;
            };
            let tri = self.ids[i];
            if best.is_none_or(|b| (t, tri) < (b.t, b.tri)) {
                best = Some(Hit { tri, t });
            }
            // Shrink the traversal ray, a hair long so that ties still get tested.
            (t + back) * (1.0 + 4.0 * f32::EPSILON)
        });
        best
    }

    /// Whether any triangle other than `skip_tri` crosses the ray with
    /// `t_min <= t <= t_max`. Use `t_max = f32::INFINITY` for an unbounded ray.
    pub fn any_hit(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
        skip_tri: Option<u32>,
    ) -> bool {
        let (o, d) = (Vec3A::from(origin), sanitize(dir));
        let Some((ray, _)) = Self::traversal_ray(o, d, t_max) else {
            return false;
        };
        let missed = self.cwbvh.ray_traverse_miss(ray, |_, i| {
            let hit = Some(self.ids[i]) != skip_tri
                && self.tris[i].intersect(o, d, t_min, t_max).is_some();
            // Anything below the ray's t_max stops the traversal.
            if hit {
                0.0
            } else {
                f32::INFINITY
            }
        });
        !missed
    }
}

/// `-0.0 + 0.0 == +0.0`: the octant test and the inverse then agree (see top).
fn sanitize(dir: Vec3) -> Vec3A {
    Vec3A::from(dir) + Vec3A::ZERO
}

#[cfg(test)]
pub(crate) mod tests {
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

    fn brute_any(
        tris: &[PreparedTri],
        o: Vec3,
        d: Vec3,
        t0: f32,
        t1: f32,
        skip: Option<u32>,
    ) -> bool {
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
}
