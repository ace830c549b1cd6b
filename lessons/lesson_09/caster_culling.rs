//! Which casters each cascade draws, and where (lesson 09). A cascade's
//! map is read only by its receivers ([`super::receivers`]), and a caster
//! changes what they read only where its shadow can fall on one of them.
//! So cascade `i` draws a caster only if a receiver of cascade `i` can lie
//! behind it along the light, inside its footprint, and only inside
//! rectangles of the map around those receivers (a scissor per draw). The
//! default scene's 600 m ground, flat, with nothing below it, is drawn only
//! around the feet of the objects that stand on it; a tower 150 m away is
//! not drawn into the first cascade.
//!
//! The geometry, in the light's view space of [`light_view`] (x and y
//! across the light, z towards it: the light travels along −z). A texel is
//! the cascade's, `W/N` metres.
//!
//! - **Only deeper lookups.** The map keeps the nearest depth in each
//!   texel, cleared to the far plane, which reads as lit. Leaving a caster
//!   out can only raise a texel's depth, and a lookup at depth `s` changes
//!   only if that caster shadowed it: `s` deeper than the caster's stored
//!   depth, which lesson 02's bias only pushes farther than the caster's
//!   nearest point. A lookup starts from a surface point moved by at most
//!   a texel (`NORMAL_OFFSET_TEXELS`). So a caster matters only to surface
//!   points whose z is below its largest z plus [`ALONG_TEXELS`] (z grows
//!   towards the light).
//! - **Only near its footprint.** A caster writes the texels whose
//!   centres it covers; a lookup reads the 2×2 texels whose centres lie
//!   within a texel of it, a texel at most from its surface point. So a
//!   caster matters only to surface points within [`ACROSS_TEXELS`] of its
//!   footprint across the light, and its texels only to lookups within as
//!   much of those points: the scissor rectangles.
//! - **A flat caster: only what lies behind its plane, or just in front.**
//!   Every point of a flat mesh is on its plane. A lookup on its lit side
//!   sits one texel's slope `|g| = w·tan θ` in front of it along the light
//!   (the normal offset, `w sin θ` along the normal towards the light);
//!   the 2×2 texels around it are at most `√2|g|` nearer the light, and
//!   the slope-scaled bias (1.5 times the steeper of the two slopes, at
//!   least `1.06|g|`) pushes them back: the plane never shadows its lit
//!   side. (Its other side, seen only by a camera behind the plane, moves
//!   its lookups behind it and reads itself: dark under Lambert anyway.)
//!   Another surface can read the plane if it reaches past the plane, or
//!   comes within [`PLANE_REACH_TEXELS`] in front of it, bias left out: a
//!   ball lying on the ground, at grazing light. So a flat caster is drawn
//!   for those receivers only, and a ground with nothing on or under it
//!   casts nothing.
//!
//! Everything is tested on boxes, which hold what they bound, so a caster
//! that can change a lookup is always drawn where the lookup reads; when
//! in doubt (a mesh not quite flat, a box that pokes below the plane) it
//! is drawn.

use common::glam::{DMat4, DVec2, DVec3};
use common::scene::{LightKind, Scene};

use super::cascades::{light_view, Cascade, NORMAL_OFFSET_TEXELS};
use super::receivers::{read_depths, Aabb, Grid, LitView, Rect, Region};

/// The normal offset of a lookup, in texels (one texel: 1).
const OFFSET: f64 = NORMAL_OFFSET_TEXELS as f64;

/// How far across the light from a caster's footprint a surface point can
/// still read the caster's texels, in texels of the cascade: one for the
/// 2×2 lookup, the normal offset, and two more for lesson 01's single map
/// (whose axes may turn about the light's, a factor up to √2) and the
/// runner's 1/16-texel moves (`--fragile`). 4 texels.
pub const ACROSS_TEXELS: f64 = 3.0 + OFFSET;

/// How far in front of a caster's nearest point (towards the light) a
/// surface point can lie and still look up deeper than it: its normal
/// offset, twice over. 2 texels.
pub const ALONG_TEXELS: f64 = 2.0 * OFFSET;

/// How far in front of a flat caster's plane (along its normal) another
/// surface can read it: the 2×2 texels' `√2` texels of slope, counting no
/// bias, and the normal offset. 2.5 texels.
pub const PLANE_REACH_TEXELS: f64 = 1.5 + OFFSET;

/// A rectangle of a cascade's map, in texels: x, y, width, height.
pub type Scissor = [u32; 4];

