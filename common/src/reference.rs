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

use std::time::Instant;

use glam::{DMat4, DVec3, DVec4, Mat4, Vec3};
use rayon::prelude::*;

use crate::bvh::Bvh;
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
    /// (also 0.0 where nothing was hit or the surface faces away from it).
    pub visibility: Vec<Vec<f32>>,
    /// `lit_by[k][pixel]`: geometric N·L (clamped at 0) where the pixel is
    /// inside light `k`'s influence (range, and cone for a spot), else 0.0.
    pub lit_by: Vec<Vec<f32>>,
    /// Wall-clock time of [`render_reference`], BVH builds included.
    pub ms: f64,
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
    fn new(scene: &Scene, tris: &[([Vec3; 3], u32)]) -> Self {
        let casts = |o: u32| scene.objects[o as usize].casts_shadow;
        if tris.iter().all(|&(_, o)| casts(o)) {
            return Occluders {
                bvh: None,
                local: Vec::new(),
            };
        }
        let mut local = vec![u32::MAX; tris.len()];
        let mut list = Vec::new();
        for (i, &(t, o)) in tris.iter().enumerate() {
            if casts(o) {
                local[i] = list.len() as u32;
                list.push(t);
            }
        }
        Occluders {
            bvh: Some(Bvh::build(list)),
            local,
        }
    }

    /// Whether a caster other than scene triangle `skip` crosses the ray.
    fn blocked(&self, primary: &Bvh, from: Vec3, dir: Vec3, t_max: f32, skip: u32) -> bool {
        match &self.bvh {
            None => primary.any_hit(from, dir, 0.0, t_max, Some(skip)),
            Some(bvh) => {
                let skip = Some(self.local[skip as usize]).filter(|&l| l != u32::MAX);
                bvh.any_hit(from, dir, 0.0, t_max, skip)
            }
        }
    }
}

