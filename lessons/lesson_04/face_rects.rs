//! No map fuller than it must be (lesson 04): each cube face is rendered
//! only over the texels that a lookup from a visible receiver can read.
//!
//! For a light and a face: every receiver's bounds, cut to the camera's
//! frustum (what the camera can see of it), are projected into the face;
//! their texel rectangle, widened by the lookup's footprint (its taps'
//! reach in texels, one more for a bilinear tap, one for rounding) and
//! clamped to the face, is the face pass's scissor. A face no visible
//! receiver looks into is not drawn. Texels outside the rectangle keep the
//! pass's clear (1.0, "nothing here"), which no visible pixel reads: the
//! image is the same, bit for bit (`tests/lesson_04_face_rects.rs`). The
//! footprints are in [`super::footprint`].

use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat3, DVec3, DVec4, Mat4, Vec3};

use super::faces::{FaceRects, TexelRect, CUBE_FACES};
use super::footprint::{reach_texels, Footprint};

/// A receiver's world-space bounding box, origin-relative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub lo: DVec3,
    pub hi: DVec3,
}

/// The planes `n · p + d ≥ 0` (as `(n, d)`, n of unit length) of the
/// camera's frustum, from its view-projection, widened by `margin` in NDC
/// at the sides (pixel centres lie half a pixel inside). A plane with no
/// normal (the far plane of an infinite projection) is left out.
pub fn frustum_planes(view_proj: Mat4, margin: f64) -> Vec<DVec4> {
    let m = view_proj.as_dmat4();
    let r = |i| m.row(i);
    let side = 1.0 + margin;
    [
        r(0) + side * r(3),
        side * r(3) - r(0),
        r(1) + side * r(3),
        side * r(3) - r(1),
        r(2) + 1e-6 * r(3),
        r(3) * (1.0 + 1e-6) - r(2),
    ]
    .into_iter()
    .filter_map(|p| {
        let n = p.truncate().length();
        (n > 1e-12).then(|| p / n)
    })
    .collect()
}

/// The planes of a box, `n · p + d ≥ 0` inside.
fn box_planes(b: Bounds) -> [DVec4; 6] {
    [
        DVec4::new(1.0, 0.0, 0.0, -b.lo.x),
        DVec4::new(-1.0, 0.0, 0.0, b.hi.x),
        DVec4::new(0.0, 1.0, 0.0, -b.lo.y),
        DVec4::new(0.0, -1.0, 0.0, b.hi.y),
        DVec4::new(0.0, 0.0, 1.0, -b.lo.z),
        DVec4::new(0.0, 0.0, -1.0, b.hi.z),
    ]
}

/// How far inside the half-space `q` the point `p` lies (negative: outside).
fn side(q: DVec4, p: DVec3) -> f64 {
    q.truncate().dot(p) + q.w
}

/// The vertices of the intersection of the half-spaces `planes`: every
/// point where three of them meet inside all of them, `tol` allowed for
/// rounding. Empty when they leave nothing.
fn vertices(planes: &[DVec4], tol: f64) -> Vec<DVec3> {
    let mut corners = Vec::new();
    for (i, &a) in planes.iter().enumerate() {
        for (j, &b) in planes.iter().enumerate().skip(i + 1) {
            for &c in &planes[j + 1..] {
                let m = DMat3::from_cols(a.truncate(), b.truncate(), c.truncate()).transpose();
                if m.determinant().abs() < 1e-9 {
                    continue;
                }
                let p = m.inverse() * -DVec3::new(a.w, b.w, c.w);
                if p.is_finite() && planes.iter().all(|&q| side(q, p) >= -tol) {
                    corners.push(p);
                }
            }
        }
    }
    corners
}

/// Of `planes`, those that cut the convex hull of `points` (the others
/// leave all of it); `None` when one leaves none of it.
fn cutting(planes: &[DVec4], points: &[DVec3], tol: f64) -> Option<Vec<DVec4>> {
    let mut cut = Vec::new();
    for &q in planes {
        if points.iter().all(|&p| side(q, p) < -tol) {
            return None;
        }
        if points.iter().any(|&p| side(q, p) < -tol) {
            cut.push(q);
        }
    }
    Some(cut)
}

