//! # Lesson 04: cube-map point shadows
//!
//! A point light sees in every direction, so one frustum is not enough: it
//! renders six 90° faces into a cube of depth layers, and the lit pass looks
//! the cube up with the direction from the light. Two ways to store depth
//! (linear distance, hardware depth compared along the major axis), a bias
//! that grows with distance, 3D PCF, and culling of faces and casters the
//! scene does not need, measured against the unculled frame. Then the
//! defaults of renderers people use (LearnOpenGL, Bevy: [`peers`]).
//!
//! [`peers`]: workbook::lesson_04::peers
//!
//! Run: `cargo run --release --bin lesson_04 -- --headless`
//! Book: chapter "04 Cube-map point shadows" (`book/src/lesson_04.md`).

use clap::ValueEnum;
use common::glam::DVec3;
use common::gpu::lit::LitPass;
use common::gpu::render::{shader_module_from_files, SceneGpu};
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::run::lesson::Lesson;
use common::run::per_variant::PerVariant;
use common::scene::{LightKind, Scene};
use common::Result;
use workbook::lesson_01::tally::TallyShader;
use workbook::lesson_04::costs;
use workbook::lesson_04::cube_map::{self, CubeParams, CubeShadowMap, LitKey, Storage};
use workbook::lesson_04::culling::{self, face_casters, FaceTest, Sphere};
use workbook::lesson_04::face_rects::FaceRectCache;
use workbook::lesson_04::faces::{point_light, FaceRects, FaceUniforms};
use workbook::lesson_04::peers::{self, Peer, Port};

mod harness;
use harness::CubeStats;

// ANCHOR: variants
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    #[value(name = "linear_256")]
    Linear256,
    #[value(name = "linear_1024")]
    Linear1024,
    #[value(name = "linear_2048")]
    Linear2048,
    #[value(name = "depth_1024")]
    Depth1024,
    #[value(name = "depth_euclid_1024")]
    DepthEuclid1024,
    #[value(name = "const_bias_1024")]
    ConstBias1024,
    #[value(name = "pcf3d_1024")]
    Pcf3d1024,
    #[value(name = "pcf3d_slope1_1024")]
    Pcf3dSlope1_1024,
    #[value(name = "nocull_1024")]
    Nocull1024,
    #[value(name = "clipped_1024")]
    Clipped1024,
    #[value(name = "no_range_clamp_1024")]
    NoRangeClamp1024,
    /// The renderers' point shadows, each on its own cube ([`peers`]; their
    /// source lines: `port_cards`). LearnOpenGL, one tap and its 20-tap disk:
    #[value(name = "learnopengl_1tap")]
    LearnOpenGl1Tap,
    #[value(name = "learnopengl_pcf20")]
    LearnOpenGlPcf20,
    /// Bevy's `PointLight` defaults and its Gaussian filter.
    #[value(name = "bevy_point")]
    BevyPoint,
    /// The chapter's exercises (`exercises.rs`, `exercises.wgsl`), run only when named.
    #[value(name = "exercise_cull_faces")]
    ExerciseCullFaces,
    #[value(name = "exercise_cube_faces")]
    ExerciseCubeFaces,
}

#[derive(Clone, Copy)]
struct Settings {
    size: u32,
    storage: Storage,
    /// Bias in texels of the point's own distance, plus `slope` × tan θ texels.
    bias_texels: f32,
    slope: f32,
    /// A constant world-space bias instead (the one that does not scale).
    bias_world: f32,
    /// 3D PCF radius in texels; 0 is one hard tap.
    pcf: f32,
    /// Skip out-of-range casters, and per face the casters this test says
    /// the face cannot see (the unculled frame must match); `None`: no culling.
    cull: Option<FaceTest>,
    /// The faces' near and far planes (m; `None`: the light's range).
    near: f64,
    far: Option<f64>,
    /// Near-plane clipping off (DEPTH_CLIP_CONTROL) so casters nearer than it still cast.
    unclipped: bool,
    /// Clamp receivers beyond the range to the far plane.
    clamp_range: bool,
    /// A renderer's lookup in place of the lesson's.
    peer: Peer,
}

