//! # Lesson 04: cube-map point shadows
//!
//! A point light sees in every direction, so one frustum is not enough: it
//! renders six 90° faces into a cube of depth layers, and the lit pass looks
//! the cube up with the direction from the light. Two ways to store depth
//! (linear distance, hardware depth compared along the major axis), a bias
//! that grows with distance, 3D PCF, and culling of faces and casters the
//! scene does not need, measured against the unculled frame.
//!
//! Run: `cargo run --release --bin lesson_04 -- --headless`
//! Book: chapter "04 Cube-map point shadows" (`book/src/lesson_04.md`).

use std::collections::BTreeMap;
use std::path::Path;

use common::app::{self, Lesson};
use common::cube_shadow::{self, CubeShadowMap, CubeStats, DepthStorage, FaceUniforms, Sphere};
use common::gpu::Gpu;
use common::render::{shader_module, FrameTargets, SceneGpu};
use common::scene::{LightKind, Scene};
use common::timing::Frame;
use common::Result;

// ANCHOR: variants
#[derive(Clone, Copy, PartialEq)]
enum Storage {
    /// distance / range, from the fragment shader.
    Linear,
    /// The face's hardware depth, the receiver converted along its major axis.
    Depth,
    /// Hardware depth compared with |v| instead: the naive mistake.
    DepthEuclid,
}

#[derive(Clone, Copy)]
struct Variant {
    name: &'static str,
    size: u32,
    storage: Storage,
    /// Bias in texels of the point's own distance, plus `slope` × tan θ texels.
    bias_texels: f32,
    slope: f32,
    /// A constant world-space bias instead (the one that does not scale).
    bias_world: f32,
    /// 3D PCF radius in texels; 0 is one hard tap.
    pcf: f32,
    /// Skip empty faces and out-of-range casters (the unculled frame must match).
    cull: bool,
    /// Near-plane clipping off (DEPTH_CLIP_CONTROL) so casters nearer than it still cast.
    unclipped: bool,
    /// Clamp receivers beyond the range to the far plane.
    clamp_range: bool,
}

const BEST: Variant = Variant {
    name: "linear_1024",
    size: 1024,
    storage: Storage::Linear,
    bias_texels: 1.0,
    slope: 1.0,
    bias_world: 0.0,
    pcf: 0.0,
    cull: true,
    unclipped: true,
    clamp_range: true,
};

// One line per variant: what changes from BEST.
#[rustfmt::skip]
const VARIANTS: [Variant; 10] = [
    Variant { name: "linear_256", size: 256, ..BEST },
    BEST,
    Variant { name: "linear_2048", size: 2048, ..BEST },
    Variant { name: "depth_1024", storage: Storage::Depth, ..BEST },
    Variant { name: "depth_euclid_1024", storage: Storage::DepthEuclid, ..BEST },
    Variant { name: "const_bias_1024", bias_texels: 0.0, slope: 0.0, bias_world: 0.003, ..BEST },
    Variant { name: "pcf3d_1024", pcf: 1.5, slope: 2.5, ..BEST },
    Variant { name: "nocull_1024", cull: false, ..BEST },
    Variant { name: "clipped_1024", unclipped: false, ..BEST },
    Variant { name: "no_range_clamp_1024", clamp_range: false, ..BEST },
];

/// The near plane of every face; 1 mm where DEPTH_CLIP_CONTROL is missing.
const NEAR: f64 = 0.05;
const NEAR_FALLBACK: f64 = 0.001;
// ANCHOR_END: variants

/// One variant on this device: its pipeline, lit-pass bind group, map and near plane.
struct Prepared {
    pipeline: usize,
    group: wgpu::BindGroup,
    map: usize,
    near: f64,
    unclipped: bool,
}

struct CubeShadows {
    lit_pipeline: wgpu::RenderPipeline,
    shadow_pipelines: Vec<wgpu::RenderPipeline>,
    maps: Vec<CubeShadowMap>,
    prepared: Vec<Prepared>,
    faces: FaceUniforms,
    spheres: Vec<Sphere>,
    stats: CubeStats,
}

fn find(name: &str) -> Result<usize> {
    VARIANTS
        .iter()
        .position(|v| v.name == name)
        .ok_or_else(|| anyhow::anyhow!("unknown variant {name}"))
}

impl Lesson for CubeShadows {
    const NAME: &'static str = "lesson_04";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_04.toml");