/// What the camera (its frustum `planes`) sees of a box, as the planes
/// that bound it and its vertices: every point where three of the planes
/// meet inside all of them. `None` when the camera sees none of it.
pub fn visible_part(b: Bounds, planes: &[DVec4]) -> Option<(Vec<DVec4>, Vec<DVec3>)> {
    let tol = 1e-7 * (1.0 + b.lo.abs().max(b.hi.abs()).max_element());
    let pick = |k: usize, bit: usize| if k >> bit & 1 == 0 { b.lo } else { b.hi };
    let corners: Vec<DVec3> = (0..8)
        .map(|k| DVec3::new(pick(k, 0).x, pick(k, 1).y, pick(k, 2).z))
        .collect();
    let mut bounding = box_planes(b).to_vec();
    bounding.extend(cutting(planes, &corners, tol)?);
    let v = vertices(&bounding, tol);
    (!v.is_empty()).then_some((bounding, v))
}

/// Where face `face` of a light at `light` sees `p`, in texels of a
/// `size`² face from its top left (the face pass's own projection,
/// [`super::faces::face_view_proj`]), or `None` behind the light.
pub fn face_texel(light: DVec3, face: usize, size: u32, p: DVec3) -> Option<[f64; 2]> {
    let (axis, up) = CUBE_FACES[face];
    let v = look_at_mat4(light, light + axis, up).transform_point3(p);
    let m = -v.z;
    // 90°: NDC x = x / m, and the face pass flips y (`face_view_proj`), so
    // its rows grow with the view's +y.
    (m > 0.0).then(|| {
        let n = f64::from(size);
        [(1.0 + v.x / m) * 0.5 * n, (1.0 + v.y / m) * 0.5 * n]
    })
}

// ANCHOR: face_rects
/// The scissor rectangle of every face of the light at `light` (origin-
/// relative), `size` texels a face, for the `receivers` the camera (its
/// frustum `planes` and `eye`) can see; `footprint`: the variant's lookup
/// (`None`: unknown, every face whole).
pub fn face_rects(
    light: DVec3,
    size: u32,
    receivers: &[Bounds],
    (planes, eye): (&[DVec4], DVec3),
    footprint: Option<Footprint>,
) -> FaceRects {
    let full = Some(TexelRect::full(size));
    let Some(footprint) = footprint else {
        return [full; 6];
    };
    let mut rects: FaceRects = [None; 6];
    let mut add = |face: usize, r: Option<TexelRect>| {
        rects[face] = match (rects[face], r) {
            (Some(a), Some(b)) => Some(a.union(b)),
            (a, b) => a.or(b),
        }
    };
    for &b in receivers {
        let Some(seen) = visible_part(b, planes) else {
            continue;
        };
        // The receiver's nearest point to the light (its box's).
        let r_min = (light.clamp(b.lo, b.hi) - light).length();
        let view_max = seen.1.iter().map(|c| c.distance(eye)).fold(0.0, f64::max);
        let reach = reach_texels(footprint, size, r_min, view_max);
        let Some(reach) = reach.filter(|_| r_min > 0.0) else {
            (0..6).for_each(|face| add(face, full)); // the light is in its box
            continue;
        };
        for face in 0..6 {
            add(face, receiver_rect(light, face, size, &seen, reach));
        }
    }
    rects
}
// ANCHOR_END: face_rects

