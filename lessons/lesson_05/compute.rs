//! Shadow volumes built by a compute shader (lesson 05, the third way,
//! [`Extrusion::Compute`](super::extrusion::Extrusion::Compute)).
//!
//! The CPU route finds the silhouette on the CPU and uploads the volume
//! every frame; the quads route uploads everything once and lets the
//! vertex shader throw most of it away. Here each caster's adjacency is
//! uploaded once ([`pack_adjacency`]), and every frame a compute shader
//! (`shaders/lesson_05/extrude.wgsl`, one invocation per edge and per
//! face) writes the CPU route's triangles, `(position, w)`, into a storage
//! buffer and counts them into the indirect draw arguments with
//! `atomicAdd`. The volume pass then draws them with the CPU route's own
//! pipelines (`vs_volume_cpu`) and `draw_indirect`: the CPU never learns
//! how many triangles there are.
//!
//! The triangles are the CPU route's, in another order; the wrapping
//! stencil count does not depend on the order, so the pixels are the same.

use anyhow::{bail, Result};
use common::glam::Mat4;
use common::gpu::readback::read_buffer;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use wgpu::util::{DeviceExt, DrawIndirectArgs};

use super::adjacency::Adjacency;
use super::extrusion::{world_light, CpuVertex};
use super::silhouette::LightDir;

mod pipeline;
use pipeline::{bind_group_layout, compute_pipeline};

/// The compute shader (`shaders/lesson_05/extrude.wgsl`).
pub const EXTRUDE_WGSL: &str = include_str!("../../shaders/lesson_05/extrude.wgsl");

const WORKGROUP: u32 = 64;
/// Bytes of one draw's arguments; a (light, caster) has three.
const ARGS: u64 = std::mem::size_of::<DrawIndirectArgs>() as u64;
const VERTEX: u64 = std::mem::size_of::<CpuVertex>() as u64;

/// `Params` of extrude.wgsl: one (light, caster).
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

/// One caster's adjacency as extrude.wgsl reads it: one `u32` array of
/// five tables, and how many vertices its volume can need at most.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PackedMesh {
    pub words: Vec<u32>,
    /// Where positions, normals, triangles, edges and face uses start.
    pub offsets: [u32; 5],
    pub edges: u32,
    pub faces: u32,
    /// Side vertices when every edge is a silhouette as often as it can
    /// be: max(faces running one way, faces running the other) per edge,
    /// 6 vertices each (a point light's two triangles).
    pub max_side_vertices: u32,
}

// ANCHOR: pack_adjacency
/// Packs `adj` for extrude.wgsl (see the shader's `mesh` binding).
pub fn pack_adjacency(adj: &Adjacency) -> PackedMesh {
    let mut w: Vec<u32> = Vec::new();
    let mut offsets = [0u32; 5];
    offsets[0] = w.len() as u32;
    w.extend(
        adj.positions
            .iter()
            .flat_map(|p| p.to_array().map(f32::to_bits)),
    );
    offsets[1] = w.len() as u32;
    w.extend(
        adj.face_normals
            .iter()
            .flat_map(|n| n.to_array().map(f32::to_bits)),
    );
    offsets[2] = w.len() as u32;
    w.extend(adj.triangles.iter().flatten());
    offsets[3] = w.len() as u32;
    let (mut uses, mut max_sides) = (Vec::new(), 0u32);
    for e in &adj.edges {
        let faces = adj.faces_of(e);
        w.extend([e.v[0], e.v[1], uses.len() as u32, faces.len() as u32]);
        uses.extend(faces.iter().map(|f| f.face << 1 | f.forward as u32));
        let forward = faces.iter().filter(|f| f.forward).count() as u32;
        max_sides += forward.max(faces.len() as u32 - forward);
    }
    offsets[4] = w.len() as u32;
    w.extend(uses);
    w.push(0); // never empty: wgpu rejects a zero-sized binding
    PackedMesh {
        words: w,
        offsets,
        edges: adj.edges.len() as u32,
        faces: adj.triangles.len() as u32,
        max_side_vertices: 6 * max_sides,
    }
}
// ANCHOR_END: pack_adjacency

/// The light as extrude.wgsl takes it: object space, w = 0 directional.
fn light_params(light: LightDir) -> [f32; 4] {
    match light {
        LightDir::Point(p) => p.extend(1.0).to_array(),
        LightDir::Directional(d) => d.extend(0.0).to_array(),
    }
}

/// Every caster's packed adjacency, the compute pipeline, and one region
/// of the vertex buffer and three indirect draws (sides, front cap, back
/// cap) per (light, caster): slot `light * casters + caster`.
pub struct ComputeVolumes {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    params_stride: u64,
    /// Every slot's volume vertices ([`CpuVertex`]), STORAGE | VERTEX.
    pub vertices: wgpu::Buffer,
    /// Every slot's three `DrawIndirectArgs`, INDIRECT | STORAGE | COPY_DST.
    pub args: wgpu::Buffer,
    /// The arguments each frame starts from (count 0, one instance),
    /// copied over `args` in the frame's own encoder: a queue write would
    /// land before the counting submits of [`count_costs`](super::volumes::ShadowVolumes::count_costs)
    /// and zero the counts they draw with.
    reset: wgpu::Buffer,
    /// Its contents: where each draw's vertices start.
    firsts: Vec<u32>,
    slots: usize,
    /// Per caster: its bind group, and its edges and faces.
    casters: Vec<(wgpu::BindGroup, PackedMesh)>,
    lights: usize,
}

