//! A cascade's receivers (lesson 09): the surfaces whose pixels read its
//! map. A surface reads cascade `i` if the camera sees it and its view
//! depth picks cascade `i` (`select_cascade` in `csm.wgsl`), or blends it
//! in from the band at the back of the cascade in front (`csm_visibility`).
//! That is a convex region: the camera's frustum between two planes of
//! constant view depth ([`read_depths`]), inside the scene's bounds
//! ([`Region`]). An object is a receiver of the cascade if its box meets
//! the region; the part of it that counts is its box clipped to the
//! region's box. [`super::caster_culling`] decides from them which casters
//! the cascade draws.

use common::glam::{DMat4, DVec2, DVec3};

use super::cascades::{box_corners, Cascade};
use crate::lesson_05::frustum::frustum_planes;

/// The camera's frustum is widened by this share on every side: the
/// runner moves the image by 1/16 pixel (`--fragile`), and f32 rounds.
const FRUSTUM_SLACK: f64 = 0.01;

/// An axis-aligned box; empty when `lo > hi` on some axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub lo: DVec3,
    pub hi: DVec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        lo: DVec3::INFINITY,
        hi: DVec3::NEG_INFINITY,
    };

    pub fn around(points: impl IntoIterator<Item = DVec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, |b, p| Aabb {
            lo: b.lo.min(p),
            hi: b.hi.max(p),
        })
    }

    /// The intersection.
    pub fn meet(self, o: Aabb) -> Aabb {
        Aabb {
            lo: self.lo.max(o.lo),
            hi: self.hi.min(o.hi),
        }
    }

    pub fn is_empty(self) -> bool {
        self.lo.cmpgt(self.hi).any()
    }

    pub fn corners(self) -> [DVec3; 8] {
        box_corners(self.lo, self.hi)
    }

    /// Its extent across the light (x and y in light view space).
    pub fn across(self) -> Rect {
        Rect {
            lo: self.lo.truncate(),
            hi: self.hi.truncate(),
        }
    }
}

/// A rectangle across the light (x and y in light view space); empty when
/// `lo > hi` on some axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub lo: DVec2,
    pub hi: DVec2,
}

impl Rect {
    pub fn meet(self, o: Rect) -> Rect {
        Rect {
            lo: self.lo.max(o.lo),
            hi: self.hi.min(o.hi),
        }
    }

