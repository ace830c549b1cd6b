//! The exact hard-shadow reference: one primary ray per pixel, one shadow ray
//! per pixel and light, through a [`Bvh`], on every core (rayon).
//!
//! Everything is origin-relative, like the GPU's view (see [`Scene::origin`]).
//! Two small numbers decide what "exact" means here:
//!
//! - [`SHADOW_OFFSET`]: a shadow ray starts this fraction of the scene's
//!   diagonal off the surface, on the camera's side, and ignores the triangle
//!   it starts on. That is far above `f32` rounding at the scene's size
//!   (about `6e-8` of it) and far below anything a pixel can show.
//! - A surface whose camera-facing normal points away from a light
//!   (N·L <= 0) is in its own shadow: visibility 0, no ray is cast.
//!
//! A light with a size (lesson 10) gets a fractional visibility: the share
//! of its emitter the point sees, by stratified rays ([`area`]), cast
//! wherever a conservative query of the BVH finds a caster in the cone of
//! those rays ([`cone`]); V = 1 without a ray where it finds none.
//!
//! Beside the reference:
//! - [`area`]: the soft shadow of an area light, by stratified rays.
//! - [`bvh`]: the bounding-volume hierarchy the reference casts against.
//! - [`cache`]: CI's cache of references on disk (off unless
//!   `WORKBOOK_REFERENCE_CACHE` names a folder).
//! - [`cone`]: the cone of an area light's rays, and what might block it.
//! - [`fragile`]: the receivers a rasteriser could flip, found by drawing
//!   the frame again with the camera moved by a sixteenth of a pixel.
//! - [`dv_view`]: the signed ΔV view of a soft shadow (GPU − exact), on a
//!   diverging colour scale.
//! - [`metrics`]: error of a GPU visibility image against the reference.
//! - [`soft_metrics`]: a soft shadow's error per class of receiver (umbra,
//!   penumbra, lit), its leak and spill, and its penumbra-width error.

pub mod area;
pub mod bvh;
pub mod cache;
pub mod cone;
pub mod dv_view;
pub mod fragile;
pub mod metrics;
pub mod soft_metrics;

use web_time::Instant;

use glam::{DMat4, DVec3, DVec4, Mat4, Vec3};
use rayon::prelude::*;

use crate::reference::area::{AreaSampling, Emitter, LightAt, Query};
use crate::reference::bvh::Bvh;
use crate::reference::cone::RayCone;
use crate::scene::{LightKind, Scene};

/// Shadow-ray start offset, as a fraction of the scene's bounding diagonal.
pub const SHADOW_OFFSET: f32 = 1e-5;

/// What the primary ray of a pixel hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelHit {
    /// Index into `scene.objects`.
    pub object: u32,
    /// Index into `scene.world_triangles()`.
    pub triangle: u32,
    /// Distance from the ray's start on the near plane.
    pub t: f32,
    /// Origin-relative world position (see [`Scene::origin`]), on the
    /// triangle's plane.
    pub position: Vec3,
    /// Unit geometric normal, flipped to face the camera.
    pub normal: Vec3,
}

/// The reference images, row-major, row 0 at the top.
#[derive(Clone, Debug)]
pub struct Reference {
    pub width: u32,
    pub height: u32,
    pub hits: Vec<Option<PixelHit>>,
    /// `visibility[k][pixel]`: 1.0 where light `k` is unoccluded, else 0.0
    /// (also 0.0 where nothing was hit or the surface faces away from it);
    /// for a light with a size, the fraction of its emitter the point sees.
    pub visibility: Vec<Vec<f32>>,
    /// `lit_by[k][pixel]`: geometric N·L (clamped at 0) where the pixel is
    /// inside light `k`'s influence (range, and cone for a spot), else 0.0.
    pub lit_by: Vec<Vec<f32>>,
    /// `area_light[k]`: whether light `k` has a size (a soft shadow).
    pub area_light: Vec<bool>,
    /// `horizon_clipped[k][pixel]`: for a light with a size, whether part
    /// of its emitter is below the point's tangent plane (the surface
    /// itself hides that part). Such a point got the full strata whatever
    /// is in the way if it faces the light's centre, and V = 0 with no ray
    /// if it does not. False for a hard light and where nothing was hit.
    pub horizon_clipped: Vec<Vec<bool>>,
    /// Wall-clock time of [`render_reference`], BVH builds included.
    pub ms: f64,
    /// Shadow rays cast, all lights: one per receiver and hard light; per
    /// receiver and area light, none where nothing is in the cone toward
    /// the emitter (V = 1), else the full strata.
    pub shadow_rays: u64,
}

