//! The range sphere of a light (lesson 08): a point light of range r
//! lights nothing outside its sphere, so a shadow-volume fragment can only
//! matter at a pixel whose *stored* scene depth lies inside the sphere's
//! window-depth interval [zmin, zmax] ([`sphere_depth_bounds`]), and inside
//! the sphere's screen rectangle ([`sphere_scissor`]).

use common::glam::{DMat4, DVec3, DVec4};
use common::gpu::render::SceneGpu;
use common::scene::LightKind;

/// Widens the range sphere a little, so that a point the lit shader finds
/// at distance ≤ r (in f32) is inside the bounds computed here (in f64).
pub const SPHERE_MARGIN: f64 = 1e-3;
/// Widens the depth interval by a few 24-bit steps for the same reason.
pub const DEPTH_MARGIN: f64 = 4.0 / 16_777_215.0;

/// The window depth of view distance `d` (> 0) under projection `proj`
/// (right-handed, [0, 1] depth). Past a finite far plane it exceeds 1
/// (below 0 when reversed): the caller clamps.
pub fn window_depth(proj: DMat4, d: f64) -> f64 {
    let c = proj * DVec4::new(0.0, 0.0, -d, 1.0);
    c.z / c.w
}

// ANCHOR: sphere_depth_bounds
/// [zmin, zmax] in window depth of a sphere (centre in *view* space, radius
/// r), for a camera with this `near` distance and projection. `None` when
/// the sphere lies wholly behind the near plane. Window depth is monotonic
/// in view distance, so the two ends of the sphere's distance interval give
/// the two ends of the depth interval, in either order: the same code holds
/// for depth growing with distance (standard, infinite) and shrinking
/// (reversed).
pub fn sphere_depth_bounds(
    proj: DMat4,
    near: f64,
    centre_view: DVec3,
    r: f64,
) -> Option<(f32, f32)> {
    let r = r * (1.0 + SPHERE_MARGIN);
    let d = -centre_view.z; // distance along the view axis
    let (d_near, d_far) = (d - r, d + r);
    if d_far <= near {
        return None;
    }
    // A sphere crossing the near plane starts at the near plane's depth.
    let (a, b) = (
        window_depth(proj, d_near.max(near)),
        window_depth(proj, d_far),
    );
    // Past a finite far plane the depth leaves [0, 1]; a stored depth
    // never does (clipped surfaces leave the clear value, 1): clamp.
    let zmin = a.min(b) - DEPTH_MARGIN;
    let zmax = a.max(b) + DEPTH_MARGIN;
    Some((zmin.clamp(0.0, 1.0) as f32, zmax.clamp(0.0, 1.0) as f32))
}
// ANCHOR_END: sphere_depth_bounds

/// A scissor rectangle in pixels (x, y from the top left).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Scissor {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

impl Scissor {
    pub fn full(w: u32, h: u32) -> Scissor {
        Scissor {
            x: 0,
            y: 0,
            width: w,
            height: h,
        }
    }