/// `linear_1024`: the baseline the others change one thing of, not a
/// verdict (`depth_1024` measures the same error in less time: chapter 04).
const BASE: Settings = Settings {
    size: 1024,
    storage: Storage::Linear,
    bias_texels: 1.0,
    slope: 1.0,
    bias_world: 0.0,
    pcf: 0.0,
    cull: Some(sphere_test),
    near: NEAR,
    far: None,
    unclipped: true,
    clamp_range: true,
    peer: Peer::None,
};

/// A renderer's defaults: its own cube, planes and world-space bias, none
/// of ours (the culling stays: it changes no pixel).
#[rustfmt::skip]
const fn port(p: Port) -> Settings {
    Settings {
        size: p.size, storage: p.storage, near: p.near, far: p.far, unclipped: !p.clipped,
        bias_world: p.bias_world, bias_texels: 0.0, slope: 0.0,
        clamp_range: p.clamp_range, peer: p.lookup, ..BASE
    }
}

impl Variant {
    // One line per variant: what changes from BASE.
    #[rustfmt::skip]
    fn settings(self) -> Settings {
        match self {
            Variant::Linear256 => Settings { size: 256, ..BASE },
            Variant::Linear1024 => BASE,
            Variant::Linear2048 => Settings { size: 2048, ..BASE },
            Variant::Depth1024 => Settings { storage: Storage::Depth, ..BASE },
            Variant::DepthEuclid1024 => Settings { storage: Storage::DepthEuclid, ..BASE },
            Variant::ConstBias1024 => Settings { bias_texels: 0.0, slope: 0.0, bias_world: 0.003, ..BASE },
            // 3D PCF also raises the slope bias, by its radius: reported
            // as counters.slope_bias_millitexels, and without it below.
            Variant::Pcf3d1024 => Settings { pcf: PCF3D_RADIUS, slope: BASE.slope + PCF3D_RADIUS, ..BASE },
            Variant::Pcf3dSlope1_1024 => Settings { pcf: PCF3D_RADIUS, ..BASE },
            Variant::Nocull1024 => Settings { cull: None, ..BASE },
            Variant::Clipped1024 => Settings { unclipped: false, ..BASE },
            Variant::NoRangeClamp1024 => Settings { clamp_range: false, ..BASE },
            Variant::LearnOpenGl1Tap => port(peers::LEARNOPENGL_1TAP),
            Variant::LearnOpenGlPcf20 => port(peers::LEARNOPENGL_PCF20),
            Variant::BevyPoint => port(peers::BEVY_POINT),
            // Graded against linear_1024 and depth_1024 (exercises.toml).
            Variant::ExerciseCullFaces => Settings { cull: Some(exercise_face_test), ..BASE },
            Variant::ExerciseCubeFaces => Settings { storage: Storage::DepthExercise, ..BASE },
        }
    }
}

/// 3D PCF's radius in texels. Its taps sit up to this far to the side of the
/// receiver, where a slope at θ is this × tan θ texels nearer the light, so
/// `pcf3d_1024` adds it to the slope bias (1 + 1.5 = 2.5 texels × tan θ);
/// `pcf3d_slope1_1024` keeps the baseline's 1 and shows what that costs.
const PCF3D_RADIUS: f32 = 1.5;

/// The lesson's near plane of every face; 1 mm where DEPTH_CLIP_CONTROL is missing.
const NEAR: f64 = 0.05;
const NEAR_FALLBACK: f64 = 0.001;
// ANCHOR_END: variants

/// The lesson's test: the sphere only.
fn sphere_test(centre: DVec3, radius: f64, _half: DVec3, face: usize) -> bool {
    culling::sphere_touches_face(centre, radius, face)
}

/// `exercise_cull_faces`: the student's [`exercises::faces_touched`](workbook::lesson_04::exercises::faces_touched), on
/// the box.
fn exercise_face_test(centre: DVec3, _radius: f64, half: DVec3, face: usize) -> bool {
    workbook::exercise!(lesson_04::faces_touched(centre, half))[face]
}