// ANCHOR: primary_ray
/// The ray through the centre of pixel `(i, j)` of a `w × h` image, from the
/// near plane, with a unit direction. `inv_view_proj` is the inverse of the
/// origin-relative camera matrix.
///
/// It unprojects two depths of the same NDC point, 0 (the near plane) and 0.5,
/// in `f64`: that works for an infinite far plane, where depth 1 has w = 0.
pub fn primary_ray(inv_view_proj: DMat4, i: u32, j: u32, w: u32, h: u32) -> (Vec3, Vec3) {
    let (o, d, _) = primary_ray_f64(inv_view_proj, i, j, w, h);
    (o.as_vec3(), d.as_vec3())
}

/// The pixel's ray in `f64` and the distance to the far plane (infinite for
/// an infinite far plane).
fn primary_ray_f64(inv: DMat4, i: u32, j: u32, w: u32, h: u32) -> (DVec3, DVec3, f64) {
    // NDC y points up, image rows go down.
    let x = (i as f64 + 0.5) / w as f64 * 2.0 - 1.0;
    let y = 1.0 - (j as f64 + 0.5) / h as f64 * 2.0;
    let unproject = |z: f64| inv * DVec4::new(x, y, z, 1.0);
    let near = unproject(0.0);
    let near = near.truncate() / near.w;
    let mid = unproject(0.5);
    let dir = (mid.truncate() / mid.w - near).normalize();
    // Depth 1: w is 0 for an infinite far plane (or rounds to either sign).
    let far = unproject(1.0);
    let t_far = if far.w.abs() > 1e-12 * far.truncate().length() {
        (far.truncate() / far.w - near).dot(dir)
    } else {
        f64::INFINITY
    };
    let t_far = if t_far.is_finite() && t_far > 0.0 {
        t_far
    } else {
        f64::INFINITY
    };
    (near, dir, t_far)
}
// ANCHOR_END: primary_ray

/// Where a light is, seen from an origin-relative point.
enum LightRel {
    /// Unit vector toward the light (opposite to the way the light travels).
    Directional { to_light: Vec3 },
    /// `cos_half`: cosine of half the cone angle; -1 for a point light.
    Local {
        position: Vec3,
        range: f32,
        spot_dir: Vec3,
        cos_half: f32,
    },
}

impl LightRel {
    fn new(kind: &LightKind, origin: DVec3) -> Self {
        match *kind {
            LightKind::Directional { direction } => LightRel::Directional {
                to_light: (-direction).normalize().as_vec3(),
            },
            LightKind::Point { position, range } => LightRel::Local {
                position: (position - origin).as_vec3(),
                range: range as f32,
                spot_dir: Vec3::ZERO,
                cos_half: -1.0,
            },
            LightKind::Spot {
                position,
                direction,
                range,
                spot_angle_deg,
            } => LightRel::Local {
                position: (position - origin).as_vec3(),
                range: range as f32,
                spot_dir: direction.normalize().as_vec3(),
                cos_half: (0.5 * spot_angle_deg).to_radians().cos() as f32,
            },
        }
    }

    /// Geometric N·L at a point, and whether the point is inside the light's
    /// influence (within range, and inside a spot's cone).
    fn n_dot_l(&self, p: Vec3, normal: Vec3) -> (f32, bool) {
        match *self {
            LightRel::Directional { to_light } => (normal.dot(to_light), true),
            LightRel::Local {
                position,
                range,
                spot_dir,
                cos_half,
            } => {
                let v = position - p;
                let (dist, l) = (v.length(), v.normalize_or_zero());
                (
                    normal.dot(l),
                    dist <= range && (-l).dot(spot_dir) >= cos_half,
                )
            }
        }
    }

    /// Where an area light's rays aim: its position, or toward it.
    fn at(&self) -> LightAt {
        match *self {
            LightRel::Directional { to_light } => LightAt::Direction(to_light),
            LightRel::Local { position, .. } => LightAt::Position(position),
        }
    }

