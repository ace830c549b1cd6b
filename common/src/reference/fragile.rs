//! The receivers a rasteriser could flip, measured by the run itself.
//!
//! Two conformant GPUs draw the same frame a little differently: where a
//! triangle's edge crosses a pixel's (or a shadow map texel's) centre,
//! which one it covers is decided by how finely each snaps vertices
//! (Vulkan asks for at least 1/16 of a pixel, [`JITTER_PX`]); where a
//! receiver's depth and a shadow map's texel are within a few ulps, which
//! side of the compare it lands on is decided by each one's rounding.
//! Neither is the technique's doing, so the error figures of one technique
//! on two adapters differ by those pixels, and only those.
//!
//! The runner counts them: it draws the variant again at each of
//! [`JITTERS`], three offsets that each move, in the same frame,
//!
//! - the camera by [`JITTER_PX`] of a pixel: the receivers, and what is
//!   rasterised on screen (the lit pass, stencil volumes);
//! - every light's shadow map by [`LIGHT_JITTER_TEXELS`] of a texel
//!   ([`LightJitter`], which each shadow-map lesson applies where it builds
//!   a light's matrix, for drawing the map and for looking it up alike):
//!   what is rasterised in light space, the map's fragments and depth
//!   writes, and which texel a receiver reads.
//!
//! The camera moves nothing in a map, and a map's move nothing on screen
//! but the shadows, so one frame counts what each moves alone: a counter
//! is moved by one of them only, and the figures' bounds of lessons 03
//! and 04 come out within 13 % of those of separate frames, at no cost in
//! frames (acne's figures, which every frame draws anew, grow with the
//! number of frames: no bound makes them portable). A lesson that moved no
//! map (stencil volumes: no light space is rasterised) is drawn 3 times
//! more with every light turned instead, by the angle [`light_turn`]
//! finds, about the scene's centre ([`turned_lights`]): each shadow's
//! edge, the volumes' silhouettes and extrusions move by about
//! [`JITTER_PX`] on screen, against the receivers and casters whose
//! depths the volumes are tested against (depth ties). These are frames
//! of their own: turning the light and moving the camera change the same
//! counters, and in one frame their moves could cancel (lesson 08's
//! volume fragments: ±222 so, against ±316 with the camera alone). A
//! count the CPU makes from the turned light (silhouette edges, volume
//! triangles) moves too, but no adapter turns the light: the snapshots
//! keep such counts exact.
//!
//! Each offset asks which receivers then change surface or change side of
//! the lit threshold, and how far each counter moved. A figure that counts
//! pixels can move by at most that many of them; a figure that averages
//! |ΔV| by at most the mean change. [`Fragile::bounds`] gives each figure's
//! bound in the figure's own units, and the snapshots and the book's drift
//! test allow a figure to move between adapters by its bound
//! (`tests/support/tolerance.rs`).

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};

use serde::{Deserialize, Serialize};

use crate::reference::metrics::RECEIVER_MIN_N_DOT_L;
use crate::reference::soft_metrics::{BLEEDING_THRESHOLD, LIT_THRESHOLD};
use crate::reference::Reference;
use crate::scene::{Light, LightKind, Scene};

/// How far the camera moves (pixels, in x and in y): the coarsest sub-pixel
/// grid a conformant rasteriser may snap vertices to (Vulkan's
/// `subPixelPrecisionBits` >= 4).
pub const JITTER_PX: f64 = 1.0 / 16.0;

/// How far every light's shadow map moves (texels of the map, along its u
/// and v): the same sub-texel grid as [`JITTER_PX`], since the map is
/// rasterised like any target.
pub const LIGHT_JITTER_TEXELS: f64 = 1.0 / 16.0;

/// The offsets tried, in units of [`JITTER_PX`] (the camera, in pixels),
/// of [`LIGHT_JITTER_TEXELS`] (the lights' maps, in texels) and of
/// [`light_turn`] (the lights): three directions 120° apart. Their
/// components along any direction sum to zero, so every edge, whatever its
/// direction, is crossed from both sides.
pub const JITTERS: [[f64; 2]; 3] = [[0.0, 1.0], [-0.866_025, -0.5], [0.866_025, -0.5]];

