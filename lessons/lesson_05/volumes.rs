//! Shadow volumes on the GPU (lesson 05): every caster's volume data, the
//! volume pipelines, and the volume pass that counts them into the stencil.
//!
//! # What a frame does
//!
//! ```text
//! base pass (depth + ambient)              scene.base_pass
//! for each light:                          ShadowVolumes::light_passes
//!     volume pass: clear stencil, draw     ShadowVolumes::volume_pass
//!                  volumes, count in stencil
//!     lit pass where stencil == 0          scene.lit_pass with lit_stencil()
//! ```
//!
//! The volume pass clears the stencil itself (its stencil attachment is
//! `LoadOp::Clear(0)`, depth is loaded): that is the per-light stencil
//! clear, merged into the pass that needs it.
//!
//! Open, non-manifold or misoriented meshes cast as two-sided surfaces
//! ([`caster_adjacency`]). A mirrored model (det < 0) reverses every
//! winding in world space: such casters are drawn with a pipeline whose
//! front face is `Cw`.
//!
//! Vertices at infinity (w = 0) lie beyond any finite far plane: lesson 05
//! uses scenes with `far = "infinite"`; lesson 07 handles a finite one by
//! depth clamping. Lesson 06 can instead give each caster a finite *reach*
//! ([`ShadowVolumes::set_reach`]): its far vertices at `w = reach_w`, that is
//! `1 / reach_w` times as far from the light, with a finite back cap.
//!
//! What the volumes cost ([`costs`]: `volume_fragments`, `stencil_updates`,
//! `volume_triangles`, `draws`) is counted exactly, on Vulkan and GL, by an
//! untimed copy of the volume pass. [`FragmentCounter`] adds the adapter's
//! pipeline statistics (`fragment_shader_invocations`) where it has them.

use std::ops::Range;

use anyhow::Result;
use common::glam::{DVec3, Mat4};
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::fragment_counter::FragmentCounter;
use common::measure::timing::Frame;

use super::adjacency::Adjacency;
use super::compute::{self, ComputeVolumes};
use super::extrusion::{
    cpu_volume_parts, light_relative_to, CpuParts, CpuVertex, Extrusion, VolumeRanges,
};
use super::fit;
use super::frustum::frustum_planes;
use super::quads::REACH_SLOT;
use super::silhouette::LightDir;
use super::stencil::{Counting, Method, VolumePipelines};
use crate::lesson_01::tally::Tally;

mod casters;
mod costs;
mod frame;
use casters::build_casters;
pub use casters::VolumeCaster;
pub use costs::{base_and_lit_draws, SecondFrameCounts, VolumeCosts};

/// Which pipelines [`ShadowVolumes::draw_casters`] draws with: the volume
/// pass's own, or a counting copy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DrawRole {
    /// Counting in the stencil (the volume pass).
    Stencil,
    /// No depth test, for pipeline statistics ([`FragmentCounter`]).
    Statistics,
    /// For a [`Tally`]: with the volume pass's depth test, or none.
    Tally { depth_test: bool },
}

/// One caster's volume in one light's volume pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CasterDraw {
    /// Index into `scene.objects`.
    pub object: usize,
    pub method: Method,
    pub front_cap: bool,
    pub back_cap: bool,
}

impl CasterDraw {
    /// Sides only, z-pass.
    pub fn zpass(object: usize) -> CasterDraw {
        CasterDraw {
            object,
            method: Method::ZPass,
            front_cap: false,
            back_cap: false,
        }
    }

    /// The ranges of `r` this draw covers, each with "is it a cap?".
    fn ranges(&self, r: &VolumeRanges) -> impl Iterator<Item = (Range<u32>, bool)> {
        [
            Some((r.sides.clone(), false)),
            self.front_cap.then(|| (r.front.clone(), true)),
            self.back_cap.then(|| (r.back.clone(), true)),
        ]
        .into_iter()
        .flatten()
        .filter(|(r, _)| !r.is_empty())
    }
}

/// One light's volumes in a volume pass: which casters, counted how
/// ([`CasterDraw`]), with the geometry of which extrusion.
#[derive(Clone, Copy, Debug)]
pub struct LightVolumes<'a> {
    pub light: usize,
    pub extrusion: Extrusion,
    pub draws: &'a [CasterDraw],
}

/// The per-frame CPU geometry: one buffer for every light, so the writes of
/// light 0 and light 1 do not overwrite each other before the submit.
#[derive(Default)]
struct CpuGeometry {
    buffer: Option<wgpu::Buffer>,
    /// `ranges[light][caster]`.
    ranges: Vec<Vec<VolumeRanges>>,
    vertices: Vec<CpuVertex>,
}

