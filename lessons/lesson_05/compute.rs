//! Shadow volumes built by a compute shader (lesson 05, the third way,
//! [`Extrusion::Compute`](super::extrusion::Extrusion::Compute)).
//!
//! The CPU route finds the silhouette on the CPU and uploads the volume
//! every frame; the quads route uploads everything once and lets the
//! vertex shader throw most of it away. Here each caster's adjacency is
//! uploaded once, in chunks ([`chunks`]: no binding holds a whole mesh),
//! and every frame a compute shader (`shaders/lesson_05/extrude.wgsl`, one
//! invocation per edge and per face of a chunk) writes the CPU route's
//! triangles, `(position, w)`, into the chunk's vertex buffer and counts
//! them into the indirect draw arguments with `atomicAdd`. The volume
//! pass then draws them with the CPU route's own pipelines
//! (`vs_volume_cpu`) and `draw_indirect`: the CPU never learns how many
//! triangles there are, and its work per frame does not grow with the
//! mesh (one dispatch and up to three draws a chunk).
//!
//! The triangles are the CPU route's, in another order; the wrapping
//! stencil count does not depend on the order, so the pixels are the same.

use anyhow::{bail, Result};
use common::glam::Mat4;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::scene::LightKind;
use wgpu::util::{DeviceExt, DrawIndirectArgs};

use super::adjacency::Adjacency;
use super::extrusion::CpuVertex;
use super::silhouette::LightDir;

pub mod chunks;
mod pipeline;
mod read;
pub use chunks::{pack_adjacency, PackedMesh};
use pipeline::{bind_group_layout, compute_pipeline};
use read::read_words;
pub use read::{extrude_in_chunks, extrude_once};

/// The compute shader (`shaders/lesson_05/extrude.wgsl`).
pub const EXTRUDE_WGSL: &str = include_str!("../../shaders/lesson_05/extrude.wgsl");

const WORKGROUP: u32 = 64;
/// Bytes of one draw's arguments; a (light, chunk) has three.
const ARGS: u64 = std::mem::size_of::<DrawIndirectArgs>() as u64;
const VERTEX: u64 = std::mem::size_of::<CpuVertex>() as u64;

/// `Params` of extrude.wgsl: one (light, chunk).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    light: [f32; 4],
    reach_w: f32,
    edges: u32,
    faces: u32,
    slot: u32,
    offsets: [u32; 5],
    row: u32,
    _pad: [u32; 2],
}

/// Why this adapter cannot build volumes with a compute shader, in one
/// line that names the variant that works; `None` when it can.
pub fn unavailable(gpu: &Gpu) -> Option<String> {
    let flags = gpu.adapter.get_downlevel_capabilities().flags;
    let missing: Vec<&str> = [
        (wgpu::DownlevelFlags::COMPUTE_SHADERS, "compute shaders"),
        (wgpu::DownlevelFlags::INDIRECT_EXECUTION, "indirect draws"),
    ]
    .iter()
    .filter(|(f, _)| !flags.contains(*f))
    .map(|(_, name)| *name)
    .collect();
    (!missing.is_empty()).then(|| {
        format!(
            "the compute-built volumes need {} (GL needs OpenGL 4.3 or GLES 3.1), \
             which {} on {} does not have: the _cpu and _quads variants build \
             the same volumes without",
            missing.join(" and "),
            gpu.adapter_name(),
            gpu.backend_name()
        )
    })
}

/// The most bytes one chunk may bind, its tables or its worst-case
/// volume: the adapter's storage binding limit (and buffer size limit).
pub fn chunk_bytes(gpu: &Gpu) -> u64 {
    let limits = gpu.device.limits();
    (limits.max_storage_buffer_binding_size).min(limits.max_buffer_size)
}

/// The light as extrude.wgsl takes it: object space, w = 0 directional.
fn light_params(light: LightDir) -> [f32; 4] {
    match light {
        LightDir::Point(p) => p.extend(1.0).to_array(),
        LightDir::Directional(d) => d.extend(0.0).to_array(),
    }
}

/// What the shader needs of one chunk: its table offsets and counts.
#[derive(Clone, Copy, Debug)]
struct ChunkShape {
    offsets: [u32; 5],
    edges: u32,
    faces: u32,
    /// Where its sides, front cap and back cap start in its vertex buffer.
    firsts: [u32; 3],
}