    pub fn area(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    pub fn contains(&self, px: u32, py: u32) -> bool {
        px >= self.x && py >= self.y && px < self.x + self.width && py < self.y + self.height
    }
}

// ANCHOR: axis_bounds
/// One axis of the sphere's projection (Mara & McGuire 2013, "2D polyhedral
/// bounds of a clipped, perspective-projected 3D sphere"). In the plane of
/// the axis `a` (x or y) and the view axis z, the circle (ca, cz, r) is seen
/// from the eye between its two tangent points; a tangent point in front of
/// the near plane (z > −near) is replaced by where the circle crosses it.
/// Returns the two bounding points as (a, z), z < 0.
fn axis_bounds(ca: f64, cz: f64, r: f64, near: f64) -> [(f64, f64); 2] {
    let near_z = -near;
    let crosses_near = cz + r > near_z;
    let t2 = ca * ca + cz * cz - r * r; // squared tangent length
    let len = (ca * ca + cz * cz).sqrt();
    let mut out = [(0.0, 0.0); 2];
    for (i, s) in [1.0f64, -1.0].into_iter().enumerate() {
        let mut p = (f64::NAN, f64::NAN);
        if t2 > 0.0 {
            // Rotate the centre direction by ±θ (sin θ = r/len), scale by cos θ.
            let (cos, sin) = (t2.sqrt() / len, s * r / len);
            p = (cos * (cos * ca + sin * cz), cos * (-sin * ca + cos * cz));
        }
        if crosses_near && (t2 <= 0.0 || p.1 > near_z) {
            let half_chord = (r * r - (near_z - cz).powi(2)).max(0.0).sqrt();
            p = (ca + s * half_chord, near_z);
        }
        out[i] = p;
    }
    out
}
// ANCHOR_END: axis_bounds

// ANCHOR: sphere_scissor
/// The pixel rectangle that holds the sphere's image (centre in view space),
/// for a `w × h` target. The camera inside the sphere sees it everywhere:
/// the full screen. `None` when the sphere is behind the near plane or off
/// screen.
pub fn sphere_scissor(
    proj: DMat4,
    near: f64,
    centre_view: DVec3,
    r: f64,
    w: u32,
    h: u32,
) -> Option<Scissor> {
    let r = r * (1.0 + SPHERE_MARGIN);
    let c = centre_view;
    if c.length() <= r {
        return Some(Scissor::full(w, h));
    }
    if c.z - r >= -near {
        return None;
    }
    // NDC of a point (a, z) on one axis: proj[a][a] · a / −z.
    let ndc = |scale: f64, (a, z): (f64, f64)| scale * a / -z;
    let xs = axis_bounds(c.x, c.z, r, near).map(|p| ndc(proj.x_axis.x, p));
    let ys = axis_bounds(c.y, c.z, r, near).map(|p| ndc(proj.y_axis.y, p));
    let (x0, x1) = (xs[0].min(xs[1]).max(-1.0), xs[0].max(xs[1]).min(1.0));
    let (y0, y1) = (ys[0].min(ys[1]).max(-1.0), ys[0].max(ys[1]).min(1.0));
    if x0 >= x1 || y0 >= y1 {
        return None;
    }
    // NDC → pixels: x right, y down; round outwards.
    let px0 = ((x0 + 1.0) * 0.5 * w as f64).floor() as u32;
    let px1 = (((x1 + 1.0) * 0.5 * w as f64).ceil() as u32).min(w);
    let py0 = ((1.0 - y1) * 0.5 * h as f64).floor() as u32;
    let py1 = (((1.0 - y0) * 0.5 * h as f64).ceil() as u32).min(h);
    (px1 > px0 && py1 > py0).then(|| Scissor {
        x: px0,
        y: py0,
        width: px1 - px0,
        height: py1 - py0,
    })
}
// ANCHOR_END: sphere_scissor

/// The bounds of one light for one camera: `None` when the light can affect
/// nothing on screen (its volumes need not be drawn at all).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    pub depth: (f32, f32),
    pub scissor: Scissor,
}

/// Depth bounds and scissor of a point or spot light's range sphere
/// (`centre` origin-relative world space).
pub fn light_bounds(
    view: DMat4,
    proj: DMat4,
    near: f64,
    centre: DVec3,
    range: f64,
    w: u32,
    h: u32,
) -> Option<LightBounds> {
    let c = view.transform_point3(centre);
    let depth = sphere_depth_bounds(proj, near, c, range)?;
    let scissor = sphere_scissor(proj, near, c, range, w, h)?;
    Some(LightBounds { depth, scissor })
}

/// A light's range sphere: its centre (origin-relative world space) and
/// radius; `None` for a light without a range (directional).
pub type RangeSphere = Option<(DVec3, f64)>;

/// Every light's [`RangeSphere`], relative to `origin`, the scene's
/// ([`Scene::origin`](common::scene::Scene::origin), a pass over every
/// vertex: found once, since objects do not move).
pub fn range_spheres(scene: &common::scene::Scene, origin: DVec3) -> Vec<RangeSphere> {
    let sphere = |l: &common::scene::Light| match l.kind {
        LightKind::Directional { .. } => None,
        LightKind::Point { position, range }
        | LightKind::Spot {
            position, range, ..
        } => Some((position - origin, range)),
    };
    scene.lights.iter().map(sphere).collect()
}

// ANCHOR: light_bounds
/// Per light (`spheres`: [`range_spheres`]): `None` for a directional
/// light (no range, no limits), else the range sphere's bounds,
/// `Some(None)` when it is off screen.
pub fn all_bounds(scene: &SceneGpu, spheres: &[RangeSphere]) -> Vec<Option<Option<LightBounds>>> {
    let (cam, s) = (&scene.camera, &scene.scene);
    let (view, proj) = (cam.view.as_dmat4(), cam.proj.as_dmat4());
    spheres
        .iter()
        .map(|sphere| {
            let &(centre, range) = sphere.as_ref()?;
            Some(light_bounds(
                view,
                proj,
                s.camera.near,
                centre,
                range,
                scene.width,
                scene.height,
            ))
        })
        .collect()
}
// ANCHOR_END: light_bounds