impl ComputeVolumes {
    /// Uploads every caster's adjacency and sizes the outputs for the
    /// worst case. A one-line error if the adapter cannot; whether the
    /// buffers fit its limits is `fit::compute_unfit`'s to say, before.
    pub fn new(gpu: &Gpu, casters: &[&Adjacency], lights: usize) -> Result<ComputeVolumes> {
        if let Some(why) = unavailable(gpu) {
            bail!("{why}");
        }
        let limits = gpu.device.limits();
        let packed: Vec<PackedMesh> = casters.iter().map(|a| pack_adjacency(a)).collect();
        // Each slot's regions: sides, front cap, back cap.
        let mut reset = Vec::new();
        let mut first = 0u64;
        for _ in 0..lights {
            for p in &packed {
                for n in [p.max_side_vertices, 3 * p.faces, 3 * p.faces] {
                    reset.push(DrawIndirectArgs {
                        vertex_count: 0,
                        instance_count: 1,
                        first_vertex: first as u32,
                        first_instance: 0,
                    });
                    first += n as u64;
                }
            }
        }
        let bytes = first.max(1) * VERTEX;
        let buffer = |label, size, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        let vertices = buffer(
            "compute volumes",
            bytes,
            U::STORAGE | U::VERTEX | U::COPY_SRC,
        );
        let args_size = (reset.len() as u64).max(1) * ARGS;
        reset.resize(reset.len().max(1), DrawIndirectArgs::default());
        let reset_src = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("compute volume draws reset"),
                contents: bytemuck::cast_slice(&reset),
                usage: U::COPY_SRC,
            });
        let args = buffer(
            "compute volume draws",
            args_size,
            U::INDIRECT | U::STORAGE | U::COPY_DST | U::COPY_SRC,
        );
        let params_stride = (std::mem::size_of::<Params>() as u64)
            .next_multiple_of(limits.min_uniform_buffer_offset_alignment as u64);
        let slots = (lights * casters.len()).max(1) as u64;
        let params = buffer(
            "extrude params",
            params_stride * slots,
            U::UNIFORM | U::COPY_DST,
        );
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("extrude"),
                source: wgpu::ShaderSource::Wgsl(EXTRUDE_WGSL.into()),
            });
        let layout = bind_group_layout(gpu);
        let pipeline = compute_pipeline(gpu, &module, &layout);
        let packed_len = packed.len();
        let casters: Vec<(wgpu::BindGroup, PackedMesh)> = packed
            .into_iter()
            .map(|p| {
                let mesh = gpu
                    .device
                    .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some("caster adjacency"),
                        contents: bytemuck::cast_slice(&p.words),
                        usage: U::STORAGE,
                    });
                let params = wgpu::BufferBinding {
                    buffer: &params,
                    offset: 0,
                    size: wgpu::BufferSize::new(std::mem::size_of::<Params>() as u64),
                };
                let bg = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("extrude"),
                    layout: &layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::Buffer(params),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: mesh.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: vertices.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 3,
                            resource: args.as_entire_binding(),
                        },
                    ],
                });
                (bg, p)
            })
            .collect();
        Ok(ComputeVolumes {
            pipeline,
            params,
            params_stride,
            vertices,
            args,
            reset: reset_src,
            firsts: reset.iter().map(|a| a.first_vertex).collect(),
            slots: lights * packed_len,
            casters,
            lights,
        })
    }

    fn slot(&self, light: usize, caster: usize) -> usize {
        light * self.casters.len() + caster
    }

    // ANCHOR: extrude
    /// The per-frame work: for every light k and caster whose object
    /// `drawn(k, object)` says, the light in object space (`models`) and the reach
    /// (`reach[light][caster]`, 0 infinity) go to the shader, the vertex
    /// counts are reset, and one dispatch per (light, caster) writes the
    /// volumes. Timed as the pass `extrude`.
    pub fn extrude(
        &self,
        frame: &mut Frame,
        scene: &SceneGpu,
        objects: &[usize],
        (models, reach): (&[Mat4], &[Vec<f32>]),
        drawn: impl Fn(usize, usize) -> bool,
    ) {
        let mut jobs = Vec::new();
        for k in 0..self.lights {
            let world = world_light(scene, k);
            for (ci, &object) in objects.iter().enumerate() {
                if drawn(k, object) {
                    // Silhouettes in object space: the light moves, not the mesh.
                    let light = world.to_object_space(models[object]);
                    let w = reach.get(k).and_then(|r| r.get(ci)).copied();
                    jobs.push((k, ci, light, w.unwrap_or(0.0)));
                }
            }
        }
        let dispatches = self.write_params(frame.gpu, &jobs);
        frame.pass("extrude", |enc, ts| {
            self.record(enc, ts.compute(), &dispatches)
        });
    }
    // ANCHOR_END: extrude

    /// Writes the `Params` of each job (light k, caster, object-space
    /// light, reach w); returns the dispatches: (caster, slot, grid).
    fn write_params(
        &self,
        gpu: &Gpu,
        jobs: &[(usize, usize, LightDir, f32)],
    ) -> Vec<(usize, usize, (u32, u32))> {
        let max_groups = gpu.device.limits().max_compute_workgroups_per_dimension;
        let stride = self.params_stride as usize;
        let mut params = vec![0u8; stride * self.slots.max(1)];
        let mut dispatches = Vec::new();
        for &(k, ci, light, reach_w) in jobs {
            let p = &self.casters[ci].1;
            let n = p.edges + p.faces;
            if n == 0 {
                continue;
            }
            let groups = n.div_ceil(WORKGROUP);
            let grid = (groups.min(max_groups), groups.div_ceil(max_groups));
            let slot = self.slot(k, ci);
            let value = Params {
                light: light_params(light),
                reach_w,
                edges: p.edges,
                faces: p.faces,
                slot: slot as u32,
                offsets: p.offsets,
                row: grid.0 * WORKGROUP,
                _pad: [0; 2],
            };
            params[slot * stride..][..std::mem::size_of::<Params>()]
                .copy_from_slice(bytemuck::bytes_of(&value));
            dispatches.push((ci, slot, grid));
        }
        gpu.queue.write_buffer(&self.params, 0, &params);
        dispatches
    }

    /// Resets the counts and records the dispatches.
    fn record(
        &self,
        enc: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
        dispatches: &[(usize, usize, (u32, u32))],
    ) {
        // Every count back to 0 before the dispatches add to it.
        enc.copy_buffer_to_buffer(&self.reset, 0, &self.args, 0, self.args.size());
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("extrude"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        for &(ci, slot, (x, y)) in dispatches {
            let offset = (slot as u64 * self.params_stride) as u32;
            pass.set_bind_group(0, &self.casters[ci].0, &[offset]);
            pass.dispatch_workgroups(x, y, 1);
        }
    }

    /// One caster's indirect draws for light `light`: (byte offset in
    /// [`args`](Self::args), is it a cap?), the sides and the caps asked
    /// for, `(front, back)`. A directional light has no back cap (it is one point).
    pub fn draws(
        &self,
        scene: &SceneGpu,
        light: usize,
        caster: usize,
        (front, back): (bool, bool),
    ) -> Vec<(u64, bool)> {
        let directional = matches!(world_light(scene, light), LightDir::Directional(_));
        let at = self.slot(light, caster) as u64 * 3 * ARGS;
        [
            Some((at, false)),
            front.then_some((at + ARGS, true)),
            (back && !directional).then_some((at + 2 * ARGS, true)),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    /// Reads back every slot's vertex counts (sides, front cap, back cap),
    /// `counts[light * casters + caster]`, as the last frame left them.
    /// Untimed: its own submit.
    pub fn read_counts(&self, gpu: &Gpu) -> Result<Vec<[u32; 3]>> {
        let size = self.args.size();
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("compute volume counts"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(&self.args, 0, &staging, 0, size);
        gpu.queue.submit([enc.finish()]);
        let bytes = read_buffer(gpu, &staging, size, "compute volume counts")?;
        let words: &[u32] = bytemuck::cast_slice(&bytes);
        Ok((0..self.slots)
            .map(|s| [0, 1, 2].map(|p| words[(3 * s + p) * 4]))
            .collect())
    }

    /// The number of vertices on one side of a silhouette edge: 6 for a
    /// point light, 3 for a directional one.
    pub fn per_side(scene: &SceneGpu, light: usize) -> u32 {
        match world_light(scene, light) {
            LightDir::Directional(_) => 3,
            LightDir::Point(_) => 6,
        }
    }
}

/// One caster's volume for one light, built by the compute shader and
/// read back: (sides, front cap, back cap), each a triangle list in the
/// order the invocations appended it. [`cpu_volume_reaching`](super::extrusion::cpu_volume_reaching)'s
/// triangles, in another order (the tests compare the two).
pub fn extrude_once(
    gpu: &Gpu,
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
) -> Result<[Vec<CpuVertex>; 3]> {
    let volumes = ComputeVolumes::new(gpu, &[adj], 1)?;
    let dispatches = volumes.write_params(gpu, &[(0, 0, light, reach_w)]);
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    volumes.record(&mut enc, None, &dispatches);
    gpu.queue.submit([enc.finish()]);
    let counts = volumes.read_counts(gpu)?[0];
    let firsts = &volumes.firsts;
    let size = volumes.vertices.size();
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("compute volume readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    enc.copy_buffer_to_buffer(&volumes.vertices, 0, &staging, 0, size);
    gpu.queue.submit([enc.finish()]);
    let bytes = read_buffer(gpu, &staging, size, "compute volume")?;
    let all: &[CpuVertex] = bytemuck::cast_slice(&bytes);
    Ok([0, 1, 2].map(|p| {
        let first = firsts[p] as usize;
        all[first..first + counts[p] as usize].to_vec()
    }))
}