/// One receiver's rectangle in one face: the part the camera sees (its
/// bounding planes and vertices), cut to the face's frustum widened by
/// `reach` texels (outside it no tap that reads this face starts),
/// projected, widened by `reach`, clamped to the face.
fn receiver_rect(
    light: DVec3,
    face: usize,
    size: u32,
    (bounding, seen): &(Vec<DVec4>, Vec<DVec3>),
    reach: f64,
) -> Option<TexelRect> {
    let n = f64::from(size);
    let (axis, up) = CUBE_FACES[face];
    let wide = 1.0 + 2.0 * reach / n;
    // |q · s| ≤ wide · (q · axis) and |q · up| ≤ wide · (q · axis), q = p − light.
    let s = axis.cross(up);
    let cone: Vec<DVec4> = [s, -s, up, -up]
        .into_iter()
        .map(|t| {
            let normal = wide * axis - t;
            normal.extend(-normal.dot(light)) / normal.length()
        })
        .collect();
    let scale = 1.0
        + light.abs().max_element()
        + seen
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
    let tol = 1e-7 * scale;
    let cut = cutting(&cone, seen, tol)?;
    let corners = if cut.is_empty() {
        seen.clone()
    } else {
        vertices(&[bounding.as_slice(), &cut].concat(), tol)
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in corners {
        // A vertex at the light itself (rounding): no bound, the whole face.
        let Some(t) = face_texel(light, face, size, p).filter(|t| t.iter().all(|x| x.is_finite()))
        else {
            return Some(TexelRect::full(size));
        };
        for ((lo, hi), t) in lo.iter_mut().zip(&mut hi).zip(t) {
            (*lo, *hi) = (lo.min(t), hi.max(t));
        }
    }
    let x0 = (lo[0] - reach).floor().max(0.0);
    let y0 = (lo[1] - reach).floor().max(0.0);
    let x1 = (hi[0] + reach).ceil().min(n);
    let y1 = (hi[1] + reach).ceil().min(n);
    (x1 > x0 && y1 > y0).then_some(TexelRect {
        x: x0 as u32,
        y: y0 as u32,
        w: (x1 - x0) as u32,
        h: (y1 - y0) as u32,
    })
}

/// The last rectangles computed per light, made again only when the
/// camera, the light, the face size or the footprint change (objects do
/// not move): most frames reuse them.
#[derive(Default)]
pub struct FaceRectCache {
    made_for: Vec<Option<RectsMadeFor>>,
    rects: Vec<FaceRects>,
}

/// What a light's rectangles were made for: the camera's view-projection
/// and eye, the light, the face size and the footprint.
type RectsMadeFor = (Mat4, Vec3, DVec3, u32, Option<Footprint>);

impl FaceRectCache {
    /// [`face_rects`] of light `k` at `light` for the camera `view_proj`
    /// (at `eye`), reused while none of it changes.
    pub fn get(
        &mut self,
        (k, light): (usize, DVec3),
        size: u32,
        receivers: &[Bounds],
        (view_proj, eye): (Mat4, Vec3),
        footprint: Option<Footprint>,
    ) -> FaceRects {
        if self.made_for.len() <= k {
            self.made_for.resize(k + 1, None);
            self.rects.resize(k + 1, [None; 6]);
        }
        let key = Some((view_proj, eye, light, size, footprint));
        if self.made_for[k] != key {
            // Pixel centres lie half a pixel inside the frustum's sides:
            // a margin for rounding only.
            let planes = frustum_planes(view_proj, 1e-4);
            let camera = (planes.as_slice(), eye.as_dvec3());
            self.rects[k] = face_rects(light, size, receivers, camera, footprint);
            self.made_for[k] = key;
        }
        self.rects[k]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::glam::DMat4;

    /// The face's matrix as the face pass builds it, in doubles.
    fn face_view_proj_f64(light: DVec3, face: usize) -> DMat4 {
        super::super::faces::face_view_proj(light, face, 0.05, 10.0).as_dmat4()
    }

    /// A unit box 2 m along +X from a light at the origin fills the middle
    /// half of the +X face: x and y from N/4 to 3N/4 of a 1024² face
    /// (0.5 m / 1.5 m at its nearest side, 0.5 / 2.5 at its far side).
    #[test]
    fn a_box_ahead_of_the_light_projects_to_its_rectangle() {
        let b = Bounds {
            lo: DVec3::new(1.5, -0.5, -0.5),
            hi: DVec3::new(2.5, 0.5, 0.5),
        };
        let nothing_cut: [DVec4; 0] = [];
        let exact = Footprint::default();
        let rects = face_rects(
            DVec3::ZERO,
            1024,
            &[b],
            (&nothing_cut, DVec3::ZERO),
            Some(exact),
        );
        // The near side: 512 ± 512 / 3 texels; one texel for rounding.
        let (lo, hi): (f64, f64) = (512.0 - 512.0 / 3.0, 512.0 + 512.0 / 3.0);
        let side = |a: f64, b: f64| (b.ceil() + 1.0 - (a.floor() - 1.0)) as u32;
        let want = TexelRect {
            x: lo.floor() as u32 - 1,
            y: lo.floor() as u32 - 1,
            w: side(lo, hi),
            h: side(lo, hi),
        };
        assert_eq!(rects[0], Some(want));
        // The box lies wholly in +X's frustum: no other face sees it.
        assert_eq!(&rects[1..], &[None; 5]);
        // A bilinear lookup widens it by one texel each way.
        let bilinear = Footprint {
            bilinear: true,
            ..exact
        };
        let wider = face_rects(
            DVec3::ZERO,
            1024,
            &[b],
            (&nothing_cut, DVec3::ZERO),
            Some(bilinear),
        );
        let w = wider[0].unwrap();
        assert_eq!((w.x, w.w), (want.x - 1, want.w + 2));
    }

    /// The texel the face pass rasterises a point into is the one
    /// `face_texel` names, for every face.
    #[test]
    fn face_texel_is_the_face_pass_projection() {
        let light = DVec3::new(0.3, 1.8, -0.2);
        let p = [
            DVec3::new(2.0, 0.7, -0.4),
            DVec3::new(-2.0, 0.5, 0.9),
            DVec3::new(0.2, 3.0, 0.6),
            DVec3::new(-0.7, -3.0, 0.1),
            DVec3::new(0.4, 0.6, 2.0),
            DVec3::new(-0.9, -0.3, -2.0),
        ];
        for (face, &p) in p.iter().enumerate() {
            let q = light + p;
            let clip = face_view_proj_f64(light, face) * q.extend(1.0);
            let ndc = clip.truncate().truncate() / clip.w;
            let want = [(ndc.x + 1.0) * 512.0, (1.0 - ndc.y) * 512.0];
            let got = face_texel(light, face, 1024, q).unwrap();
            let off = (got[0] - want[0]).abs().max((got[1] - want[1]).abs());
            assert!(off < 1e-3, "face {face}: {got:?} vs {want:?}");
        }
    }

    /// What the camera cannot see of a receiver is cut away, and a receiver
    /// wholly outside the frustum gives no rectangle at all.
    #[test]
    fn the_camera_frustum_cuts_receivers() {
        let proj = common::glam::dcamera::rh::proj::directx::perspective(1.0, 1.0, 0.1, 50.0);
        let view = look_at_mat4(DVec3::new(0.0, 10.0, 0.0), DVec3::ZERO, DVec3::NEG_Z);
        let planes = frustum_planes((proj * view).as_mat4(), 0.0);
        let floor = Bounds {
            lo: DVec3::new(-50.0, 0.0, -50.0),
            hi: DVec3::new(50.0, 0.0, 50.0),
        };
        // tan(0.5) × 10 m: the floor the camera sees.
        let half = 0.5f64.tan() * 10.0;
        let (_, c) = visible_part(floor, &planes).unwrap();
        for p in &c {
            assert!(p.x.abs() <= half + 1e-6 && p.z.abs() <= half + 1e-6, "{p}");
        }
        let behind = Bounds {
            lo: DVec3::new(-1.0, 11.0, -1.0),
            hi: DVec3::new(1.0, 12.0, 1.0),
        };
        assert!(visible_part(behind, &planes).is_none());
    }

    /// A receiver around the light gets every face whole.
    #[test]
    fn conservative_where_it_cannot_bound() {
        let around = Bounds {
            lo: DVec3::splat(-1.0),
            hi: DVec3::splat(1.0),
        };
        let none: [DVec4; 0] = [];
        let rects = face_rects(
            DVec3::ZERO,
            256,
            &[around],
            (&none, DVec3::ZERO),
            Some(Footprint::default()),
        );
        assert_eq!(rects, [Some(TexelRect::full(256)); 6]);
    }
}