// ANCHOR: caster_reaches
/// Whether a caster (its bounding sphere, origin-relative) can shadow
/// anything inside a light's range sphere. A point in range is
/// shadowed only by a caster on the segment from the light to it, and that
/// segment lies inside the range sphere: a caster whose bounding sphere
/// misses the range sphere casts nothing there. Its volume may still cross
/// pixels beyond the range, which the lit pass discards in every variant,
/// so leaving it out changes no pixel. A light without a range reaches
/// every caster.
pub fn caster_reaches(light: RangeSphere, center: DVec3, radius: f64) -> bool {
    match light {
        Some((position, range)) => position.distance(center) <= range + radius,
        None => true,
    }
}
// ANCHOR_END: caster_reaches

#[cfg(test)]
mod tests {

    /// A caster reaches a light's range when its bounding sphere meets the
    /// range sphere, even with its centre outside; a directional light
    /// reaches everything.
    #[test]
    fn a_caster_reaches_the_range_when_its_sphere_meets_it() {
        let text = "[camera]\neye = [0.0, 0.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n\
            [[lights]]\ntype = \"point\"\nposition = [0.0, 0.0, 0.0]\nrange = 3.0\n\
            [[lights]]\ntype = \"directional\"\ndirection = [0.0, -1.0, 0.0]\n\
            [[objects]]\nmesh = \"cube\"\n";
        let scene = common::scene::Scene::parse(text, "test", std::path::Path::new(".")).unwrap();
        let at = |x: f64| DVec3::new(x, 0.0, 0.0) - scene.origin();
        let spheres = range_spheres(&scene, scene.origin());
        assert!(
            caster_reaches(spheres[0], at(3.5), 1.0),
            "centre out, sphere in"
        );
        assert!(!caster_reaches(spheres[0], at(4.5), 1.0), "sphere out");
        assert!(caster_reaches(spheres[1], at(100.0), 1.0), "directional");
    }

    use super::*;
    use glam::dcamera::rh::proj::directx::{perspective, perspective_infinite};

    const W: u32 = 640;
    const H: u32 = 360;

    fn proj() -> DMat4 {
        perspective(50f64.to_radians(), W as f64 / H as f64, 0.1, 100.0)
    }

