//! The depth-bounds test, emulated (lesson 08). wgpu has no depth-bounds
//! test (`VK_EXT_depth_bounds_test`, `GL_EXT_depth_bounds_test`).
//! [`BoundedVolumes`] emulates it with two full-screen triangles and the
//! fixed-function depth test: stencil bit 7 is set exactly where
//! zmin ≤ stored depth ≤ zmax, and the volume pass tests that bit. Its
//! costs are counted in [`super::costs`].

use anyhow::Result;
use common::gpu::bindings::{self, uniform_entry};
use common::gpu::fullscreen::Fullscreen;
use common::gpu::render::{pipeline_layout_for, SceneGpu};
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::fragment_counter::FragmentCounter;

use super::range_sphere::{caster_reaches, LightBounds, RangeSphere};
use crate::lesson_05::extrusion::volume_shader_module;
use crate::lesson_05::quads::QUAD_VERTEX_LAYOUT;
use crate::lesson_05::stencil::lit_stencil;
use crate::lesson_05::volumes::ShadowVolumes;
use crate::lesson_06::caps::{zfail_stencil, CAP_DEPTH_BIAS};

/// Bit 7 of the stencil: "this pixel's stored depth is inside the bounds".
pub const BOUNDS_BIT: u32 = 0x80;
/// Bits 0–6: the shadow-volume count. It wraps modulo 128, so lesson 08
/// warns from 128 overlapping volumes on (`count_bits`).
pub const COUNT_BITS: u32 = 0x7f;

const SLOT: u64 = 256;

/// One caster's pre-built volume: lesson 05's quads buffers (shared, not
/// copied), drawn whole (sides and both caps) with this module's pipelines.
struct Caster {
    object: usize,
    mirrored: bool,
    /// Bounding sphere, origin-relative ([`caster_reaches`]).
    center: common::glam::DVec3,
    radius: f64,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    /// The index ranges, each with "is it a cap?" (caps get lesson 06's bias).
    ranges: Vec<(std::ops::Range<u32>, bool)>,
}

/// `[mirrored][cap]`: the pipelines one volume draw picks from.
pub(super) type Pipes<'a> = [[&'a wgpu::RenderPipeline; 2]; 2];

/// Z-fail shadow volumes whose stencil updates can be limited to one
/// light's depth bounds (emulated) and scissor rectangle.
pub struct BoundedVolumes {
    casters: Vec<Caster>,
    /// `[bounded][mirrored][cap]`: the z-fail pipelines.
    volume: [[[wgpu::RenderPipeline; 2]; 2]; 2],
    /// No depth-stencil, an R8 target: for the pipeline-statistics counter.
    rasterised: wgpu::RenderPipeline,
    mark_max: wgpu::RenderPipeline,
    mark_min: wgpu::RenderPipeline,
    bounds_buf: wgpu::Buffer,
    bounds_group: wgpu::BindGroup,
}

/// Which of the two savings a volume pass uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Limits {
    pub scissor: bool,
    pub depth_bounds: bool,
    /// Draw only the casters that reach into the light's range
    /// ([`caster_reaches`]).
    pub cull: bool,
}

/// One light's bounded volume pass: the light, its range sphere (for
/// `cull`) and the sphere's bounds (`None` for a light without a range,
/// `Some(None)` when the sphere is off screen), and the savings to use.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundedLight {
    pub light: usize,
    pub sphere: RangeSphere,
    pub bounds: Option<Option<LightBounds>>,
    pub limits: Limits,
}

// ANCHOR: bounds_stencil
/// The volume pass's stencil with the emulated depth-bounds test: a
/// fragment updates the count only where bit 7 says "stored depth in
/// bounds" (compare Equal on bit 7 alone); the count lives in bits 0–6.
pub fn bounded_volume_stencil(bounded: bool) -> wgpu::StencilState {
    let mut s = zfail_stencil();
    for face in [&mut s.front, &mut s.back] {
        face.compare = if bounded {
            wgpu::CompareFunction::Equal
        } else {
            wgpu::CompareFunction::Always
        };
    }
    s.read_mask = BOUNDS_BIT;
    s.write_mask = COUNT_BITS;
    s
}

/// Stencil bit 7 := [stored depth ≤ zmax] (a quad at zmax, test GreaterEqual),
/// then bit 7 := 0 where stored depth < zmin (a quad at zmin, test Greater).
fn marker_stencil(
    pass_op: wgpu::StencilOperation,
    depth_fail_op: wgpu::StencilOperation,
) -> wgpu::StencilState {
    let face = wgpu::StencilFaceState {
        compare: wgpu::CompareFunction::Always,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op,
        pass_op,
    };
    wgpu::StencilState {
        front: face,
        back: face,
        read_mask: 0xff,
        write_mask: BOUNDS_BIT,
    }
}

/// The lit pass: the light where the count (bits 0–6) is 0.
pub fn bounded_lit_stencil() -> wgpu::StencilState {
    let mut s = lit_stencil();
    s.read_mask = COUNT_BITS;
    s
}
// ANCHOR_END: bounds_stencil