/// One (light, chunk): the chunk's vertex buffer for that light, and the
/// bind group of its dispatch.
struct Slot {
    vertices: wgpu::Buffer,
    group: wgpu::BindGroup,
    chunk: usize,
}

/// One indirect draw of a caster's volume ([`ComputeVolumes::draws`]).
pub struct ChunkDraw<'a> {
    /// The chunk's vertices, and where its arguments are in [`ComputeVolumes::args`].
    pub vertices: &'a wgpu::Buffer,
    pub args_at: u64,
    /// Which part: 0 sides, 1 front cap, 2 back cap (a cap if not 0).
    pub part: usize,
    /// Its slot in [`ComputeVolumes::read_counts`].
    pub slot: usize,
}

/// Every caster's chunks (their tables on the GPU), the compute
/// pipeline, and per (light, chunk) a vertex buffer and three indirect
/// draws (sides, front cap, back cap): slot `light * chunks + chunk`.
pub struct ComputeVolumes {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    params_stride: u64,
    /// Every slot's three `DrawIndirectArgs`, INDIRECT | STORAGE | COPY_DST.
    pub args: wgpu::Buffer,
    /// The arguments each frame starts from (count 0, one instance),
    /// copied over `args` in the frame's own encoder: a queue write would
    /// land before the counting submits of [`count_costs`](super::volumes::ShadowVolumes::count_costs)
    /// and zero the counts they draw with.
    reset: wgpu::Buffer,
    chunks: Vec<ChunkShape>,
    /// Per caster: its chunks, a range of `chunks`.
    caster_chunks: Vec<std::ops::Range<usize>>,
    slots: Vec<Slot>,
    lights: usize,
    /// The bytes last written to `params`.
    written: Vec<u8>,
}

/// The dispatches of a frame: (slot, workgroup grid).
type Dispatches = Vec<(usize, (u32, u32))>;

impl ComputeVolumes {
    /// Uploads every caster's adjacency in chunks of at most
    /// [`chunk_bytes`] and sizes the outputs for the worst case. A
    /// one-line error if the adapter cannot, or if its memory cannot hold
    /// them.
    pub fn new(gpu: &Gpu, casters: &[&Adjacency], lights: usize) -> Result<ComputeVolumes> {
        ComputeVolumes::in_chunks(gpu, casters, lights, chunk_bytes(gpu))
    }

    /// [`new`](Self::new), with chunks of at most `max_bytes` (the tests
    /// split small meshes with it).
    pub fn in_chunks(
        gpu: &Gpu,
        casters: &[&Adjacency],
        lights: usize,
        max_bytes: u64,
    ) -> Result<ComputeVolumes> {
        if let Some(why) = unavailable(gpu) {
            bail!("{why}");
        }
        let (built, oom) =
            gpu.out_of_memory_scope(|| ComputeVolumes::build(gpu, casters, lights, max_bytes));
        if let Some(e) = oom {
            let bytes: u64 = (casters.iter())
                .map(|a| VERTEX * lights as u64 * fit_vertices(a))
                .sum();
            bail!(
                "the compute route's worst-case vertex buffers ({:.0} MiB for {lights} lights) \
                 do not fit in the memory of {}: {}; the _cpu route needs only what is drawn",
                bytes as f64 / (1u64 << 20) as f64,
                gpu.adapter_name(),
                e.to_string()
                    .split_whitespace()
                    .collect::<Vec<_>>()
                    .join(" ")
            );
        }
        built
    }