    /// A shadow ray from `from`: unit direction and length. A local light's
    /// ray stops `margin` short of it.
    fn shadow_ray(&self, from: Vec3, margin: f32) -> (Vec3, f32) {
        match *self {
            LightRel::Directional { to_light } => (to_light, f32::INFINITY),
            LightRel::Local { position, .. } => {
                let v = position - from;
                (v.normalize_or_zero(), v.length() - margin)
            }
        }
    }
}

/// The triangles that block shadow rays: only objects with `casts_shadow`.
struct Occluders {
    /// `None` when every object casts: the primary BVH serves both.
    bvh: Option<Bvh>,
    /// `local[scene triangle]`: its index in `bvh`, or `u32::MAX`.
    local: Vec<u32>,
}

impl Occluders {
    fn new(scene: &Scene, tris: &[([Vec3; 3], u32)]) -> anyhow::Result<Self> {
        let casts = |o: u32| scene.objects[o as usize].casts_shadow;
        if tris.iter().all(|&(_, o)| casts(o)) {
            return Ok(Occluders {
                bvh: None,
                local: Vec::new(),
            });
        }
        let mut local = vec![u32::MAX; tris.len()];
        let mut list = Vec::new();
        for (i, &(t, o)) in tris.iter().enumerate() {
            if casts(o) {
                local[i] = list.len() as u32;
                list.push(t);
            }
        }
        Ok(Occluders {
            bvh: Some(Bvh::try_build(list)?),
            local,
        })
    }

    /// The casters' tree, and scene triangle `skip`'s index in it.
    fn tree<'a>(&'a self, primary: &'a Bvh, skip: u32) -> (&'a Bvh, Option<u32>) {
        match &self.bvh {
            None => (primary, Some(skip)),
            Some(bvh) => (
                bvh,
                Some(self.local[skip as usize]).filter(|&l| l != u32::MAX),
            ),
        }
    }

    /// Whether a caster other than scene triangle `skip` crosses the ray.
    fn blocked(&self, primary: &Bvh, from: Vec3, dir: Vec3, t_max: f32, skip: u32) -> bool {
        let (bvh, skip) = self.tree(primary, skip);
        bvh.any_hit(from, dir, 0.0, t_max, skip)
    }

    /// Whether a caster other than scene triangle `skip` might cross a ray
    /// of `cone` (conservative: `false` only where none can).
    fn may_block(&self, primary: &Bvh, cone: &RayCone, skip: u32) -> bool {
        let (bvh, skip) = self.tree(primary, skip);
        bvh.may_block(cone, skip)
    }
}

// ANCHOR: render_reference
/// Ray casts the scene through `view_proj` (origin-relative, depth in [0, 1]):
/// what each pixel sees, and whether each light reaches it.
///
/// Panics where [`try_render_reference`] fails: on a scene that was not
/// validated (a vertex beyond the BVH's bounds).
pub fn render_reference(scene: &Scene, view_proj: Mat4, width: u32, height: u32) -> Reference {
    try_render_reference(scene, view_proj, width, height).unwrap_or_else(|e| panic!("{e:#}"))
}

/// [`try_render_reference_with`] the default rays for area lights.
pub fn try_render_reference(
    scene: &Scene,
    view_proj: Mat4,
    width: u32,
    height: u32,
) -> anyhow::Result<Reference> {
    try_render_reference_with(scene, view_proj, width, height, AreaSampling::DEFAULT)
}