/// Every caster's volume data and the pipelines of both extrusion methods.
pub struct ShadowVolumes {
    pub casters: Vec<VolumeCaster>,
    /// `caster_of[object]`: the object's index in `casters`, if it casts.
    caster_of: Vec<Option<usize>>,
    /// Every object's origin-relative model matrix, and the origin (the
    /// centre of the scene's bounds, a pass over every vertex), found once:
    /// objects do not move (the window moves only the camera and the lights).
    models: Vec<Mat4>,
    origin: DVec3,
    /// `reach[light][caster]`: the w of extruded vertices (0: infinity).
    reach: Vec<Vec<f32>>,
    /// The same, one [`REACH_SLOT`] per (light, caster), for the quads path;
    /// `None` unless the counting has `finite_reach`.
    reach_buffer: Option<wgpu::Buffer>,
    cpu: CpuGeometry,
    /// Which parts of the CPU route's volumes an exercise's code builds
    /// (the lesson's own by default; [`ShadowVolumes::set_cpu_parts`]).
    cpu_parts: CpuParts,
    /// The compute route's buffers, made when it first runs.
    compute: Option<ComputeVolumes>,
    /// Per route (cpu, quads, compute): why its buffers would not fit the
    /// adapter ([`fit`]), or `None`.
    unfit: [Option<String>; 3],
    cpu_pipelines: VolumePipelines,
    quad_pipelines: VolumePipelines,
    counter: Option<FragmentCounter>,
    tally: Tally,
}