    fn build(
        gpu: &Gpu,
        casters: &[&Adjacency],
        lights: usize,
        max_bytes: u64,
    ) -> Result<ComputeVolumes> {
        use wgpu::BufferUsages as U;
        let limits = gpu.device.limits();
        let layout = bind_group_layout(gpu);
        // Every caster's chunks, their tables uploaded once.
        let (mut chunks, mut meshes, mut caster_chunks) = (Vec::new(), Vec::new(), Vec::new());
        for adj in casters {
            let first = chunks.len();
            for p in chunks::split(adj, max_bytes)? {
                let sides = p.max_side_vertices;
                chunks.push(ChunkShape {
                    offsets: p.offsets,
                    edges: p.edges,
                    faces: p.faces,
                    firsts: [0, sides, sides + 3 * p.faces],
                });
                meshes.push(
                    gpu.device
                        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                            label: Some("caster adjacency chunk"),
                            contents: bytemuck::cast_slice(&p.words),
                            usage: U::STORAGE,
                        }),
                );
            }
            caster_chunks.push(first..chunks.len());
        }
        let slots_n = (lights * chunks.len()).max(1) as u64;
        let mut reset = Vec::new();
        for _ in 0..lights {
            for c in &chunks {
                reset.extend(c.firsts.map(|first| DrawIndirectArgs {
                    vertex_count: 0,
                    instance_count: 1,
                    first_vertex: first,
                    first_instance: 0,
                }));
            }
        }
        reset.resize(reset.len().max(1), DrawIndirectArgs::default());
        let buffer = |label, size, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let reset_src = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("compute volume draws reset"),
                contents: bytemuck::cast_slice(&reset),
                usage: U::COPY_SRC,
            });
        let args_usage = U::INDIRECT | U::STORAGE | U::COPY_DST | U::COPY_SRC;
        let args = buffer(
            "compute volume draws",
            reset.len() as u64 * ARGS,
            args_usage,
        );
        let params_stride = (std::mem::size_of::<Params>() as u64)
            .next_multiple_of(limits.min_uniform_buffer_offset_alignment as u64);
        let params = buffer(
            "extrude params",
            params_stride * slots_n,
            U::UNIFORM | U::COPY_DST,
        );
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("extrude"),
                source: wgpu::ShaderSource::Wgsl(EXTRUDE_WGSL.into()),
            });
        let pipeline = compute_pipeline(gpu, &module, &layout);
        // Per light and chunk: the volume's vertices, within one binding.
        let mut slots = Vec::with_capacity(lights * chunks.len());
        for _ in 0..lights {
            for (chunk, c) in chunks.iter().enumerate() {
                let n = (c.firsts[2] + 3 * c.faces).max(1) as u64;
                let usage = U::STORAGE | U::VERTEX | U::COPY_SRC;
                let vertices = buffer("compute volume chunk", n * VERTEX, usage);
                let params = wgpu::BufferBinding {
                    buffer: &params,
                    offset: 0,
                    size: wgpu::BufferSize::new(std::mem::size_of::<Params>() as u64),
                };
                let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
                let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("extrude"),
                    layout: &layout,
                    entries: &[
                        entry(0, wgpu::BindingResource::Buffer(params)),
                        entry(1, meshes[chunk].as_entire_binding()),
                        entry(2, vertices.as_entire_binding()),
                        entry(3, args.as_entire_binding()),
                    ],
                });
                slots.push(Slot {
                    vertices,
                    group,
                    chunk,
                });
            }
        }
        Ok(ComputeVolumes {
            pipeline,
            params,
            params_stride,
            args,
            reset: reset_src,
            chunks,
            caster_chunks,
            slots,
            lights,
            written: Vec::new(),
        })
    }

    /// The slots of light `light`'s volume of caster `caster`, one per chunk.
    pub fn slots_of(&self, light: usize, caster: usize) -> std::ops::Range<usize> {
        let c = &self.caster_chunks[caster];
        let at = light * self.chunks.len();
        at + c.start..at + c.end
    }

    // ANCHOR: extrude
    /// The per-frame work: for every light k (`lights`, origin-relative
    /// world space) and caster whose object `drawn(k, object)` says, the
    /// light in object space (`models`) and the reach (`reach[light][caster]`,
    /// 0 infinity) go to the shader, the vertex counts are reset, and one
    /// dispatch per (light, chunk) writes the volumes. Timed as the pass
    /// `extrude`.
    pub fn extrude(
        &mut self,
        frame: &mut Frame,
        lights: &[LightDir],
        objects: &[usize],
        (models, reach): (&[Mat4], &[Vec<f32>]),
        drawn: impl Fn(usize, usize) -> bool,
    ) {
        let mut jobs = Vec::new();
        for (k, world) in lights.iter().enumerate().take(self.lights) {
            for (ci, &object) in objects.iter().enumerate() {
                if drawn(k, object) {
                    // Silhouettes in object space: the light moves, not the mesh.
                    let light = world.to_object_space(models[object]);
                    let w = reach.get(k).and_then(|r| r.get(ci)).copied();
                    jobs.push((k, ci, light, w.unwrap_or(0.0)));
                }
            }
        }
        let (params, dispatches) = self.params_of(frame.gpu, &jobs);
        // Uploaded again only when a light or a reach has moved.
        if params != self.written {
            frame.gpu.queue.write_buffer(&self.params, 0, &params);
            self.written = params;
        }
        frame.pass("extrude", |enc, ts| {
            self.record(enc, ts.compute(), &dispatches)
        });
    }
    // ANCHOR_END: extrude

    /// The `Params` of each job's chunks (light k, caster, object-space
    /// light, reach w), as the bytes of [`params`](Self::params), and the
    /// dispatches: (slot, grid).
    fn params_of(
        &self,
        gpu: &Gpu,
        jobs: &[(usize, usize, LightDir, f32)],
    ) -> (Vec<u8>, Dispatches) {
        let max_groups = gpu.device.limits().max_compute_workgroups_per_dimension;
        let stride = self.params_stride as usize;
        let mut params = vec![0u8; stride * self.slots.len().max(1)];
        let mut dispatches = Vec::new();
        for &(k, ci, light, reach_w) in jobs {
            for slot in self.slots_of(k, ci) {
                let c = &self.chunks[self.slots[slot].chunk];
                let n = c.edges + c.faces;
                if n == 0 {
                    continue;
                }
                let groups = n.div_ceil(WORKGROUP);
                let grid = (groups.min(max_groups), groups.div_ceil(max_groups));
                let value = Params {
                    light: light_params(light),
                    reach_w,
                    edges: c.edges,
                    faces: c.faces,
                    slot: slot as u32,
                    offsets: c.offsets,
                    row: grid.0 * WORKGROUP,
                    _pad: [0; 2],
                };
                params[slot * stride..][..std::mem::size_of::<Params>()]
                    .copy_from_slice(bytemuck::bytes_of(&value));
                dispatches.push((slot, grid));
            }
        }
        (params, dispatches)
    }

    /// Resets the counts and records the dispatches.
    fn record(
        &self,
        enc: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
        dispatches: &[(usize, (u32, u32))],
    ) {
        // Every count back to 0 before the dispatches add to it.
        enc.copy_buffer_to_buffer(&self.reset, 0, &self.args, 0, self.args.size());
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("extrude"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        for &(slot, (x, y)) in dispatches {
            let offset = (slot as u64 * self.params_stride) as u32;
            pass.set_bind_group(0, &self.slots[slot].group, &[offset]);
            pass.dispatch_workgroups(x, y, 1);
        }
    }

    /// One caster's indirect draws for light `light`, chunk by chunk: the
    /// sides and the caps asked for, `(front, back)`. A directional light
    /// has no back cap (it is one point).
    pub fn draws(
        &self,
        scene: &SceneGpu,
        light: usize,
        caster: usize,
        (front, back): (bool, bool),
    ) -> Vec<ChunkDraw<'_>> {
        let directional = is_directional(scene, light);
        let parts = [true, front, back && !directional];
        let draw = |slot: usize, part: usize| ChunkDraw {
            vertices: &self.slots[slot].vertices,
            args_at: (3 * slot + part) as u64 * ARGS,
            part,
            slot,
        };
        (self.slots_of(light, caster))
            .flat_map(|slot| (0..3).filter(|&p| parts[p]).map(move |p| draw(slot, p)))
            .collect()
    }

    /// Reads back every slot's vertex counts (sides, front cap, back cap),
    /// `counts[slot]` ([`slots_of`](Self::slots_of)), as the last frame
    /// left them. Untimed: its own submit.
    pub fn read_counts(&self, gpu: &Gpu) -> Result<Vec<[u32; 3]>> {
        let words = read_words(gpu, &self.args, "compute volume counts")?;
        Ok((0..self.slots.len())
            .map(|s| [0, 1, 2].map(|p| words[(3 * s + p) * 4]))
            .collect())
    }

    /// The number of vertices on one side of a silhouette edge: 6 for a
    /// point light, 3 for a directional one.
    pub fn per_side(scene: &SceneGpu, light: usize) -> u32 {
        if is_directional(scene, light) {
            3
        } else {
            6
        }
    }
}

/// A directional light (no back cap, one triangle a side).
fn is_directional(scene: &SceneGpu, light: usize) -> bool {
    matches!(
        scene.scene.lights[light].kind,
        LightKind::Directional { .. }
    )
}

/// `adj`'s worst-case volume, in vertices: every side, both caps.
fn fit_vertices(adj: &Adjacency) -> u64 {
    super::fit::max_side_vertices(adj) + 6 * adj.triangles.len() as u64
}