    /// The smallest rectangle holding both.
    pub fn join(self, o: Rect) -> Rect {
        Rect {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    pub fn grow(self, by: f64) -> Rect {
        Rect {
            lo: self.lo - by,
            hi: self.hi + by,
        }
    }

    pub fn is_empty(self) -> bool {
        self.lo.cmpgt(self.hi).any()
    }
}

/// What the lit pass sees: its camera (`view_proj`, origin-relative, and
/// `eye`), and the view axis `forward` its cascades were split along.
/// The runner's world-locked probe draws one frame's view with the next
/// frame's cascades, so the two need not be the same camera.
#[derive(Clone, Copy, Debug)]
pub struct LitView {
    pub view_proj: DMat4,
    pub eye: DVec3,
    pub forward: DVec3,
}

/// The view depths at which cascade `i` of `fit` is read: its slice; from
/// the blend band at the back of the cascade in front (a share `band` of
/// it, `csm_visibility`); and, for the last, beyond the last split
/// (`select_cascade`). The first starts at −∞ (the near plane cuts it).
/// Each end moves out by more than the shader's f32 depth can be off.
pub fn read_depths(fit: &[Cascade], i: usize, band: f64) -> (f64, f64) {
    let near = match i.checked_sub(1).map(|j| fit[j]) {
        Some(c) => c.far - band * (c.far - c.near),
        None => f64::NEG_INFINITY,
    };
    let far = if i + 1 == fit.len() {
        f64::INFINITY
    } else {
        fit[i].far
    };
    let slack = |d: f64| 1e-3 + 1e-5 * d.abs();
    (near - slack(near), far + slack(far))
}

/// The part of the world whose surfaces read one cascade: half-spaces
/// `(n, d)`, n·p + d ≥ 0 inside (the camera's frustum, widened; the view
/// depths; the scene's box), and the box around their intersection.
#[derive(Clone, Debug)]
pub struct Region {
    pub planes: Vec<(DVec3, f64)>,
    pub bounds: Aabb,
    /// The camera's eye.
    pub eye: DVec3,
    tolerance: f64,
}

impl Region {
    /// What `view` sees between view depths `near` and `far` (either may
    /// be infinite), inside `scene`; `tolerance` is a length far below
    /// anything the scene resolves.
    pub fn new(view: &LitView, near: f64, far: f64, scene: Aabb, tolerance: f64) -> Region {
        // |x|, |y| ≤ (1 + s)·w and −s·w ≤ z ≤ (1 + s)·w in clip space.
        let s = FRUSTUM_SLACK;
        let mut widen = DMat4::from_diagonal((1.0 / (1.0 + s), 1.0 / (1.0 + s), 1.0, 1.0).into());
        widen.z_axis.z = 1.0 / (1.0 + 2.0 * s);
        widen.w_axis.z = s / (1.0 + 2.0 * s);
        let mut planes = frustum_planes(widen * view.view_proj);
        let (f, at) = (view.forward, view.forward.dot(view.eye));
        if near.is_finite() {
            planes.push((f, -at - near)); // f·p − f·eye ≥ near
        }
        if far.is_finite() {
            planes.push((-f, at + far));
        }
        for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
            planes.push((axis, -axis.dot(scene.lo) + tolerance));
            planes.push((-axis, axis.dot(scene.hi) + tolerance));
        }
        let bounds = Aabb::around(vertices(&planes, tolerance));
        Region {
            planes,
            bounds,
            eye: view.eye,
            tolerance,
        }
    }

    /// Whether box `b` lies wholly outside one of the planes.
    pub fn misses(&self, b: Aabb) -> bool {
        self.planes.iter().any(|&(n, d)| {
            // The corner farthest along n.
            let p = DVec3::select(n.cmpge(DVec3::ZERO), b.hi, b.lo);
            n.dot(p) + d < -self.tolerance
        })
    }

    /// The objects whose boxes meet the region, seen through `light`.
    /// `boxes`: each object's world box and light-space box.
    pub fn receivers(
        &self,
        light: DMat4,
        boxes: impl Iterator<Item = (Aabb, Aabb)>,
    ) -> Vec<Receiver> {
        boxes
            .enumerate()
            .filter_map(|(index, (w, l))| {
                let clipped = w.meet(self.bounds);
                if clipped.is_empty() || self.misses(w) {
                    return None;
                }
                let seen = clipped.corners().map(|p| light.transform_point3(p));
                let part = Aabb::around(seen).meet(l);
                let outline = convex_hull(seen.map(|p| p.truncate()));
                (!part.is_empty()).then_some(Receiver {
                    index,
                    part,
                    outline,
                })
            })
            .collect()
    }
}

/// An object that receives in a region, and where: its world box clipped
/// to the region's box, seen from the light.
#[derive(Clone, Debug)]
pub struct Receiver {
    pub index: usize,
    /// The light-space box of that part, inside the object's own.
    pub part: Aabb,
    /// The outline of that part across the light (a convex polygon,
    /// counter-clockwise): a long slice of ground seen at an angle is a
    /// thin parallelogram, whose box is mostly empty.
    pub outline: Vec<DVec2>,
}

impl Receiver {
    /// Whether the part's box and outline both meet rectangle `r`.
    pub fn meets(&self, r: Rect) -> bool {
        if self.part.across().meet(r).is_empty() {
            return false;
        }
        // A separating axis among the outline's edges: r wholly outside
        // one of them (a segment's two sides, for a flat part seen edge-on).
        let n = self.outline.len();
        !(0..n).any(|k| {
            let (a, b) = (self.outline[k], self.outline[(k + 1) % n]);
            let out = DVec2::new(b.y - a.y, a.x - b.x);
            let nearest = DVec2::select(out.cmpge(DVec2::ZERO), r.lo, r.hi);
            out.dot(nearest - a) > 0.0
        })
    }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone
/// chain).
fn convex_hull<const N: usize>(mut points: [DVec2; N]) -> Vec<DVec2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let turn = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * N);
    for pass in [
        &points[..],
        &points.iter().rev().copied().collect::<Vec<_>>(),
    ] {
        let start = hull.len();
        for &p in pass.iter() {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// The corners of the convex region the half-spaces `planes` bound: every
/// point where three of the planes meet that lies inside all of them
/// (none when the region is empty). The region is bounded (the scene's
/// box is among them), so its box is the box of these points.
fn vertices(planes: &[(DVec3, f64)], tolerance: f64) -> Vec<DVec3> {
    let mut out = Vec::new();
    let n = planes.len();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let [(a, da), (b, db), (c, dc)] = [planes[i], planes[j], planes[k]];
                let det = a.dot(b.cross(c));
                if det.abs() < 1e-12 {
                    continue; // two of them parallel: no single point
                }
                let p = -(da * b.cross(c) + db * c.cross(a) + dc * a.cross(b)) / det;
                if planes.iter().all(|&(m, e)| m.dot(p) + e >= -tolerance) {
                    out.push(p);
                }
            }
        }
    }
    out
}