/// The runner's move of every light's shadow map (`--fragile`), held by
/// `SceneGpu::light_jitter`: a lesson moves a map where it builds the
/// light's matrix for it ([`LightJitter::matrix`]), for drawing the map
/// and for looking it up alike.
#[derive(Debug, Default)]
pub struct LightJitter {
    /// Texels of the map, along its u and v: 0 (no move) but in the
    /// runner's moved frames.
    pub texels: [f64; 2],
    /// Whether a lesson moved a map since [`LightJitter::set`].
    used: AtomicBool,
}

impl LightJitter {
    /// Moves every map by `texels` from the next frame on.
    pub fn set(&mut self, texels: [f64; 2]) {
        self.texels = texels;
        self.used = AtomicBool::new(false);
    }

    /// The clip-space translation that moves a `size`² map's image by
    /// [`LightJitter::texels`]: pre-multiply the light's view-projection by
    /// it. The identity when nothing moves.
    pub fn matrix(&self, size: u32) -> glam::Mat4 {
        if self.texels == [0.0; 2] {
            return glam::Mat4::IDENTITY;
        }
        self.used.store(true, Ordering::Relaxed);
        jitter_matrix(self.texels, size, size)
    }

    /// Whether a lesson asked for a moved map since [`LightJitter::set`]:
    /// one without shadow maps (stencil volumes) never does.
    pub fn used(&self) -> bool {
        self.used.load(Ordering::Relaxed)
    }
}

/// What a run's sub-pixel jitter showed, over every light.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Default)]
pub struct Fragile {
    /// The jitter, pixels ([`JITTER_PX`]), and how many frames were drawn
    /// moved: 3 (camera and maps together), 6 where no map moved (then 3
    /// more with the lights turned).
    pub jitter_px: f64,
    pub offsets: u32,
    /// How far the lights' maps moved, texels ([`LIGHT_JITTER_TEXELS`]; 0
    /// where no map moved, or in a run that moved only the camera).
    #[serde(default)]
    pub light_jitter_texels: f64,
    /// Receivers (summed over lights) that changed surface or side of the
    /// lit threshold under some offset.
    pub flipped_pixels: u64,
    /// Per error figure (its `ErrorStats` / `SoftError` field name), how far
    /// it can move if only what moved under the jitter moves: in the
    /// figure's own units.
    pub bounds: BTreeMap<String, f64>,
    /// Per counter, how far it moved under the offsets, summed over them:
    /// fragments that tie in a depth test, or cover a pixel's or a map
    /// texel's centre by a hair. Each offset moves other fragments, and another rasteriser may
    /// move any of them, so the moves add (as the flipped pixels do).
    #[serde(default)]
    pub counters: BTreeMap<String, u64>,
}

/// One frame's images: object id (0 = nothing) and one light's visibility.
#[derive(Clone, Copy)]
pub struct Images<'a> {
    pub id: &'a [u32],
    pub visibility: &'a [f32],
}

/// Numerators and denominators of the bounds of one or more lights.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    receivers: u64,
    flipped: u64,
    dv_sum: f64,
    penumbra: u64,
    penumbra_dv_sum: f64,
    umbra: u64,
    umbra_flipped: u64,
    umbra_bleed_flipped: u64,
    umbra_dv_sum: f64,
    soft: bool,
    /// Per pixel class (lesson 09's cascades): its name, receivers and
    /// flipped receivers.
    classes: Vec<(String, u64, u64)>,
}

impl Tally {
    /// Per-class bounds too: `names` and one class index per pixel (the
    /// lesson's `pixel_classes`).
    pub fn with_classes(names: &[String]) -> Tally {
        Tally {
            classes: names.iter().map(|n| (n.clone(), 0, 0)).collect(),
            ..Tally::default()
        }
    }