impl BoundedVolumes {
    /// `unclipped_depth`: clamp depth instead of clipping it (lesson 07's
    /// `clamp`), for a finite far plane; needs DEPTH_CLIP_CONTROL.
    pub fn new(
        gpu: &Gpu,
        scene: &SceneGpu,
        volumes: &ShadowVolumes,
        unclipped_depth: bool,
    ) -> Result<BoundedVolumes> {
        if unclipped_depth && !gpu.has(wgpu::Features::DEPTH_CLIP_CONTROL) {
            anyhow::bail!(
                "a finite far plane needs depth clamp (DEPTH_CLIP_CONTROL), which {} lacks; use far = \"infinite\"",
                gpu.adapter_name()
            );
        }
        let device = &gpu.device;
        // The same pre-built quads as lessons 05-07 draw: shared buffers.
        let casters = volumes
            .casters
            .iter()
            .map(|c| {
                let (vertices, indices, _) = c.quad_buffers();
                let r = &c.quad_ranges;
                let ranges = [(&r.sides, false), (&r.front, true), (&r.back, true)];
                Caster {
                    object: c.object,
                    mirrored: c.mirrored,
                    center: c.center,
                    radius: c.radius,
                    vertices,
                    indices,
                    ranges: ranges
                        .into_iter()
                        .filter(|(r, _)| !r.is_empty())
                        .map(|(r, cap)| (r.clone(), cap))
                        .collect(),
                }
            })
            .collect();
        let module = volume_shader_module(gpu, "bounded volumes", "");
        let entry = uniform_entry(0, wgpu::ShaderStages::VERTEX, true, Some(16));
        let bounds_layout = bindings::layout(gpu, "depth bounds", &[entry]);
        let lights = scene.scene.lights.len().max(1) as u32;
        let bounds_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("depth bounds"),
            size: SLOT * lights as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bounds_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("depth bounds"),
            layout: &bounds_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &bounds_buf,
                    offset: 0,
                    size: wgpu::BufferSize::new(16),
                }),
            }],
        });
        let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
        let quads = [Some(QUAD_VERTEX_LAYOUT)];
        let targets = [Some(wgpu::TextureFormat::R8Unorm.into())];
        let ds = |compare, stencil| wgpu::DepthStencilState {
            format: scene.depth_format,
            depth_write_enabled: Some(false),
            depth_compare: Some(compare),
            stencil,
            bias: Default::default(),
        };
        // Caps pushed back by lesson 06's bias, as lessons 06 and 07 draw them.
        let cap_ds = |compare, stencil, cap: bool| wgpu::DepthStencilState {
            bias: if cap {
                CAP_DEPTH_BIAS
            } else {
                Default::default()
            },
            ..ds(compare, stencil)
        };
        // The volumes: `ds` None is the rasterised-fragment counter's copy.
        let volume = |label: &str, ds: Option<wgpu::DepthStencilState>, mirrored: bool| {
            let fragment = ds.is_none().then(|| wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_volume_count"),
                compilation_options: Default::default(),
                targets: &targets,
            });
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_volume_quads"),
                    compilation_options: Default::default(),
                    buffers: &quads,
                },
                primitive: wgpu::PrimitiveState {
                    front_face: if mirrored {
                        wgpu::FrontFace::Cw
                    } else {
                        wgpu::FrontFace::Ccw
                    },
                    // The back caps and far ends past a finite far plane
                    // are clamped to depth 1, not clipped (lesson 07).
                    unclipped_depth,
                    ..Default::default()
                },
                depth_stencil: ds,
                multisample: Default::default(),
                fragment,
                multiview_mask: None,
                cache: None,
            })
        };
        use wgpu::CompareFunction::{Greater, GreaterEqual, Less};
        use wgpu::StencilOperation::{Keep, Replace, Zero};
        let bounded = |b: bool, m: bool| {
            [false, true].map(|cap| {
                let ds = cap_ds(Less, bounded_volume_stencil(b), cap);
                volume("bounded volume", Some(ds), m)
            })
        };
        let marker = |vs_entry, compare, stencil| {
            Fullscreen {
                label: vs_entry,
                wgsl: include_str!("../../shaders/lesson_08/bounds.wgsl"),
                vs_entry,
                fragment: None,
                groups: &[&bounds_layout],
                depth_stencil: Some(ds(compare, stencil)),
            }
            .pipeline(gpu)
        };
        Ok(BoundedVolumes {
            casters,
            volume: [
                [bounded(false, false), bounded(false, true)],
                [bounded(true, false), bounded(true, true)],
            ],
            rasterised: volume("volume fragments", None, false),
            mark_max: marker("vs_bound_max", GreaterEqual, marker_stencil(Replace, Zero)),
            mark_min: marker("vs_bound_min", Greater, marker_stencil(Zero, Keep)),
            bounds_buf,
            bounds_group,
        })
    }

    /// Draw calls and triangles of one light's volumes, as
    /// [`draw_volumes`](Self::draw_volumes) draws them, without the two
    /// bounds-marker triangles.
    pub fn volume_draws(&self, b: &BoundedLight) -> (u64, u64) {
        let ranges = (self.casters.iter())
            .filter(|c| self.drawn(b, c))
            .flat_map(|c| &c.ranges);
        ranges.fold((0, 0), |(d, t), (r, _)| (d + 1, t + r.len() as u64 / 3))
    }

    /// Uploads every light's depth bounds, one slot a light, in one write
    /// (before the frame is submitted); a light without bounds gets zeros,
    /// which nothing reads.
    pub fn write_bounds(&self, gpu: &Gpu, bounds: &[Option<Option<LightBounds>>]) {
        let mut slots = vec![0f32; bounds.len() * SLOT as usize / 4];
        for (slot, b) in slots.chunks_exact_mut(SLOT as usize / 4).zip(bounds) {
            if let Some(Some(b)) = b {
                slot[..2].copy_from_slice(&[b.depth.0, b.depth.1]);
            }
        }
        if !slots.is_empty() {
            gpu.queue
                .write_buffer(&self.bounds_buf, 0, bytemuck::cast_slice(&slots));
        }
    }

    /// Whether `b`'s volume pass draws caster `c`: every caster, or with
    /// `cull` only those that reach into the light's range.
    fn drawn(&self, b: &BoundedLight, c: &Caster) -> bool {
        !b.limits.cull || caster_reaches(b.sphere, c.center, c.radius)
    }

    /// Draws light `b.light`'s volumes (sides and caps of every caster, or
    /// with `cull` of the casters that reach into its range) with
    /// `pipes[mirrored][cap]`. Returns the casters drawn.
    pub(super) fn draw_volumes(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        scene: &SceneGpu,
        b: &BoundedLight,
        pipes: Pipes<'_>,
    ) -> u32 {
        scene.bind_frame(pass, b.light);
        let mut drawn = 0;
        for c in &self.casters {
            if !self.drawn(b, c) {
                continue;
            }
            drawn += 1;
            scene.bind_object(pass, c.object);
            pass.set_vertex_buffer(0, c.vertices.slice(..));
            pass.set_index_buffer(c.indices.slice(..), wgpu::IndexFormat::Uint32);
            for (range, cap) in &c.ranges {
                pass.set_pipeline(pipes[c.mirrored as usize][*cap as usize]);
                pass.draw_indexed(range.clone(), 0, 0..1);
            }
        }
        drawn
    }

    /// Scissor and the bit-7 marker for one light, inside an open pass.
    /// Returns whether the depth-bounds test applies.
    pub(super) fn limit(&self, pass: &mut wgpu::RenderPass<'_>, b: &BoundedLight) -> bool {
        let Some(bounds) = b.bounds.flatten() else {
            return false;
        };
        if b.limits.scissor {
            let s = bounds.scissor;
            pass.set_scissor_rect(s.x, s.y, s.width, s.height);
        }
        if b.limits.depth_bounds {
            let offset = (SLOT * b.light as u64) as u32;
            pass.set_bind_group(0, &self.bounds_group, &[offset]);
            pass.set_stencil_reference(BOUNDS_BIT);
            pass.set_pipeline(&self.mark_max);
            pass.draw(0..3, 0..1);
            pass.set_pipeline(&self.mark_min);
            pass.draw(0..3, 0..1);
        }
        b.limits.depth_bounds
    }

    // ANCHOR: bounded_volume_pass
    /// One light's z-fail volume pass, limited as `b.limits` says. Returns
    /// the number of casters drawn: 0 when the light's range sphere is off
    /// screen, since its volumes cannot change a lit pixel.
    pub fn volume_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &SceneGpu,
        targets: &FrameTargets,
        b: BoundedLight,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) -> u32 {
        let mut pass = targets.stencil_pass(encoder, "bounded volume pass", ts, None);
        if b.limits != Limits::default() && b.bounds == Some(None) {
            return 0; // the range sphere is behind the camera or off screen
        }
        let bounded = self.limit(&mut pass, &b);
        pass.set_stencil_reference(BOUNDS_BIT);
        let p = &self.volume[bounded as usize];
        let pipes = [[&p[0][0], &p[0][1]], [&p[1][0], &p[1][1]]];
        self.draw_volumes(&mut pass, scene, &b, pipes)
    }
    // ANCHOR_END: bounded_volume_pass

    /// Fragments the volumes rasterise (after the scissor, before any depth
    /// or stencil test), from pipeline statistics; `None` without them (GL).
    pub fn count_rasterised(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        counter: Option<&FragmentCounter>,
        lights: &[BoundedLight],
    ) -> Option<u64> {
        let counter = counter?;
        counter
            .count(gpu, |pass| {
                for b in lights {
                    if b.limits.scissor && b.bounds == Some(None) {
                        continue;
                    }
                    match b.bounds.flatten() {
                        Some(lb) if b.limits.scissor => pass.set_scissor_rect(
                            lb.scissor.x,
                            lb.scissor.y,
                            lb.scissor.width,
                            lb.scissor.height,
                        ),
                        _ => pass.set_scissor_rect(0, 0, scene.width, scene.height),
                    }
                    self.draw_volumes(pass, scene, b, [[&self.rasterised; 2]; 2]);
                }
            })
            .ok()
    }
}