/// A cascade's receivers in a grid across the light, so that a caster is
/// tested against those near its footprint, not every receiver: a city of
/// boxes would otherwise cost the square of its size per frame.
pub struct Grid<'a> {
    receivers: &'a [Receiver],
    lo: DVec2,
    cell: DVec2,
    side: usize,
    /// Per cell, the receivers whose boxes touch it.
    cells: Vec<Vec<usize>>,
}

impl<'a> Grid<'a> {
    pub fn new(receivers: &'a [Receiver]) -> Grid<'a> {
        let all = Aabb::around(receivers.iter().flat_map(|r| [r.part.lo, r.part.hi]));
        let side = ((receivers.len() as f64).sqrt().ceil() as usize).clamp(1, 64);
        let (lo, size) = (all.lo.truncate(), (all.hi - all.lo).truncate());
        let cell = (size / side as f64).max(DVec2::splat(1e-9));
        let mut grid = Grid {
            receivers,
            lo,
            cell,
            side,
            cells: vec![Vec::new(); side * side],
        };
        for (k, r) in receivers.iter().enumerate() {
            for c in grid.cells_of(r.part.across()) {
                grid.cells[c].push(k);
            }
        }
        grid
    }

    /// The cells `r` touches (none when it misses them all).
    fn cells_of(&self, r: Rect) -> Vec<usize> {
        let at = |p: DVec2| (p - self.lo) / self.cell;
        let (a, b) = (at(r.lo), at(r.hi));
        let side = DVec2::splat(self.side as f64);
        let misses = b.cmplt(DVec2::ZERO).any() || a.cmpgt(side).any();
        if self.receivers.is_empty() || misses || a.is_nan() || b.is_nan() {
            return Vec::new();
        }
        let cell = |p: DVec2| p.floor().clamp(DVec2::ZERO, side - 1.0);
        let (a, b) = (cell(a), cell(b));
        let (x, y) = (
            (a.x as usize)..=(b.x as usize),
            (a.y as usize)..=(b.y as usize),
        );
        y.flat_map(|j| x.clone().map(move |i| j * self.side + i))
            .collect()
    }

    /// The receivers in the cells `r` touches (one may come more than
    /// once).
    pub fn near(&self, r: Rect) -> impl Iterator<Item = &Receiver> + '_ {
        let cells = self.cells_of(r);
        cells
            .into_iter()
            .flat_map(move |c| self.cells[c].iter().map(|&k| &self.receivers[k]))
    }
}
