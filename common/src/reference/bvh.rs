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
//! Beside rays, [`Bvh::may_block`] asks whether anything might cross a
//! cone of rays (an area light's, [`crate::reference::cone`]), walking the
//! same tree's boxes.
//!
//! The triangle test is double-sided Möller–Trumbore. Its barycentric bounds
//! are widened by [`EDGE_EPSILON`] (relative to the triangle), so neighbours
//! overlap a hair and a ray through a shared edge hits at least one of them.

use glam::{Vec3, Vec3A};
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::cwbvh::{bvh2_to_cwbvh::bvh2_to_cwbvh, CwBvh};
use obvhs::ploc::PlocBuilder;
use obvhs::ray::{Ray, RayHit};
use obvhs::splits::split_aabbs_preset;
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;

use crate::reference::cone::RayCone;

/// The BVH refuses a vertex beyond `±MAX_COORD` (or a non-finite one): obvhs
/// computes box areas in `f32`, and past about 1e19 they overflow and its
/// build indexes out of bounds. Validated scenes stay within
/// [`crate::scene::limits::MAX_EXTENT`] of their origin, far inside this.
pub const MAX_COORD: f32 = 1e7;

/// Barycentric slack: shared edges overlap by this fraction of the triangle.
pub const EDGE_EPSILON: f32 = 1e-6;

/// How far behind the real origin the traversal ray starts (world units).
const BACK_UP: f32 = 1e-3;

/// The input index of the first copy of every distinct triangle, in order.
/// Linear time: one hash lookup per triangle.
fn first_copies(tris: &[[Vec3; 3]]) -> Vec<u32> {
    let mut seen = std::collections::HashSet::with_capacity(tris.len());
    let mut unique = Vec::with_capacity(tris.len());
    for (i, t) in tris.iter().enumerate() {
        let mut corners = t.map(|v| v.to_array().map(f32::to_bits));
        corners.sort_unstable();
        if seen.insert(corners) {
            unique.push(i as u32);
        }
    }
    unique
}

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

    /// The three corners.
    fn corners(&self) -> [Vec3; 3] {
        [self.v0, self.v0 + self.e1, self.v0 + self.e2].map(Vec3::from)
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
        // Exact duplicates (the same corners, in any order) go in once, as the
        // first of them: obvhs' PLOC merges only one of many equal boxes per
        // pass, so 200k copies of a triangle took minutes. A hit reports the
        // first copy, as the GPU's depth test (less) keeps the first drawn.
        let unique = first_copies(&tris);
        let soup: Vec<Triangle> = unique
            .iter()
            .map(|&i| &tris[i as usize])
            .map(|t| Triangle {
                v0: t[0].into(),
                v1: t[1].into(),
                v2: t[2].into(),
            })
            .collect();
        let params = BvhBuildParams::medium_build();
        let mut cwbvh = build_cwbvh(&soup, params);
        // Reorder so that leaf primitive i is triangle i.
        let ids: Vec<u32> = std::mem::take(&mut cwbvh.primitive_indices)
            .into_iter()
            .map(|k| unique[k as usize])
            .collect();
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

    /// Number of triangles in the tree (exact duplicates count once).
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

    /// Whether a triangle other than `skip_tri` might cross a ray of
    /// `cone` ([`RayCone`]: its tests are conservative, so `false` means
    /// that no ray of the cone leaving above its horizon can hit one).
    /// Walks obvhs' tree with its (outward-rounded) child boxes.
    pub fn may_block(&self, cone: &RayCone, skip_tri: Option<u32>) -> bool {
        if self.cwbvh.nodes.is_empty() {
            return false;
        }
        let mut stack = Vec::with_capacity(32);
        stack.push(0u32);
        while let Some(n) = stack.pop() {
            let node = &self.cwbvh.nodes[n as usize];
            for child in (0..8).filter(|&c| !node.is_child_empty(c)) {
                let b = node.child_aabb(child);
                if !cone.may_touch_box(b.min.into(), b.max.into()) {
                    continue;
                }
                if !node.is_leaf(child) {
                    stack.push(node.child_node_index(child));
                    continue;
                }
                let (first, count) = node.child_primitives(child);
                for i in first as usize..(first + count) as usize {
                    let i = self.cwbvh.primitive_indices[i] as usize;
                    if Some(self.ids[i]) != skip_tri
                        && cone.may_hit_triangle(self.tris[i].corners())
                    {
                        return true;
                    }
                }
            }
        }
        false
    }
}

/// `-0.0 + 0.0 == +0.0`: the octant test and the inverse then agree (see top).
fn sanitize(dir: Vec3) -> Vec3A {
    Vec3A::from(dir) + Vec3A::ZERO
}

/// obvhs's `build_cwbvh_from_tris` (0.4.0), step for step, without the
/// build timer it keeps for its own profiling: that timer reads
/// `std::time::Instant`, which a web page has not (the web build), and the
/// crate offers the steps for exactly this ("feel free to reimplement").
/// The same steps in the same order: the same tree.
fn build_cwbvh(triangles: &[Triangle], config: BvhBuildParams) -> CwBvh {
    let mut bvh2 = if config.pre_split {
        let mut largest_half_area = 0.0f32;
        let mut avg_area = 0.0;
        let mut aabbs: Vec<_> = (triangles.iter())
            .map(|tri| {
                let aabb = tri.aabb();
                let half_area = aabb.half_area();
                largest_half_area = half_area.max(largest_half_area);
                avg_area += half_area;
                aabb
            })
            .collect();
        let mut indices: Vec<u32> = (0..triangles.len() as u32).collect();
        avg_area /= triangles.len() as f32;
        split_aabbs_preset(
            &mut aabbs,
            &mut indices,
            triangles,
            avg_area,
            largest_half_area,
        );
        PlocBuilder::with_capacity(aabbs.len()).build(
            config.ploc_search_distance,
            &aabbs,
            indices,
            config.sort_precision,
            config.search_depth_threshold,
        )
    } else {
        PlocBuilder::with_capacity(triangles.len()).build(
            config.ploc_search_distance,
            triangles,
            (0..triangles.len() as u32).collect(),
            config.sort_precision,
            config.search_depth_threshold,
        )
    };
    bvh2.uses_spatial_splits = config.pre_split;
    ReinsertionOptimizer::default().run(&mut bvh2, config.reinsertion_batch_ratio, None);
    bvh2_to_cwbvh(&bvh2, config.max_prims_per_leaf.clamp(1, 3), true, false)
}

#[cfg(test)]
#[path = "unit_tests/bvh.rs"]
pub(crate) mod tests;