    /// Points on the sphere and on its cut by the near plane that the
    /// camera sees (in front of the near plane).
    fn visible_samples(c: DVec3, r: f64, near: f64) -> Vec<DVec3> {
        let mut v = Vec::new();
        for i in 0..200 {
            for j in 0..400 {
                let th = std::f64::consts::PI * (i as f64 + 0.5) / 200.0;
                let ph = std::f64::consts::TAU * j as f64 / 400.0;
                v.push(c + r * DVec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()));
            }
        }
        let dz = -near - c.z;
        if dz.abs() < r {
            let rr = (r * r - dz * dz).sqrt();
            for k in 0..2000 {
                let a = std::f64::consts::TAU * k as f64 / 2000.0;
                v.push(DVec3::new(c.x + rr * a.cos(), c.y + rr * a.sin(), -near));
            }
        }
        v.retain(|p| p.z <= -near);
        v
    }

    fn pixel_of(p: DMat4, q: DVec3) -> (f64, f64) {
        let c = p * q.extend(1.0);
        (
            (c.x / c.w + 1.0) * 0.5 * W as f64,
            (1.0 - c.y / c.w) * 0.5 * H as f64,
        )
    }

    /// The rectangle contains every sample and is tight to within 2 pixels.
    fn check_scissor(c: DVec3, r: f64) {
        let p = proj();
        let s = sphere_scissor(p, 0.1, c, r, W, H).expect("visible sphere");
        let (mut lo, mut hi) = ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN));
        for q in visible_samples(c, r, 0.1) {
            let (x, y) = pixel_of(p, q);
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        }
        let (lo, hi) = (
            (lo.0.max(0.0), lo.1.max(0.0)),
            (hi.0.min(W as f64), hi.1.min(H as f64)),
        );
        let (x0, y0, x1, y1) = (
            s.x as f64,
            s.y as f64,
            (s.x + s.width) as f64,
            (s.y + s.height) as f64,
        );
        assert!(
            x0 <= lo.0 && y0 <= lo.1 && x1 >= hi.0 && y1 >= hi.1,
            "{s:?} misses samples {lo:?}..{hi:?}"
        );
        let slack = (lo.0 - x0).max(lo.1 - y0).max(x1 - hi.0).max(y1 - hi.1);
        assert!(
            slack <= 2.0 + r * 0.01 * W as f64 / c.z.abs(),
            "{s:?} is loose around {lo:?}..{hi:?} (slack {slack})"
        );
    }

    #[test]
    fn scissor_bounds_a_sphere_in_front_of_the_camera() {
        check_scissor(DVec3::new(0.0, 0.0, -10.0), 2.0);
        check_scissor(DVec3::new(3.0, -1.5, -8.0), 1.0);
        check_scissor(DVec3::new(-6.0, 2.0, -7.0), 3.0);
    }

    #[test]
    fn scissor_handles_a_sphere_crossing_the_near_plane() {
        // The centre is behind the camera's near plane, off axis.
        check_scissor(DVec3::new(0.9, 0.0, -0.3), 0.8);
        check_scissor(DVec3::new(1.0, -0.4, -0.2), 0.9);
        check_scissor(DVec3::new(-0.5, 0.6, 0.2), 0.7);
    }

    #[test]
    fn camera_inside_the_sphere_gives_the_full_screen() {
        let s = sphere_scissor(proj(), 0.1, DVec3::new(0.3, 0.1, -0.5), 2.0, W, H);
        assert_eq!(s, Some(Scissor::full(W, H)));
        let b = sphere_depth_bounds(proj(), 0.1, DVec3::new(0.3, 0.1, -0.5), 2.0).unwrap();
        assert_eq!(b.0, 0.0, "a sphere around the camera starts at depth 0");
    }

    #[test]
    fn a_sphere_behind_the_camera_is_culled() {
        assert_eq!(
            sphere_scissor(proj(), 0.1, DVec3::new(0.0, 0.0, 5.0), 2.0, W, H),
            None
        );
        assert_eq!(
            sphere_depth_bounds(proj(), 0.1, DVec3::new(0.0, 0.0, 5.0), 2.0),
            None
        );
    }

    #[test]
    fn depth_bounds_hold_every_point_of_the_sphere() {
        let aspect = W as f64 / H as f64;
        // Reversed depth: near and far swapped (near → 1, far → 0).
        let reversed = perspective(50f64.to_radians(), aspect, 100.0, 0.1);
        for (p, rev) in [
            (proj(), false),
            (perspective_infinite(50f64.to_radians(), aspect, 0.1), false),
            (reversed, true),
        ] {
            for (c, r) in [
                (DVec3::new(1.0, 0.0, -10.0), 3.0),
                (DVec3::new(0.0, 1.0, -0.5), 1.0),
                (DVec3::new(0.0, 0.0, -90.0), 20.0),
            ] {
                let (zmin, zmax) = sphere_depth_bounds(p, 0.1, c, r).unwrap();
                let (mut lo, mut hi) = (f64::MAX, f64::MIN);
                for q in visible_samples(c, r, 0.1) {
                    let z = window_depth(p, -q.z).clamp(0.0, 1.0);
                    lo = lo.min(z);
                    hi = hi.max(z);
                }
                assert!(
                    zmin as f64 <= lo && zmax as f64 >= hi,
                    "[{zmin}, {zmax}] misses [{lo}, {hi}] for {c:?} r {r}"
                );
                // Tight: the interval is no wider than the margins allow.
                assert!(
                    hi - lo > 0.0 && (zmax as f64 - hi) < 1e-3 && (lo - zmin as f64) < 1e-3,
                    "[{zmin}, {zmax}] vs [{lo}, {hi}]"
                );
                if c.z + r * (1.0 + SPHERE_MARGIN) > -0.1 {
                    let at_near = if rev { zmax } else { zmin };
                    assert_eq!(at_near, if rev { 1.0 } else { 0.0 }, "near plane");
                }
                // (0, 0, -90), r 20 crosses the far plane at 100.
                if c.z - r < -100.0 && p == proj() {
                    assert_eq!(zmax, 1.0, "past the far plane the bound is 1");
                }
            }
        }
    }
}
