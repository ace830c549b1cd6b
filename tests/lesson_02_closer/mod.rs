//! lesson_02's closer look, pixel by pixel: the exact reference of a scene
//! ray-cast in the test process, read against a variant's visibility PNG
//! on the floor (acne, lost shadow, the gap at a caster's foot), and the
//! per-axis model of the floor's acne. Used by `tests/lesson_02.rs`.

use common::glam::{DVec3, Vec3};
use common::measure::counters::SHADOW_MAP_SIZE;
use common::reference::{render_reference, Reference};
use common::scene::camera::{camera_matrices, light_view_proj};
use common::scene::{LightKind, Scene};

// ---- a closer look, pixel by pixel ------------------------------------------

/// The scene and its exact reference at the size the lesson ran.
pub struct Closer {
    scene: Scene,
    reference: Reference,
    /// The larger side of one shadow-map texel (light 0, directional) in
    /// world units: the unit of the gaps below.
    pub texel: f64,
    /// The floor's acne model: a texel's extent along the floor's depth
    /// gradient from the map's u and v sides (their sum is "a texel" of
    /// `shadow_texel_size`), and tan θ of the floor.
    pub floor_along_u: f64,
    pub floor_along_v: f64,
    pub floor_tan: f64,
}

impl Closer {
    pub fn new(scene: &str, size: (u32, u32), map_size: u64) -> Closer {
        let scene = Scene::load(&support::scene_path(scene)).expect("scene loads");
        let cam = camera_matrices(&scene, size.0, size.1);
        let reference = render_reference(&scene, cam.view_proj, size.0, size.1);
        // A texel is 2/N of NDC; the light's x_ndc = row 0 · p (orthographic).
        let m = light_view_proj(&scene, 0)
            .expect("a directional light")
            .as_dmat4();
        let row = |i: usize| DVec3::new(m.x_axis[i], m.y_axis[i], m.z_axis[i]);
        let (u, v) = (row(0), row(1));
        let extent = |r: DVec3| 2.0 / (map_size as f64 * r.length());
        let texel = extent(u).max(extent(v));
        // The floor (normal +Y) falls away from the light fastest along g.
        let l = match scene.lights[0].kind {
            LightKind::Directional { direction } => -direction.normalize(),
            _ => panic!("the closer look needs a directional light"),
        };
        let (n, cos_t) = (DVec3::Y, l.y);
        let g = (n - cos_t * l).normalize();
        Closer {
            floor_along_u: extent(u) * g.dot(u.normalize()).abs(),
            floor_along_v: extent(v) * g.dot(v.normalize()).abs(),
            floor_tan: (1.0 - cos_t * cos_t).sqrt() / cos_t,
            scene,
            reference,
            texel,
        }
    }

    /// The floor acne (percent) that a bias of `bias` world units leaves,
    /// per the per-axis model: the receiver sits Δ from its texel's centre,
    /// Δ uniform over the texel, and lies Δ·∇d = tan θ (a·x + b·y) behind the
    /// stored depth, x and y uniform in [-1/2, 1/2].
    pub fn floor_acne_model_pct(&self, bias: f64) -> f64 {
        let (a, b, k) = (self.floor_along_u, self.floor_along_v, 400);
        let cell = |i: u32| (i as f64 + 0.5) / k as f64 - 0.5;
        let behind = (0..k * k)
            .filter(|i| self.floor_tan * (a * cell(i % k) + b * cell(i / k)) > bias)
            .count();
        100.0 * behind as f64 / (k * k) as f64
    }