/// Per object, the rectangles of one cascade's map it is drawn into, one
/// draw each (none: the cascade does not draw it).
pub type Kept = Vec<Vec<Scissor>>;

/// What the rule reads of one object. Found once: objects and lights do
/// not move.
#[derive(Clone, Copy, Debug)]
pub struct Body {
    /// Its box in the world, origin-relative.
    pub world: Aabb,
    /// Its box in the light's view space, around its vertices.
    pub light: Aabb,
    pub casts: bool,
    /// A flat mesh's plane `(n, d)`: n·p + d = 0, n of unit length.
    pub plane: Option<(DVec3, f64)>,
}

/// One directional light's view of the scene's objects.
#[derive(Clone, Debug)]
pub struct CasterCulling {
    light: DMat4,
    /// The direction the light travels, of unit length.
    travel: DVec3,
    bodies: Vec<Body>,
    /// The scene's box, origin-relative, and a length far below anything
    /// it resolves.
    scene: Aabb,
    tolerance: f64,
}

impl CasterCulling {
    /// For the light travelling along `direction`, over `scene`'s objects
    /// made relative to `origin` (`Scene::origin`).
    pub fn new(scene: &Scene, origin: DVec3, direction: DVec3) -> CasterCulling {
        let light = light_view(direction);
        let bodies: Vec<Body> = (scene.objects.iter())
            .map(|o| {
                let world: Vec<DVec3> = (o.mesh.positions.iter())
                    .map(|p| o.model.transform_point3(p.as_dvec3()) - origin)
                    .collect();
                Body {
                    world: Aabb::around(world.iter().copied()),
                    light: Aabb::around(world.iter().map(|&p| light.transform_point3(p))),
                    casts: o.casts_shadow,
                    plane: flat_plane(&world, &o.mesh.indices),
                }
            })
            .collect();
        let scene = Aabb::around(bodies.iter().flat_map(|b| [b.world.lo, b.world.hi]));
        let size = (scene.hi - scene.lo).length();
        CasterCulling {
            light,
            travel: direction.normalize(),
            bodies,
            scene,
            tolerance: 1e-9 * if size.is_finite() { size.max(1.0) } else { 1.0 },
        }
    }

    /// One for each of `scene`'s lights, over its objects made relative
    /// to `origin`. A light other than a directional one, which the lesson
    /// refuses before it draws, gets one for straight down.
    pub fn for_lights(scene: &Scene, origin: DVec3) -> Vec<CasterCulling> {
        let direction = |kind: LightKind| match kind {
            LightKind::Directional { direction } => direction,
            _ => DVec3::NEG_Y,
        };
        let lights = scene.lights.iter();
        lights
            .map(|l| CasterCulling::new(scene, origin, direction(l.kind)))
            .collect()
    }

    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// Without culling (`k4_nocull`): every caster into each of `cascades`
    /// maps of `resolution`² texels, over the whole map.
    pub fn every_caster(&self, cascades: usize, resolution: u32) -> Vec<Kept> {
        let whole = |b: &Body| match b.casts {
            true => vec![[0, 0, resolution, resolution]],
            false => Vec::new(),
        };
        vec![self.bodies.iter().map(whole).collect(); cascades]
    }

    /// For each cascade of `fit` (maps of `resolution`² texels, blended
    /// over a share `band` of each, 0 for none) seen by `view`, where it
    /// draws each object.
    pub fn casters(
        &self,
        view: &LitView,
        fit: &[Cascade],
        resolution: u32,
        band: f64,
    ) -> Vec<Kept> {
        let to_light = self.light.inverse();
        let cascades = fit.iter().enumerate();
        cascades
            .map(|(i, cascade)| {
                let (near, far) = read_depths(fit, i, band);
                let region = Region::new(view, near, far, self.scene, self.tolerance);
                let texel = cascade.width / resolution as f64;
                let to_map = cascade.view_proj * to_light;
                let scissor = |r: &Rect| scissor(*r, to_map, resolution);
                let rects = self.cascade_casters(&region, texel).into_iter();
                rects
                    .map(|r| r.iter().filter_map(scissor).collect())
                    .collect()
            })
            .collect()
    }