/// One variant on this device: its pipeline, lit-pass bind group, map and
/// planes, its knob `face_scissor`, and the face passes' depth writes and
/// fragments, counted once.
struct Prepared {
    pipeline: usize,
    /// Index into `lit_pipelines`.
    lit: usize,
    group: wgpu::BindGroup,
    map: usize,
    near: f64,
    far: Option<f64>,
    unclipped: bool,
    /// Each face drawn only over its rectangle (`harness.rs`); on by default.
    scissor: bool,
    texels_written: Option<(u64, u64)>,
}

struct CubeShadows {
    /// One per [`LitKey`] the variants use.
    lit_pipelines: Vec<wgpu::RenderPipeline>,
    shadow_pipelines: Vec<wgpu::RenderPipeline>,
    /// Their counting copies ([`costs::cube_tally_pipelines`]).
    tally_pipelines: Vec<[wgpu::RenderPipeline; 2]>,
    maps: Vec<CubeShadowMap>,
    /// Each variant's pipelines, map and planes.
    prepared: PerVariant<Variant, Prepared>,
    faces: FaceUniforms,
    spheres: Vec<Sphere>,
    stats: CubeStats,
    /// The last frame's draw calls ([`costs::frame_draws`]).
    draws: u64,
    /// Each face's rectangle per light (`harness.rs`).
    rects: FaceRectCache,
}

impl Lesson for CubeShadows {
    const NAME: &'static str = "lesson_04";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_04.toml");
    type Variant = Variant;

    fn check_scene(scene: &Scene) -> Result<()> {
        if let Some(k) = scene
            .lights
            .iter()
            .position(|l| matches!(l.kind, LightKind::Directional { .. }))
        {
            anyhow::bail!("lights[{k}]: lesson_04 shadows point (and spot) lights; directional lights are lessons lesson_01-lesson_03");
        }
        Ok(())
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        // The lesson's shader, the renderers' lookups, the exercise's function.
        let exercises_path = workbook::exercises_wgsl_path("lesson_04");
        let files = [
            (
                "shaders/lesson_04/cube_map.wgsl",
                include_str!("../../shaders/lesson_04/cube_map.wgsl"),
            ),
            (
                "shaders/lesson_04/peers.wgsl",
                include_str!("../../shaders/lesson_04/peers.wgsl"),
            ),
            (
                exercises_path.as_str(),
                workbook::exercise!(lesson_04::EXERCISES_WGSL),
            ),
        ];
        let module = shader_module_from_files(gpu, "lesson_04", &files)?;
        let params_size = std::mem::size_of::<CubeParams>() as u64;
        let layout = cube_map::cube_map_layout(gpu, params_size, false);
        let faces_layout = cube_map::cube_map_layout(gpu, params_size, true);
        let (mut lit_keys, mut lit_pipelines) = (Vec::<LitKey>::new(), Vec::new());
        let has_unclipped = gpu.has(wgpu::Features::DEPTH_CLIP_CONTROL);
        let tally = TallyShader::new(gpu);
        let (mut maps, mut shadow_pipelines, mut tally_pipelines, mut keys) = (
            Vec::<CubeShadowMap>::new(),
            Vec::new(),
            Vec::new(),
            Vec::new(),
        );
        let prepared = PerVariant::new(|variant: Variant| {
            let v = variant.settings();
            // The exercise's lookup reads its own map, as a 2D array.
            let faces = v.storage == Storage::DepthExercise;
            let map = maps
                .iter()
                .position(|m| m.size == v.size && m.faces == faces)
                .unwrap_or_else(|| {
                    maps.push(match faces {
                        false => CubeShadowMap::new(gpu, v.size),
                        true => CubeShadowMap::new_faces(gpu, v.size),
                    });
                    maps.len() - 1
                });
            // Without DEPTH_CLIP_CONTROL (GL), fall back to a 1 mm near plane (reported).
            let unclipped = v.unclipped && has_unclipped;
            let near = if v.unclipped && !has_unclipped {
                NEAR_FALLBACK
            } else {
                v.near
            };
            let storage = v.storage.pass();
            let pipeline = keys
                .iter()
                .position(|k| *k == (storage, unclipped))
                .unwrap_or_else(|| {
                    shadow_pipelines.push(cube_map::cube_shadow_pipeline(
                        gpu, scene, &module, storage, unclipped,
                    ));
                    tally_pipelines.push(costs::cube_tally_pipelines(
                        gpu, scene, &module, storage, unclipped, &tally,
                    ));
                    keys.push((storage, unclipped));
                    keys.len() - 1
                });
            let (peer, peer_scale) = v.peer.params(v.size);
            let key = LitKey {
                storage: v.storage as u32,
                peer,
                filtered: v.pcf > 0.0,
                clamp_range: v.clamp_range,
            };
            let lit = lit_keys.iter().position(|k| *k == key).unwrap_or_else(|| {
                let layout = if faces { &faces_layout } else { &layout };
                lit_pipelines.push(key.pipeline(gpu, scene, &module, layout));
                lit_keys.push(key);
                lit_keys.len() - 1
            });
            let params = CubeParams {
                near: near as f32,
                texel_at_1m: 2.0 / v.size as f32,
                far: v.far.unwrap_or(0.0) as f32,
                bias_world: v.bias_world,
                bias_texels: v.bias_texels,
                slope: v.slope,
                pcf: v.pcf,
                peer_scale,
            };
            let filter = if v.pcf > 0.0 || v.peer.linear() {
                wgpu::FilterMode::Linear
            } else {
                wgpu::FilterMode::Nearest
            };
            let group = cube_map::cube_map_group(
                gpu,
                if faces { &faces_layout } else { &layout },
                &maps[map],
                filter,
                bytemuck::bytes_of(&params),
            );
            Prepared {
                pipeline,
                lit,
                group,
                map,
                near,
                far: v.far,
                unclipped,
                scissor: true,
                texels_written: None,
            }
        });
        let faces = FaceUniforms::new(gpu, scene);
        let spheres = culling::bounding_spheres(&scene.scene);
        Ok(CubeShadows {
            lit_pipelines,
            shadow_pipelines,
            tally_pipelines,
            maps,
            prepared,
            faces,
            spheres,
            stats: CubeStats::default(),
            draws: 0,
            rects: FaceRectCache::default(),
        })
    }