    /// Adds light `light`'s receivers: `base` is the frame measured,
    /// `moved` the same variant drawn at each jitter, `class_of` each
    /// pixel's class (see [`Tally::with_classes`]).
    pub fn add(
        &mut self,
        reference: &Reference,
        light: usize,
        base: Images,
        moved: &[Images],
        class_of: Option<&[u8]>,
    ) {
        let (ref_vis, lit_by) = (&reference.visibility[light], &reference.lit_by[light]);
        let soft = reference.area_light[light];
        self.soft |= soft;
        for p in 0..reference.hits.len() {
            let Some(hit) = reference.hits[p] else {
                continue;
            };
            // The receivers of `metrics::compare`: the GPU sees the
            // reference's surface, which faces the light.
            if base.id[p] != hit.object + 1 || lit_by[p] <= RECEIVER_MIN_N_DOT_L {
                continue;
            }
            let v = base.visibility[p];
            let (mut flip, mut bleed_flip, mut dv) = (false, false, 0.0f32);
            for m in moved {
                if m.id[p] != base.id[p] {
                    (flip, bleed_flip, dv) = (true, true, 1.0);
                    continue;
                }
                let w = m.visibility[p];
                flip |= (w >= LIT_THRESHOLD) != (v >= LIT_THRESHOLD);
                bleed_flip |= (w > BLEEDING_THRESHOLD) != (v > BLEEDING_THRESHOLD);
                dv = dv.max((w - v).abs());
            }
            self.receivers += 1;
            self.flipped += u64::from(flip);
            if let Some(c) = class_of.and_then(|c| self.classes.get_mut(c[p] as usize)) {
                c.1 += 1;
                c.2 += u64::from(flip);
            }
            self.dv_sum += f64::from(dv);
            if soft {
                let exact = ref_vis[p];
                if exact <= 0.0 {
                    self.umbra += 1;
                    self.umbra_flipped += u64::from(flip);
                    self.umbra_bleed_flipped += u64::from(bleed_flip);
                    self.umbra_dv_sum += f64::from(dv);
                } else if exact < 1.0 {
                    self.penumbra += 1;
                    self.penumbra_dv_sum += f64::from(dv);
                }
            }
        }
    }

    /// The bounds, pooled over the lights added, of `offsets` moved frames
    /// (`map_moved`: the lights' maps moved with the camera).
    pub fn finish(&self, offsets: usize, map_moved: bool) -> Fragile {
        let share = |n: f64, of: u64| if of == 0 { 0.0 } else { n / of as f64 };
        let pct = |n: u64, of: u64| 100.0 * share(n as f64, of);
        let mut bounds = BTreeMap::new();
        let flipped = pct(self.flipped, self.receivers);
        for key in [
            "misclassified_pct",
            "false_shadow_pct",
            "false_lit_pct",
            "interior_misclassified_pct",
        ] {
            bounds.insert(key.to_string(), flipped);
        }
        bounds.insert("mean_abs".into(), share(self.dv_sum, self.receivers));
        for (name, receivers, flipped) in &self.classes {
            for key in ["misclassified_pct", "false_shadow_pct", "false_lit_pct"] {
                bounds.insert(format!("class {name} {key}"), pct(*flipped, *receivers));
            }
        }
        if self.soft {
            bounds.insert(
                "penumbra_mean_abs".into(),
                share(self.penumbra_dv_sum, self.penumbra),
            );
            bounds.insert(
                "umbra_misclassified_pct".into(),
                pct(self.umbra_flipped, self.umbra),
            );
            bounds.insert(
                "light_bleeding_pct".into(),
                pct(self.umbra_bleed_flipped, self.umbra),
            );
            bounds.insert(
                "umbra_mean_abs".into(),
                share(self.umbra_dv_sum, self.umbra),
            );
        }
        Fragile {
            jitter_px: JITTER_PX,
            offsets: offsets as u32,
            light_jitter_texels: if map_moved { LIGHT_JITTER_TEXELS } else { 0.0 },
            flipped_pixels: self.flipped,
            bounds,
            counters: BTreeMap::new(),
        }
    }
}