/// [`render_reference`], with the BVH's refusal of out-of-range vertices
/// as an error (see [`Bvh::try_build`]), and `sampling`'s rays for each
/// pixel and area light.
pub fn try_render_reference_with(
    scene: &Scene,
    view_proj: Mat4,
    width: u32,
    height: u32,
    sampling: AreaSampling,
) -> anyhow::Result<Reference> {
    let start = Instant::now();
    let tris = scene.world_triangles();
    let bvh = Bvh::try_build(tris.iter().map(|(t, _)| *t).collect())?;
    let occluders = Occluders::new(scene, &tris)?;

    // Primary rays: what the camera sees at each pixel centre.
    let inv = view_proj.as_dmat4().inverse();
    let n = width as usize * height as usize;
    let hits: Vec<Option<PixelHit>> = (0..n)
        .into_par_iter()
        .with_min_len(256)
        .map(|p| {
            let (i, j) = ((p % width as usize) as u32, (p / width as usize) as u32);
            let (o, d, t_far) = primary_ray_f64(inv, i, j, width, height);
            let (o, d) = (o.as_vec3(), d.as_vec3());
            let hit = bvh.closest_hit(o, d, t_far as f32)?;
            let ([a, b, c], object) = tris[hit.tri as usize];
            let normal = (b - a).cross(c - a).normalize_or(-d);
            // o + d·t drifts off the plane by (ray length × rounding);
            // snap it back so that the shadow offset below is measured from the surface.
            let on_ray = o + d * hit.t;
            let position = on_ray - normal * (on_ray - a).dot(normal);
            Some(PixelHit {
                object,
                triangle: hit.tri,
                t: hit.t,
                position,
                // The side the camera sees.
                normal: if normal.dot(d) > 0.0 { -normal } else { normal },
            })
        })
        .collect();

    // Shadow rays: one light at a time, one ray per pixel.
    let (lo, hi) = scene.bounds();
    let diagonal = (hi - lo).length() as f32;
    let scale = if diagonal.is_finite() && diagonal > 0.0 {
        diagonal
    } else {
        1.0
    };
    let offset = SHADOW_OFFSET * scale;
    let origin = scene.origin();
    let mut visibility = Vec::with_capacity(scene.lights.len());
    let mut lit_by = Vec::with_capacity(scene.lights.len());
    let mut horizon_clipped = Vec::with_capacity(scene.lights.len());
    let mut shadow_rays = 0u64;
    for scene_light in &scene.lights {
        let light = LightRel::new(&scene_light.kind, origin);
        let emitter = Emitter::of(scene_light.size);
        let per_pixel: Vec<(f32, f32, u64, bool)> = hits
            .par_iter()
            .enumerate()
            .with_min_len(256)
            .map(|(pixel, hit)| {
                let Some(h) = hit else {
                    return (0.0, 0.0, 0, false);
                };
                let (n_dot_l, inside) = light.n_dot_l(h.position, h.normal);
                if n_dot_l.is_nan() || n_dot_l <= 0.0 {
                    // Faces away from the light: its own shadow (and an
                    // emitter's centre below the horizon).
                    return (0.0, 0.0, 0, emitter.is_some());
                }
                // Off the surface on the camera's side, then straight at the light.
                let from = h.position + h.normal * offset;
                let blocked =
                    |dir: Vec3, t_max: f32| occluders.blocked(&bvh, from, dir, t_max, h.triangle);
                let (v, rays, clipped) = match emitter {
                    None => {
                        let (dir, t_max) = light.shadow_ray(from, offset);
                        let v = !(t_max > 0.0 && blocked(dir, t_max));
                        (if v { 1.0 } else { 0.0 }, 1, false)
                    }
                    Some(emitter) => {
                        let q = Query {
                            from,
                            normal: h.normal,
                            lift: offset,
                            pixel: pixel as u32,
                            light: light.at(),
                        };
                        let may_block =
                            |cone: &RayCone| occluders.may_block(&bvh, cone, h.triangle);
                        let seen =
                            area::visibility(emitter, &q, sampling, offset, may_block, blocked);
                        (seen.visibility, seen.rays, seen.horizon_clipped)
                    }
                };
                (v, if inside { n_dot_l } else { 0.0 }, rays, clipped)
            })
            .collect();
        shadow_rays += per_pixel.iter().map(|p| p.2).sum::<u64>();
        visibility.push(per_pixel.iter().map(|p| p.0).collect());
        lit_by.push(per_pixel.iter().map(|p| p.1).collect());
        horizon_clipped.push(per_pixel.iter().map(|p| p.3).collect());
    }

    let ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(Reference {
        width,
        height,
        hits,
        visibility,
        lit_by,
        area_light: scene.lights.iter().map(|l| l.size.is_area()).collect(),
        horizon_clipped,
        ms,
        shadow_rays,
    })
}
// ANCHOR_END: render_reference

#[cfg(test)]
#[path = "unit_tests/reference.rs"]
mod tests;