impl ShadowVolumes {
    /// Every caster's adjacency and pre-built quads, and the pipelines of
    /// both extrusions, counting with `counting`.
    pub fn new(gpu: &Gpu, scene: &SceneGpu, counting: &Counting) -> Result<ShadowVolumes> {
        let casters = build_casters(gpu, scene);
        let models = scene.scene.relative_models();
        let origin = scene.scene.origin();
        let lights = scene.scene.lights.len();
        let objects = &scene.scene.objects;
        let adjacency: Vec<(&str, &Adjacency)> = (casters.iter())
            .map(|c| (objects[c.object].mesh.name.as_str(), &c.adjacency))
            .collect();
        let sizes: Vec<(&str, (u64, u64))> = (casters.iter())
            .map(|c| (objects[c.object].mesh.name.as_str(), c.quad_sizes))
            .collect();
        let unfit = [
            fit::cpu_unfit(gpu, &adjacency, lights),
            fit::quads_unfit(gpu, &sizes),
            compute::unavailable(gpu),
        ];
        let reach = vec![vec![0.0; casters.len()]; lights];
        let reach_buffer = counting.finite_reach.then(|| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("volume reach"),
                size: REACH_SLOT * (lights * casters.len()).max(1) as u64,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                // Zeros: every volume reaches infinity until set_reach.
                mapped_at_creation: false,
            })
        });
        let mut caster_of = vec![None; scene.scene.objects.len()];
        for (ci, c) in casters.iter().enumerate() {
            caster_of[c.object] = Some(ci);
        }
        Ok(ShadowVolumes {
            casters,
            caster_of,
            models,
            origin,
            reach,
            reach_buffer,
            cpu: CpuGeometry::default(),
            cpu_parts: CpuParts::default(),
            compute: None,
            unfit,
            cpu_pipelines: VolumePipelines::new(gpu, scene, Extrusion::Cpu, counting)?,
            quad_pipelines: VolumePipelines::new(gpu, scene, Extrusion::Quads, counting)?,
            counter: FragmentCounter::new(gpu, scene.width, scene.height),
            tally: Tally::new(gpu, scene.width, scene.height),
        })
    }

    /// Why `ext`'s buffers would pass one of the adapter's limits (the
    /// limit and the size, [`fit`]), or why it cannot run here at all (the
    /// compute route without compute shaders); `None` if it fits.
    pub fn unfit(&self, ext: Extrusion) -> Option<&str> {
        let route = match ext {
            Extrusion::Cpu => 0,
            Extrusion::Quads => 1,
            Extrusion::Compute => 2,
        };
        self.unfit[route].as_deref()
    }

    /// Sets `reach[light][caster]` (caster: index into `casters`), the w
    /// every extruded vertex of that volume gets: 0 is infinity (the
    /// default), `0 < w < 1` is `1 / w` times as far from the light. The
    /// quads path reads it only if the counting has `finite_reach`.
    pub fn set_reach(&mut self, gpu: &Gpu, reach: Vec<Vec<f32>>) {
        if let Some(buf) = &self.reach_buffer {
            let slots = REACH_SLOT as usize / 4;
            let mut data = vec![0f32; buf.size() as usize / 4];
            for (k, per_caster) in reach.iter().enumerate() {
                for (ci, w) in per_caster.iter().enumerate() {
                    data[(k * self.casters.len() + ci) * slots] = *w;
                }
            }
            gpu.queue.write_buffer(buf, 0, bytemuck::cast_slice(&data));
        }
        self.reach = reach;
    }

    /// Every caster, drawn as `draw` says (`CasterDraw::zpass`, or
    /// lesson 06's `caps::zfail`).
    pub fn all(&self, draw: fn(usize) -> CasterDraw) -> Vec<CasterDraw> {
        self.casters.iter().map(|c| draw(c.object)).collect()
    }

    /// Light `k` as the volumes see it (origin-relative world space), as
    /// [`world_light`](super::silhouette::world_light) finds it, from the
    /// origin found once: cheap enough for every frame.
    pub fn light(&self, scene: &SceneGpu, k: usize) -> LightDir {
        light_relative_to(&scene.scene, self.origin, k)
    }

    fn caster(&self, object: usize) -> Option<(usize, &VolumeCaster)> {
        let ci = (*self.caster_of.get(object)?)?;
        Some((ci, &self.casters[ci]))
    }

    // ANCHOR: prepare_cpu
    /// The CPU path's per-frame work: silhouettes and caps for every light
    /// and the casters in `draws[light]`, uploaded in one write. Timed as
    /// `cpu_silhouette`.
    pub fn prepare_cpu(&mut self, frame: &mut Frame, scene: &SceneGpu, draws: &[Vec<CasterDraw>]) {
        let (gpu, parts) = (frame.gpu, self.cpu_parts);
        let (cpu, origin) = (&mut self.cpu, self.origin);
        let casters = &self.casters;
        let reach = &self.reach;
        let models = &self.models;
        // An exercise's sides or caps also get the view frustum (object space).
        let view = if parts.sides.is_some() || parts.caps.is_some() {
            frustum_planes(scene.camera.view_proj.as_dmat4())
        } else {
            Vec::new()
        };
        frame.cpu("silhouette", || {
            cpu.vertices.clear();
            cpu.ranges.clear();
            for (k, draws_k) in draws.iter().enumerate() {
                let light = light_relative_to(&scene.scene, origin, k);
                let mut ranges = vec![VolumeRanges::default(); casters.len()];
                let mut drawn = vec![false; scene.scene.objects.len()];
                for d in draws_k {
                    drawn[d.object] = true;
                }
                for (ci, c) in casters.iter().enumerate() {
                    if !drawn[c.object] {
                        continue;
                    }
                    // Silhouettes in object space: the light moves, not the mesh.
                    let model = models[c.object];
                    let w = reach.get(k).and_then(|r| r.get(ci)).copied();
                    // A plane (n, d) in object space: (n, d) · (M x, 1).
                    let m = model.as_dmat4().transpose();
                    let view: Vec<(DVec3, f64)> = view
                        .iter()
                        .map(|&(n, d)| {
                            let p = m * n.extend(d);
                            (p.truncate(), p.w)
                        })
                        .collect();
                    ranges[ci] = cpu_volume_parts(
                        &c.adjacency,
                        light.to_object_space(model),
                        w.unwrap_or(0.0),
                        parts,
                        &view,
                        &mut cpu.vertices,
                    );
                }
                cpu.ranges.push(ranges);
            }
            let bytes = (cpu.vertices.len().max(1) * std::mem::size_of::<CpuVertex>()) as u64;
            if cpu.buffer.as_ref().is_none_or(|b| b.size() < bytes) {
                cpu.buffer = Some(
                    gpu.device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("cpu shadow volumes"),
                        // Room to grow, within the limit `fit::cpu_unfit` checked.
                        size: bytes
                            .next_power_of_two()
                            .min(gpu.device.limits().max_buffer_size),
                        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    }),
                );
            }
            if let Some(b) = &cpu.buffer {
                gpu.queue
                    .write_buffer(b, 0, bytemuck::cast_slice(&cpu.vertices));
            }
        });
    }
    // ANCHOR_END: prepare_cpu

    /// The sides or caps the CPU route builds from here on: an exercise's
    /// code ([`CpuParts`]), or the lesson's own (the default).
    pub fn set_cpu_parts(&mut self, parts: CpuParts) {
        self.cpu_parts = parts;
    }

    // ANCHOR: prepare_compute
    /// The compute route's per-frame work ([`ComputeVolumes::extrude`]),
    /// for every light and the casters in `draws[light]`: timed as the
    /// pass `extrude`. Its buffers are made on the first call; an adapter
    /// without compute shaders is a one-line error.
    pub fn prepare_compute(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        draws: &[Vec<CasterDraw>],
    ) -> Result<()> {
        if let Some(why) = self.unfit(Extrusion::Compute) {
            anyhow::bail!("{why}");
        }
        if self.compute.is_none() {
            let adjacency: Vec<_> = self.casters.iter().map(|c| &c.adjacency).collect();
            let lights = scene.scene.lights.len();
            // Made once, on the first frame, and left out of its times.
            let made = frame.untimed(|gpu| ComputeVolumes::new(gpu, &adjacency, lights))?;
            self.compute = Some(made);
        }
        let lights: Vec<LightDir> = (0..draws.len()).map(|k| self.light(scene, k)).collect();
        if let Some(c) = &mut self.compute {
            let objects: Vec<usize> = self.casters.iter().map(|c| c.object).collect();
            let drawn = |k: usize, o| {
                draws
                    .get(k)
                    .is_some_and(|d| d.iter().any(|d| d.object == o))
            };
            c.extrude(frame, &lights, &objects, (&self.models, &self.reach), drawn);
        }
        Ok(())
    }
    // ANCHOR_END: prepare_compute

    /// Draws one light's volumes into an open pass, with the volume
    /// pipelines of their extrusion (or the counting copy). Returns the
    /// number of casters drawn.
    pub fn draw_casters(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        scene: &SceneGpu,
        v: LightVolumes<'_>,
        role: DrawRole,
    ) -> u32 {
        let pipes = match v.extrusion {
            Extrusion::Cpu | Extrusion::Compute => &self.cpu_pipelines,
            Extrusion::Quads => &self.quad_pipelines,
        };
        scene.bind_frame(pass, v.light);
        let mut drawn = 0;
        for d in v.draws {
            let Some((ci, c)) = self.caster(d.object) else {
                continue;
            };
            let pipeline = |cap: bool| match role {
                DrawRole::Stencil => pipes.get(d.method, c.mirrored, cap),
                DrawRole::Statistics => pipes.counting(),
                DrawRole::Tally { depth_test } => pipes.tally(depth_test, cap),
            };
            scene.bind_object(pass, c.object);
            match v.extrusion {
                Extrusion::Cpu => {
                    let (Some(buf), Some(r)) = (
                        &self.cpu.buffer,
                        self.cpu.ranges.get(v.light).and_then(|r| r.get(ci)),
                    ) else {
                        continue;
                    };
                    pass.set_vertex_buffer(0, buf.slice(..));
                    for (range, cap) in d.ranges(r) {
                        pass.set_pipeline(pipeline(cap));
                        pass.draw(range, 0..1);
                    }
                }
                Extrusion::Quads => {
                    pass.set_vertex_buffer(0, c.quad_vertices.slice(..));
                    if let Some(reach) = &self.reach_buffer {
                        // This caster's reach for this light, as instance 0.
                        let at = (v.light * self.casters.len() + ci) as u64 * REACH_SLOT;
                        pass.set_vertex_buffer(1, reach.slice(at..at + REACH_SLOT));
                    }
                    pass.set_index_buffer(c.quad_indices.slice(..), wgpu::IndexFormat::Uint32);
                    for (range, cap) in d.ranges(&c.quad_ranges) {
                        pass.set_pipeline(pipeline(cap));
                        pass.draw_indexed(range, 0, 0..1);
                    }
                }
                Extrusion::Compute => {
                    let Some(cv) = &self.compute else { continue };
                    // As many vertices as the compute shader counted, chunk by chunk.
                    for draw in cv.draws(scene, v.light, ci, (d.front_cap, d.back_cap)) {
                        pass.set_vertex_buffer(0, draw.vertices.slice(..));
                        pass.set_pipeline(pipeline(draw.part > 0));
                        pass.draw_indirect(&cv.args, draw.args_at);
                    }
                }
            }
            drawn += 1;
        }
        drawn
    }

    /// The fragment counter (lesson 08 counts its own volumes with it).
    pub fn counter(&self) -> Option<&FragmentCounter> {
        self.counter.as_ref()
    }
}