impl Fragile {
    /// The bounds of two runs together (two adapters, each measured): how
    /// far a figure may move between them. Each rasteriser flips only
    /// pixels its own run found fragile, so the images differ by at most
    /// both sets: every bound and counter move is the sum of the two (a key
    /// one run lacks counts as 0 there).
    pub fn plus(&self, other: &Fragile) -> Fragile {
        let mut bounds = self.bounds.clone();
        for (k, b) in &other.bounds {
            *bounds.entry(k.clone()).or_insert(0.0) += b;
        }
        let mut counters = self.counters.clone();
        for (k, n) in &other.counters {
            *counters.entry(k.clone()).or_insert(0) += n;
        }
        Fragile {
            jitter_px: self.jitter_px.max(other.jitter_px),
            offsets: self.offsets + other.offsets,
            light_jitter_texels: self.light_jitter_texels.max(other.light_jitter_texels),
            flipped_pixels: self.flipped_pixels + other.flipped_pixels,
            bounds,
            counters,
        }
    }
}

/// Per counter, how far `moved` differ from `base`, summed over them (a
/// counter missing from one side moved by its whole value).
pub fn counter_moves(
    base: &BTreeMap<String, u64>,
    moved: &[BTreeMap<String, u64>],
) -> BTreeMap<String, u64> {
    base.iter()
        .map(|(k, &c)| {
            let sum = moved
                .iter()
                .map(|m| m.get(k).map_or(c, |&d| c.abs_diff(d)))
                .sum();
            (k.clone(), sum)
        })
        .collect()
}

/// The clip-space translation that moves the image by `px` pixels (x
/// right, y up) in a `width × height` frame: pre-multiply a view-projection
/// matrix by it.
pub fn jitter_matrix(px: [f64; 2], width: u32, height: u32) -> glam::Mat4 {
    let (tx, ty) = (2.0 * px[0] / width as f64, 2.0 * px[1] / height as f64);
    glam::Mat4::from_translation(glam::Vec3::new(tx as f32, ty as f32, 0.0))
}

/// The angle (radians) every light turns per unit of an offset's
/// `light_turn`: the one under which the scene's bounding sphere sees
/// [`JITTER_PX`] of a pixel at its centre (the camera's pixel, at the
/// centre's depth, `height` pixels high). A shadow's edge lies within the
/// sphere's diameter of its caster, so it moves on the receivers by up to
/// about that much: what the volumes' silhouettes and extrusions move by.
pub fn light_turn(scene: &Scene, height: u32) -> f64 {
    let (lo, hi) = scene.bounds();
    let (centre, radius) = ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1e-9));
    let c = &scene.camera;
    let forward = (c.target - c.eye).normalize_or_zero();
    let depth = (centre - c.eye).dot(forward).max(c.near);
    let pixel = 2.0 * depth * (c.fov_y_deg.to_radians() * 0.5).tan() / f64::from(height.max(1));
    JITTER_PX * pixel / radius
}

/// The scene's lights turned about the scene's centre by `angle` radians
/// ([`light_turn`]) times `by`, across the light's rays (along two axes
/// perpendicular to them): a directional light's direction turns, a point
/// or spot light's position moves on its sphere about the centre (a spot
/// keeps its direction). Their colour, size and range stay.
pub fn turned_lights(scene: &Scene, angle: f64, by: [f64; 2]) -> Vec<Light> {
    let (lo, hi) = scene.bounds();
    let centre = (lo + hi) * 0.5;
    // Two unit axes across `w`, and the move along them.
    let across = |w: glam::DVec3| {
        let u = w.cross(crate::scene::camera::stable_up(w)).normalize();
        let v = u.cross(w);
        (u * by[0] + v * by[1]) * angle
    };
    let turn = |l: &Light| {
        let kind = match l.kind {
            LightKind::Directional { direction } => {
                let w = direction.normalize();
                let direction = (w + across(w)).normalize();
                LightKind::Directional { direction }
            }
            LightKind::Point { position, range } => LightKind::Point {
                position: moved(position, centre, across),
                range,
            },
            LightKind::Spot {
                position,
                direction,
                range,
                spot_angle_deg,
            } => LightKind::Spot {
                position: moved(position, centre, across),
                direction,
                range,
                spot_angle_deg,
            },
        };
        Light { kind, ..*l }
    };
    scene.lights.iter().map(turn).collect()
}