    fn variants() -> Vec<String> {
        VARIANTS.iter().map(|v| v.name.to_string()).collect()
    }

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
        let module = shader_module(gpu, "lesson_04", include_str!("../shaders/lesson_04.wgsl"));
        let layout = cube_shadow::cube_map_layout(gpu, 32);
        let lit_pipeline =
            scene.lit_pipeline(gpu, &module, "fs_lit", &[&layout], Default::default());
        let has_unclipped = gpu.has(wgpu::Features::DEPTH_CLIP_CONTROL);
        let (mut maps, mut shadow_pipelines, mut keys, mut prepared) = (
            Vec::<CubeShadowMap>::new(),
            Vec::new(),
            Vec::new(),
            Vec::new(),
        );
        for v in &VARIANTS {
            let map = maps
                .iter()
                .position(|m| m.size == v.size)
                .unwrap_or_else(|| {
                    maps.push(CubeShadowMap::new(gpu, v.size));
                    maps.len() - 1
                });
            // Without DEPTH_CLIP_CONTROL (GL), fall back to a 1 mm near plane (reported).
            let unclipped = v.unclipped && has_unclipped;
            let near = if v.unclipped && !has_unclipped {
                NEAR_FALLBACK
            } else {
                NEAR
            };
            let storage = match v.storage {
                Storage::Linear => DepthStorage::Linear {
                    vs_entry: "vs_cube_linear",
                    fs_entry: "fs_cube_linear",
                },
                _ => DepthStorage::Hardware,
            };
            let pipeline = keys
                .iter()
                .position(|k| *k == (storage, unclipped))
                .unwrap_or_else(|| {
                    shadow_pipelines.push(cube_shadow::cube_shadow_pipeline(
                        gpu, scene, &module, storage, unclipped,
                    ));
                    keys.push((storage, unclipped));
                    keys.len() - 1
                });
            let mode = match v.storage {
                Storage::Linear => 0.0,
                Storage::Depth => 1.0,
                Storage::DepthEuclid => 2.0,
            };
            let params: [f32; 8] = [
                near as f32,
                2.0 / v.size as f32,
                mode,
                f32::from(u8::from(v.clamp_range)),
                v.bias_world,
                v.bias_texels,
                v.slope,
                v.pcf,
            ];
            let filter = if v.pcf > 0.0 {
                wgpu::FilterMode::Linear
            } else {
                wgpu::FilterMode::Nearest
            };
            let group = cube_shadow::cube_map_group(
                gpu,
                &layout,
                &maps[map],
                filter,
                bytemuck::cast_slice(&params),
            );
            prepared.push(Prepared {
                pipeline,
                group,
                map,
                near,
                unclipped,
            });
        }
        let faces = FaceUniforms::new(gpu, scene);
        let spheres = cube_shadow::bounding_spheres(&scene.scene);
        Ok(CubeShadows {
            lit_pipeline,
            shadow_pipelines,
            maps,
            prepared,
            faces,
            spheres,
            stats: CubeStats::default(),
        })
    }

    // ANCHOR: render
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: &str,
    ) -> Result<()> {
        let i = find(variant)?;
        let (v, p) = (VARIANTS[i], &self.prepared[i]);
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        self.stats = CubeStats::default();
        for light in 0..scene.scene.lights.len() {
            let (pos, range) = cube_shadow::point_light(&scene.scene, light)
                .expect("check_scene allows point and spot lights");
            self.faces.write(frame.gpu, &scene.scene, light, p.near);
            // Leave out what the light cannot see: casters past its range,
            // and per face, casters whose bounding sphere misses the frustum.
            let spheres = &self.spheres;
            let casters = |face: usize| -> Vec<usize> {
                (0..spheres.len())
                    .filter(|&o| scene.casts_shadow(o))
                    .filter(|&o| {
                        let c = spheres[o].centre - pos;
                        let r = spheres[o].radius;
                        !v.cull
                            || (c.length() - r < range
                                && cube_shadow::sphere_touches_face(c, r, face))
                    })
                    .collect()
            };
            let map = &mut self.maps[p.map];
            let s = cube_shadow::cube_shadow_passes(
                frame,
                scene,
                &self.shadow_pipelines[p.pipeline],
                map,
                &self.faces,
                light,
                casters,
            );
            self.stats.faces_rendered += s.faces_rendered;
            self.stats.caster_draws += s.caster_draws;
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(
                    enc,
                    targets,
                    light,
                    &self.lit_pipeline,
                    &[&p.group],
                    0,
                    ts.render(),
                )
            });
        }
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, variant: &str) -> BTreeMap<String, u64> {
        let p = find(variant).map(|i| &self.prepared[i]);
        let mut c = BTreeMap::new();
        c.insert("faces_rendered".into(), self.stats.faces_rendered);
        c.insert("caster_draws".into(), self.stats.caster_draws);
        if let Ok(p) = p {
            c.insert("unclipped_depth".into(), u64::from(p.unclipped));
            c.insert("near_plane_mm".into(), (p.near * 1000.0).round() as u64);
        }
        c
    }

    fn write_extras(&self, gpu: &Gpu, _scene: &SceneGpu, variant: &str, out: &Path) -> Result<()> {
        let map = &self.maps[self.prepared[find(variant)?].map];
        cube_shadow::write_cross_png(gpu, map, 128, &out.join(format!("{variant}_cube_map.png")))
    }
}

fn main() -> std::process::ExitCode {
    app::main::<CubeShadows>()
}