    // ANCHOR: cascade_casters
    /// For each object, the rectangles across the light where the
    /// receivers of a cascade read inside `region`, its texels `texel`
    /// metres wide, can read it (none: it cannot shadow any of them).
    pub fn cascade_casters(&self, region: &Region, texel: f64) -> Vec<Vec<Rect>> {
        let boxes = self.bodies.iter().map(|b| (b.world, b.light));
        let receivers = region.receivers(self.light, boxes);
        let grid = Grid::new(&receivers);
        let (across, along) = (ACROSS_TEXELS * texel, ALONG_TEXELS * texel);
        let bodies = self.bodies.iter().enumerate();
        bodies
            .map(|(c, caster)| {
                let mut rects = Vec::new();
                if !caster.casts {
                    return rects;
                }
                let foot = caster.light.across().grow(across);
                for r in grid.near(foot) {
                    // Near its footprint, deeper than its nearest point.
                    let deeper = r.part.lo.z < caster.light.hi.z + along;
                    if deeper && r.meets(foot) && self.can_reach(c, r.index, texel, region.eye) {
                        add(&mut rects, r.part.across().grow(across).meet(foot));
                    }
                }
                rects
            })
            .collect()
    }
    // ANCHOR_END: cascade_casters

    /// Whether receiver `r` can read caster `c` at all: always, unless `c`
    /// is flat; then only if `r` is another object whose box reaches past
    /// `c`'s plane, or within [`PLANE_REACH_TEXELS`] in front of it; or
    /// `c` itself seen from behind its plane by an `eye` there (its unlit
    /// side, whose lookups move a texel behind it: Lambert makes them
    /// dark anyway, but the visibility image shows them).
    fn can_reach(&self, c: usize, r: usize, texel: f64, eye: DVec3) -> bool {
        let Some((n, d)) = self.bodies[c].plane else {
            return true;
        };
        // Positive behind the plane: on the side the light travels to.
        let behind = |p: DVec3| n.dot(self.travel).signum() * (n.dot(p) + d);
        if r == c {
            return behind(eye) > -self.tolerance;
        }
        let reach = PLANE_REACH_TEXELS * texel;
        let corners = self.bodies[r].world.corners();
        corners.iter().any(|&p| behind(p) > -reach)
    }
}

/// Adds `r` to `rects`, merged with every rectangle it overlaps.
fn add(rects: &mut Vec<Rect>, mut r: Rect) {
    while let Some(k) = rects.iter().position(|o| !o.meet(r).is_empty()) {
        r = r.join(rects.swap_remove(k));
    }
    rects.push(r);
}

/// The texels of a map of `resolution`² that `rect` (light view space)
/// covers, and one more on each side, through `to_map` (light view space
/// to the map's clip space); `None` when it misses the map.
fn scissor(rect: Rect, to_map: DMat4, resolution: u32) -> Option<Scissor> {
    let n = resolution as f64;
    let corners = [
        rect.lo,
        DVec2::new(rect.hi.x, rect.lo.y),
        DVec2::new(rect.lo.x, rect.hi.y),
        rect.hi,
    ];
    let texels = corners.map(|p| {
        // Orthographic along the light: z does not move x and y.
        let c = to_map.project_point3(p.extend(0.0));
        DVec2::new((c.x * 0.5 + 0.5) * n, (0.5 - c.y * 0.5) * n)
    });
    let lo = texels.iter().fold(DVec2::splat(n), |a, &t| a.min(t));
    let hi = texels.iter().fold(DVec2::ZERO, |a, &t| a.max(t));
    let lo = (lo.floor() - 1.0).clamp(DVec2::ZERO, DVec2::splat(n));
    let hi = (hi.ceil() + 1.0).clamp(DVec2::ZERO, DVec2::splat(n));
    let size = hi - lo;
    (size.cmpgt(DVec2::ZERO).all()).then(|| {
        let [x, y, w, h] = [lo.x, lo.y, size.x, size.y].map(|v| v as u32);
        [x, y, w, h]
    })
}

/// The plane of a flat mesh (`points`, triangles `indices`), or `None`.
/// An open flat mesh's triangle normals sum to its plane's normal (times
/// twice its area); a closed mesh's cancel. A mesh counts as flat when
/// every vertex lies within a millionth of its size of that plane, far
/// less than any cascade's bias.
pub fn flat_plane(points: &[DVec3], indices: &[u32]) -> Option<(DVec3, f64)> {
    let normal: DVec3 = (indices.chunks_exact(3))
        .map(|t| {
            let [a, b, c] = [0, 1, 2].map(|k| points[t[k] as usize]);
            (b - a).cross(c - a)
        })
        .sum();
    let n = normal.try_normalize()?;
    let d = -n.dot(*points.first()?);
    let b = Aabb::around(points.iter().copied());
    let flat = 1e-6 * (b.hi - b.lo).length();
    points
        .iter()
        .all(|p| (n.dot(*p) + d).abs() <= flat)
        .then_some((n, d))
}