/// `position` moved across its ray from `centre` by `across(ray)` times
/// its distance: turned about the centre (unmoved at the centre).
fn moved(
    position: glam::DVec3,
    centre: glam::DVec3,
    across: impl Fn(glam::DVec3) -> glam::DVec3,
) -> glam::DVec3 {
    let d = position - centre;
    let r = d.length();
    if r < 1e-12 {
        return position;
    }
    position + across(d / r) * r
}

#[cfg(test)]
mod tests {
    use super::Fragile;
    use crate::measure::counters::{DRAWS, STENCIL_UPDATES};

    #[test]
    fn two_runs_bounds_add() {
        let a = Fragile {
            jitter_px: 0.0625,
            offsets: 3,
            light_jitter_texels: 0.0625,
            flipped_pixels: 10,
            bounds: [("misclassified_pct".to_string(), 0.1)].into(),
            counters: [(STENCIL_UPDATES.name.to_string(), 100)].into(),
        };
        let b = Fragile {
            flipped_pixels: 4,
            bounds: [
                ("misclassified_pct".to_string(), 0.05),
                ("mean_abs".to_string(), 0.01),
            ]
            .into(),
            counters: [(DRAWS.name.to_string(), 1)].into(),
            ..a.clone()
        };
        let s = a.plus(&b);
        assert!((s.bounds["misclassified_pct"] - 0.15).abs() < 1e-12);
        assert_eq!(s.bounds["mean_abs"], 0.01);
        assert_eq!(s.counters[STENCIL_UPDATES.name], 100);
        assert_eq!(s.counters[DRAWS.name], 1);
        assert_eq!((s.flipped_pixels, s.offsets), (14, 6));
    }

    /// A turned light moves across its rays by the angle asked, and the
    /// three offsets, summed, move it back (to first order).
    #[test]
    fn lights_turn_across_their_rays() {
        let text = r#"
[camera]
eye = [0.0, 2.0, 10.0]
target = [0.0, 0.0, 0.0]
fov_y_deg = 60.0
[[objects]]
mesh = "cube"
[[lights]]
type = "directional"
direction = [0.3, -1.0, 0.2]
[[lights]]
type = "point"
position = [1.0, 4.0, 0.0]
range = 20.0
"#;
        let scene = crate::scene::Scene::parse(text, "test", std::path::Path::new(".")).unwrap();
        let angle = super::light_turn(&scene, 360);
        // 1/16 of a pixel at the centre's depth, over the bounds' radius.
        let (lo, hi) = scene.bounds();
        let centre = (lo + hi) * 0.5;
        let eye = scene.camera.eye;
        let depth = (centre - eye).dot((scene.camera.target - eye).normalize());
        let pixel = 2.0 * depth * 30f64.to_radians().tan() / 360.0;
        let radius = (hi - lo).length() * 0.5;
        assert!((angle - pixel / 16.0 / radius).abs() < 1e-12, "{angle}");
        let mut sum = glam::DVec3::ZERO;
        for j in super::JITTERS {
            let turned = super::turned_lights(&scene, angle, j);
            let (
                crate::scene::LightKind::Directional { direction: a },
                crate::scene::LightKind::Directional { direction: b },
            ) = (scene.lights[0].kind, turned[0].kind)
            else {
                panic!("directional");
            };
            // |a × b| = sin(atan(angle)): exact where acos is not.
            let sin = a.normalize().cross(b).length();
            assert!((sin - angle).abs() < 1e-5 * angle, "{sin} {angle}");
            let (
                crate::scene::LightKind::Point { position: p, .. },
                crate::scene::LightKind::Point { position: q, .. },
            ) = (scene.lights[1].kind, turned[1].kind)
            else {
                panic!("point");
            };
            // Across the ray from the centre, by angle × distance.
            let ray = p - scene.origin();
            assert!((q - p).dot(ray).abs() < 1e-9);
            let r = angle * ray.length();
            assert!(((q - p).length() - r).abs() < 1e-6 * r);
            sum += q - p;
        }
        assert!(sum.length() < 1e-6 * angle, "{sum}");
    }
}