    /// The floor pixels that face light 0, with what the reference says.
    fn floor(&self) -> impl Iterator<Item = (usize, Vec3, bool)> + '_ {
        let r = &self.reference;
        (0..r.hits.len()).filter_map(move |p| {
            let h = r.hits[p]?;
            (h.object == 0 && r.lit_by[0][p] > 0.0).then_some((
                p,
                h.position,
                r.visibility[0][p] >= 0.5,
            ))
        })
    }

    /// Distance from an origin-relative point to object `i`'s unit box.
    fn distance_to(&self, i: usize, p: Vec3) -> f64 {
        let model = self.scene.objects[i].model;
        let world = p.as_dvec3() + self.scene.origin();
        let local = model.inverse().transform_point3(world);
        let inside = model.transform_point3(local.clamp(DVec3::splat(-0.5), DVec3::splat(0.5)));
        world.distance(inside)
    }

    /// Percent of the floor's lit pixels (reference) that the GPU shadows:
    /// acne on the floor, whatever its N·L.
    pub fn floor_acne_pct(&self, gpu: &Gpu) -> f64 {
        let (mut n, mut bad) = (0u32, 0u32);
        for (p, _, lit) in self.floor() {
            if lit && gpu.covered[p] {
                n += 1;
                bad += (gpu.vis[p] < 0.5) as u32;
            }
        }
        100.0 * bad as f64 / n.max(1) as f64
    }

    /// Percent of the floor's shadowed pixels (reference) nearest to
    /// `caster`, and more than 1.5 texels inside the shadow, that the GPU
    /// lights: the share of its shadow that is lost, edges left out.
    pub fn shadow_lost_pct(&self, gpu: &Gpu, caster: usize) -> f64 {
        let (w, h) = (
            self.reference.width as usize,
            self.reference.height as usize,
        );
        let floor: Vec<Option<(Vec3, bool)>> = {
            let mut f = vec![None; w * h];
            for (p, pos, lit) in self.floor() {
                f[p] = Some((pos, lit));
            }
            f
        };
        // The lit floor pixels on the shadow's outline.
        let outline: Vec<Vec3> = (0..w * h)
            .filter_map(|p| {
                let (pos, lit) = floor[p]?;
                let (x, y) = (p % w, p / w);
                let near = [
                    (x > 0, p.wrapping_sub(1)),
                    (x + 1 < w, p + 1),
                    (y > 0, p.wrapping_sub(w)),
                    (y + 1 < h, p + w),
                ];
                (lit && near
                    .iter()
                    .any(|&(ok, q)| ok && floor[q].is_some_and(|(_, l)| !l)))
                .then_some(pos)
            })
            .collect();
        let (mut n, mut bad) = (0u32, 0u32);
        for (p, pos, lit) in self.floor() {
            if lit || !gpu.covered[p] || self.nearest_caster(pos) != caster {
                continue;
            }
            let inside = outline
                .iter()
                .map(|o| o.distance(pos))
                .fold(f32::INFINITY, f32::min) as f64
                / self.texel;
            if inside > 1.5 {
                n += 1;
                bad += (gpu.vis[p] >= 0.5) as u32;
            }
        }
        100.0 * bad as f64 / n.max(1) as f64
    }

    fn nearest_caster(&self, p: Vec3) -> usize {
        (1..self.scene.objects.len())
            .min_by(|&a, &b| self.distance_to(a, p).total_cmp(&self.distance_to(b, p)))
            .unwrap_or(0)
    }

    /// Peter Panning at `caster`'s foot, in texels: the widest lit gap
    /// between the foot and the shadow. The foot is the floor in the
    /// caster's shadow (reference) within one texel of the caster; at each
    /// foot pixel the gap is the distance to the nearest floor pixel that the
    /// GPU shadows (0 where it shadows the foot itself). Infinite when the
    /// GPU shadows none of the caster's shadow.
    pub fn contact_gap_texels(&self, gpu: &Gpu, caster: usize) -> f64 {
        let mut foot = Vec::new();
        let mut shadowed = Vec::new();
        for (p, pos, lit) in self.floor() {
            if lit || !gpu.covered[p] || self.nearest_caster(pos) != caster {
                continue;
            }
            if self.distance_to(caster, pos) <= self.texel {
                foot.push(pos);
            }
            if gpu.vis[p] < 0.5 {
                shadowed.push(pos);
            }
        }
        let gap = |f: &Vec3| {
            shadowed
                .iter()
                .map(|s| s.distance(*f))
                .fold(f32::INFINITY, f32::min) as f64
        };
        foot.iter().map(gap).fold(0.0, f64::max) / self.texel
    }
}

/// One variant's visibility, read back from its PNG.
pub struct Gpu {
    covered: Vec<bool>,
    vis: Vec<f32>,
}

pub fn gpu(run: &support::LessonRun, variant: &str) -> Gpu {
    let (ids, vis, _, _) =
        support::read_visibility(&run.out.join(format!("{variant}_visibility_l0.png")));
    Gpu {
        covered: ids.iter().map(|&i| i != 0).collect(),
        vis,
    }
}

pub fn map_size(run: &support::LessonRun) -> u64 {
    run.report["variants"][0]["counters"][SHADOW_MAP_SIZE.name]
        .as_u64()
        .expect("counters.shadow_map_size")
}