    /// The harness around [`CubeShadows::draw`]: the face passes' depth
    /// writes counted once per variant (their own submits, left out of the
    /// frame's times), and the faces and draws the frame's passes made.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        // The runner's sub-texel move of the faces (`--fragile`).
        let size = variant.settings().size;
        self.faces.jitter = scene.light_jitter.matrix(size);
        self.count_texels_once(frame, scene, variant)?;
        let drawn = self.draw(frame, scene, targets, variant);
        self.record_draws(scene, &drawn);
        Ok(())
    }
}

impl CubeShadows {
    // ANCHOR: render
    /// One frame: per light, the six faces' matrices for where it is, the
    /// face passes (each face's casters culled as the variant says, each
    /// face drawn over its rectangle), then the lit pass. Returns each
    /// light's draws and rectangle per face.
    fn draw(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Vec<([u32; 6], FaceRects)> {
        let v = variant.settings();
        let (near, far) = (self.prepared[variant].near, v.far);
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        let mut drawn = Vec::new();
        for light in 0..scene.scene.lights.len() {
            self.faces.write(frame.gpu, &scene.scene, light, near, far);
            let at = point_light(&scene.scene, self.faces.origin, light)
                .expect("check_scene allows point and spot lights");
            let rects = self.face_rects(scene, variant, light, at);
            let p = &self.prepared[variant];
            let casters = |face| face_casters(scene, &self.spheres, at, v.cull, face);
            let map = &mut self.maps[p.map];
            let pipeline = &self.shadow_pipelines[p.pipeline];
            let faces = &self.faces;
            let drawn_here = cube_map::cube_shadow_passes(
                frame,
                scene,
                pipeline,
                map,
                faces,
                (light, &rects),
                casters,
            );
            drawn.push((drawn_here, rects));
            let lit = &self.lit_pipelines[p.lit];
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    LitPass::new(light, lit, &[&p.group]),
                    ts.render(),
                )
            });
        }
        drawn
    }
    // ANCHOR_END: render
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<CubeShadows>()
}