// ANCHOR: render_reference
/// Ray casts the scene through `view_proj` (origin-relative, depth in [0, 1]):
/// what each pixel sees, and whether each light reaches it.
pub fn render_reference(scene: &Scene, view_proj: Mat4, width: u32, height: u32) -> Reference {
    let start = Instant::now();
    let tris = scene.world_triangles();
    let bvh = Bvh::build(tris.iter().map(|(t, _)| *t).collect());
    let occluders = Occluders::new(scene, &tris);

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
    for light in &scene.lights {
        let light = LightRel::new(&light.kind, origin);
        let (vis, lit): (Vec<f32>, Vec<f32>) = hits
            .par_iter()
            .with_min_len(256)
            .map(|hit| {
                let Some(h) = hit else { return (0.0, 0.0) };
                let (n_dot_l, inside) = light.n_dot_l(h.position, h.normal);
                if n_dot_l.is_nan() || n_dot_l <= 0.0 {
                    return (0.0, 0.0); // faces away from the light: its own shadow
                }
                // Off the surface on the camera's side, then straight at the light.
                let from = h.position + h.normal * offset;
                let (dir, t_max) = light.shadow_ray(from, offset);
                let blocked = t_max > 0.0 && occluders.blocked(&bvh, from, dir, t_max, h.triangle);
                let v = if blocked { 0.0 } else { 1.0 };
                (v, if inside { n_dot_l } else { 0.0 })
            })
            .unzip();
        visibility.push(vis);
        lit_by.push(lit);
    }

    let ms = start.elapsed().as_secs_f64() * 1e3;
    Reference {
        width,
        height,
        hits,
        visibility,
        lit_by,
        ms,
    }
}
// ANCHOR_END: render_reference

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::dcamera::rh::{proj::directx, view::look_at_mat4};

    use super::*;
    use crate::mesh::Mesh;
    use crate::scene::{Camera, Far, Light, Object};

    /// A quad in XZ facing +Y, side 1, centred at the origin.
    fn plane() -> Mesh {
        let p = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        Mesh {
            positions: vec![p(-0.5, -0.5), p(-0.5, 0.5), p(0.5, 0.5), p(0.5, -0.5)],
            indices: vec![0, 1, 2, 0, 2, 3],
            ..Default::default()
        }
    }

    /// A closed cube of side 1 centred at the origin, counter-clockwise outside.
    fn cube() -> Mesh {
        let mut positions = Vec::new();
        for i in 0..8 {
            let c = |bit: u32| if i & bit != 0 { 0.5 } else { -0.5 };
            positions.push(Vec3::new(c(1), c(2), c(4)));
        }
        #[rustfmt::skip]
        let indices = vec![
            0, 4, 6, 0, 6, 2, // -X
            1, 3, 7, 1, 7, 5, // +X
            0, 1, 5, 0, 5, 4, // -Y
            2, 6, 7, 2, 7, 3, // +Y
            0, 2, 3, 0, 3, 1, // -Z
            4, 5, 7, 4, 7, 6, // +Z
        ];
        Mesh {
            positions,
            indices,
            ..Default::default()
        }
    }

    fn object(mesh: Mesh, model: DMat4, casts_shadow: bool) -> Object {
        Object {
            mesh_name: "test".into(),
            mesh: Arc::new(mesh),
            model,
            color: Vec3::ONE,
            casts_shadow,
        }
    }

    fn scene(objects: Vec<Object>, lights: Vec<LightKind>, eye: DVec3, target: DVec3) -> Scene {
        let camera = Camera {
            eye,
            target,
            up: DVec3::Y,
            fov_y_deg: 50.0,
            near: 0.1,
            far: Far::Finite(100.0),
        };
        let lights = lights
            .into_iter()
            .map(|kind| Light {
                kind,
                color: Vec3::ONE,
            })
            .collect();
        Scene {
            name: "test".into(),
            camera,
            ambient: Vec3::ZERO,
            lights,
            objects,
        }
    }

    /// The origin-relative camera matrix, as the GPU side builds it.
    fn view_proj(scene: &Scene, w: u32, h: u32, far: Far) -> Mat4 {
        let c = &scene.camera;
        let o = scene.origin();
        let view = look_at_mat4(c.eye - o, c.target - o, c.up);
        let aspect = w as f64 / h as f64;
        let fov = c.fov_y_deg.to_radians();
        let proj = match far {
            Far::Finite(f) => directx::perspective(fov, aspect, c.near, f),
            Far::Infinite => directx::perspective_infinite(fov, aspect, c.near),
        };
        (proj * view).as_mat4()
    }

    fn render(scene: &Scene, w: u32, h: u32) -> Reference {
        render_reference(scene, view_proj(scene, w, h, scene.camera.far), w, h)
    }

    /// The plane-hit pixel nearest to a world point on the plane.
    fn plane_pixel_near(r: &Reference, scene: &Scene, world: DVec3) -> usize {
        let target = (world - scene.origin()).as_vec3();
        (0..r.hits.len())
            .filter(|&p| r.hits[p].is_some_and(|h| h.object == 0))
            .min_by(|&a, &b| {
                let d = |p: usize| r.hits[p].unwrap().position.distance(target);
                d(a).total_cmp(&d(b))
            })
            .unwrap()
    }

    #[test]
    fn cube_shadows_the_plane_under_a_straight_down_light() {
        let s = scene(
            vec![
                object(plane(), DMat4::IDENTITY, true),
                object(
                    cube(),
                    DMat4::from_scale_rotation_translation(
                        DVec3::splat(0.2),
                        Default::default(),
                        DVec3::new(0.0, 0.5, 0.0),
                    ),
                    true,
                ),
            ],
            vec![LightKind::Directional {
                direction: DVec3::NEG_Y,
            }],
            DVec3::new(0.3, 1.5, 1.5),
            DVec3::ZERO,
        );
        let r = render(&s, 160, 120);
        let (vis, lit) = (&r.visibility[0], &r.lit_by[0]);
        let under = plane_pixel_near(&r, &s, DVec3::ZERO);
        assert_eq!(
            vis[under], 0.0,
            "the plane under the cube's centre must be shadowed"
        );
        assert!(
            lit[under] > 0.99,
            "the plane faces the light: N·L = {}",
            lit[under]
        );
        let corner = plane_pixel_near(&r, &s, DVec3::new(0.45, 0.0, 0.45));
        assert_eq!(vis[corner], 1.0, "a far corner of the plane must be lit");
        // Every plane pixel: shadowed inside the cube's footprint, lit well outside it.
        let origin = s.origin().as_vec3();
        let (mut inside, mut outside) = (0, 0);
        for (p, h) in r.hits.iter().enumerate() {
            let Some(h) = h else { continue };
            let w = h.position + origin;
            let m = w.x.abs().max(w.z.abs());
            if h.object == 0 && m < 0.099 {
                assert_eq!(vis[p], 0.0, "plane at {w} should be shadowed");
                inside += 1;
            } else if h.object == 0 && m > 0.101 {
                assert_eq!(vis[p], 1.0, "plane at {w} should be lit");
                outside += 1;
            } else if h.object == 1 && h.normal.y > 0.99 {
                assert_eq!(vis[p], 1.0, "the cube's top is lit");
            } else if h.object == 1 {
                assert_eq!(
                    (vis[p], lit[p]),
                    (0.0, 0.0),
                    "the cube's sides face away from the light"
                );
            }
        }
        assert!(
            inside > 50 && outside > 1000,
            "{inside} shadowed, {outside} lit plane pixels"
        );
    }

    #[test]
    fn point_light_inside_a_closed_box_shadows_everything_outside() {
        let floor = DMat4::from_scale_rotation_translation(
            DVec3::new(10.0, 1.0, 10.0),
            Default::default(),
            DVec3::new(0.0, -1.0, 0.0),
        );
        let light = LightKind::Point {
            position: DVec3::ZERO,
            range: 50.0,
        };
        let build = |box_casts: bool| {
            scene(
                vec![
                    object(plane(), floor, true),
                    object(cube(), DMat4::IDENTITY, box_casts),
                ],
                vec![light],
                DVec3::new(3.0, 2.5, 4.0),
                DVec3::new(0.0, -0.5, 0.0),
            )
        };
        let r = render(&build(true), 128, 96);
        let (mut floor_pixels, mut box_pixels) = (0, 0);
        for (p, h) in r.hits.iter().enumerate() {
            let Some(h) = h else { continue };
            assert_eq!(
                r.visibility[0][p], 0.0,
                "pixel {p} on object {} sees the light",
                h.object
            );
            if h.object == 0 {
                assert!(
                    r.lit_by[0][p] > 0.0,
                    "the floor faces the light and is in range"
                );
                floor_pixels += 1;
            } else {
                assert_eq!(
                    r.lit_by[0][p], 0.0,
                    "the box's outside faces away from the light"
                );
                box_pixels += 1;
            }
        }
        assert!(floor_pixels > 1000 && box_pixels > 100);
        // A box that casts no shadow lets the light out onto the floor.
        let r = render(&build(false), 128, 96);
        let lit_floor = (0..r.hits.len())
            .filter(|&p| r.hits[p].is_some_and(|h| h.object == 0) && r.visibility[0][p] == 1.0)
            .count();
        assert!(lit_floor > 1000, "only {lit_floor} floor pixels lit");
    }

    #[test]
    fn spot_light_influence_is_its_range_and_cone() {
        let floor = DMat4::from_scale(DVec3::splat(4.0));
        let spot = LightKind::Spot {
            position: DVec3::new(0.0, 1.0, 0.0),
            direction: DVec3::NEG_Y,
            range: 1.5,
            spot_angle_deg: 60.0,
        };
        let s = scene(
            vec![object(plane(), floor, true)],
            vec![spot],
            DVec3::new(0.0, 3.0, 2.0),
            DVec3::ZERO,
        );
        let r = render(&s, 96, 96);
        let radius = 30f32.to_radians().tan(); // the cone meets the floor here (inside the range)
        let origin = s.origin().as_vec3();
        let (mut inside, mut outside) = (0, 0);
        for (p, h) in r.hits.iter().enumerate() {
            let Some(h) = h else { continue };
            let w = h.position + origin;
            let d = Vec3::new(w.x, 0.0, w.z).length();
            assert_eq!(r.visibility[0][p], 1.0, "nothing occludes the spot");
            if d < radius - 0.01 {
                let expected = 1.0 / (1.0 + d * d).sqrt(); // N·L toward the light 1 unit up
                assert!(
                    (r.lit_by[0][p] - expected).abs() < 1e-4,
                    "N·L at {w}: {} vs {expected}",
                    r.lit_by[0][p]
                );
                inside += 1;
            } else if d > radius + 0.01 {
                assert_eq!(r.lit_by[0][p], 0.0, "outside the cone at {w}");
                outside += 1;
            }
        }
        assert!(
            inside > 200 && outside > 200,
            "{inside} inside, {outside} outside"
        );
    }

    #[test]
    fn primary_rays_follow_the_pixel_convention() {
        let s = scene(
            vec![object(plane(), DMat4::IDENTITY, true)],
            vec![LightKind::Directional {
                direction: DVec3::NEG_Y,
            }],
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(0.1, 0.0, -0.2),
        );
        let (w, h) = (101, 61); // odd sizes: pixel (50, 30) is the image centre
        let target = (s.camera.target - s.origin()).as_vec3();
        for (far, near) in [
            (Far::Finite(100.0), 0.1),
            (Far::Infinite, 0.1),
            (Far::Finite(1e5), 1e-3),
            (Far::Infinite, 1e-3),
        ] {
            let mut s = s.clone();
            s.camera.near = near;
            let vp = view_proj(&s, w, h, far);
            let inv = vp.as_dmat4().inverse();
            // The centre pixel's ray passes through the camera target...
            let (o, d) = primary_ray(inv, 50, 30, w, h);
            assert!((d.length() - 1.0).abs() < 1e-6);
            let closest = o + d * (target - o).dot(d);
            assert!(
                closest.distance(target) < 1e-4,
                "{far:?} near {near}: misses the target by {}",
                closest.distance(target)
            );
            // ...starts on the near plane, and the reference hits the plane there.
            let eye = (s.camera.eye - s.origin()).as_vec3();
            let forward = (target - eye).normalize();
            assert!(((o - eye).dot(forward) - near as f32).abs() < 1e-3 * near as f32);
            let r = render_reference(&s, vp, w, h);
            let hit = r.hits[30 * w as usize + 50].expect("the centre pixel hits the plane");
            assert!(
                hit.position.distance(target) < 1e-4,
                "hit at {} instead of {target}",
                hit.position
            );
            // Row 0 is the top and column 0 the left: the corner ray projects back there.
            let (o, d) = primary_ray(inv, 0, 0, w, h);
            let ndc = vp.project_point3(o + d * 2.0);
            let (x, y) = (0.5 / w as f32 * 2.0 - 1.0, 1.0 - 0.5 / h as f32 * 2.0);
            assert!(
                (ndc.x - x).abs() < 1e-4 && (ndc.y - y).abs() < 1e-4,
                "{ndc} vs ({x}, {y})"
            );
        }
    }

    #[test]
    fn geometry_beyond_the_far_plane_is_clipped() {
        let s = scene(
            vec![object(plane(), DMat4::IDENTITY, true)],
            vec![LightKind::Directional {
                direction: DVec3::NEG_Y,
            }],
            DVec3::new(0.0, 5.0, 0.01),
            DVec3::ZERO,
        );
        let (w, h) = (9, 9);
        let hit = |far| render_reference(&s, view_proj(&s, w, h, far), w, h).hits[4 * 9 + 4];
        assert!(hit(Far::Finite(4.0)).is_none());
        assert!(hit(Far::Finite(6.0)).is_some());
        assert!(hit(Far::Infinite).is_some());
    }

    #[test]
    fn empty_scene_is_all_misses() {
        let s = scene(
            Vec::new(),
            vec![LightKind::Directional {
                direction: DVec3::NEG_Y,
            }],
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::ZERO,
        );
        let r = render_reference(&s, view_proj(&s, 8, 4, Far::Infinite), 8, 4);
        assert!(r.hits.iter().all(Option::is_none));
        assert_eq!(r.visibility, vec![vec![0.0; 32]]);
        assert_eq!(r.lit_by, vec![vec![0.0; 32]]);
    }

    /// The time target: about 10k triangles, one directional light, 1280×720.
    /// `cargo test --release -p common --lib -- --ignored --nocapture reference_timing`
    #[test]
    #[ignore = "timing, run by hand"]
    fn reference_timing_10k_triangles_720p() {
        let tris = crate::bvh::tests::sphere(0.5, 40, 60); // 4,680 triangles
        let ball = Mesh {
            positions: tris.iter().flatten().copied().collect(),
            indices: (0..tris.len() as u32 * 3).collect(),
            ..Default::default()
        };
        let at = |x: f64, y: f64, z: f64, s: f64| {
            DMat4::from_scale_rotation_translation(
                DVec3::splat(s),
                Default::default(),
                DVec3::new(x, y, z),
            )
        };
        let objects = vec![
            object(plane(), at(0.0, 0.0, 0.0, 10.0), true),
            object(cube(), at(-1.5, 0.5, 0.5, 1.0), true),
            object(ball.clone(), at(1.0, 0.75, 0.0, 1.5), true),
            object(ball, at(-0.3, 0.4, 1.8, 0.8), true),
        ];
        let light = LightKind::Directional {
            direction: DVec3::new(-0.4, -1.0, -0.3).normalize(),
        };
        let s = scene(
            objects,
            vec![light],
            DVec3::new(4.0, 3.0, 6.0),
            DVec3::new(0.0, 0.5, 0.0),
        );
        let triangles = s.world_triangles().len();
        let vp = view_proj(&s, 1280, 720, s.camera.far);
        let runs: Vec<f64> = (0..5)
            .map(|_| render_reference(&s, vp, 1280, 720).ms)
            .collect();
        let r = render_reference(&s, vp, 1280, 720);
        let covered = r.hits.iter().filter(|h| h.is_some()).count();
        let shadowed = (0..r.hits.len())
            .filter(|&p| r.lit_by[0][p] > 0.05 && r.visibility[0][p] == 0.0)
            .count();
        println!("{triangles} triangles, {} threads, 1280x720: {runs:.1?} ms; {covered} covered, {shadowed} shadowed receivers", rayon::current_num_threads());
    }
}
