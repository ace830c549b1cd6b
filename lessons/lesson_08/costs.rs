//! Lesson 08's cost counters, exact on every backend: copies of the
//! bounded volume pass count with lesson 01's [`Tally`] (1.0 added per
//! fragment that passes the copy's tests), with the variant's scissor and,
//! for the depth bounds, the same stencil bit 7 test against the same
//! marks. wgpu's GL occlusion queries only say "any", so they cannot.
//!
//! Untimed: its own submits, after a frame (it needs the frame's depth,
//! and overwrites the stencil).

use anyhow::Result;
use common::gpu::render::{pipeline_layout_for, SceneGpu};
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, DRAWS, STENCIL_FRAGMENTS, STENCIL_UPDATES, VOLUME_FRAGMENTS, VOLUME_TRIANGLES,
};

use super::bounds_test::{bounded_volume_stencil, BoundedLight, BoundedVolumes, Limits};
use crate::lesson_01::tally::{Tally, TallyShader};
use crate::lesson_05::extrusion::volume_shader_module;
use crate::lesson_05::quads::QUAD_VERTEX_LAYOUT;
use crate::lesson_06::caps::CAP_DEPTH_BIAS;

/// A frame's volume costs over every light ([`VolumeTally::count`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BoundedCosts {
    /// Fragments the volumes rasterise: after the scissor, before any
    /// depth or stencil test.
    pub volume_fragments: u64,
    /// Of those, the ones the emulated depth-bounds test (stencil bit 7)
    /// lets through to the stencil update, whatever their depth.
    pub stencil_fragments: u64,
    /// Of those, the ones that write the stencil: z-fail counts where the
    /// depth test fails.
    pub stencil_updates: u64,
    /// Triangles submitted for the volumes (sides and caps).
    pub volume_triangles: u64,
    /// Draw calls of the volume passes, the bounds markers' included.
    pub draws: u64,
}

impl BoundedCosts {
    /// The counters of the same names into `c`; [`DRAWS`] is
    /// `other_draws` (base and lit passes) plus the volume passes'.
    pub fn insert_into(&self, c: &mut Counts, other_draws: u64) {
        c.set(VOLUME_FRAGMENTS, self.volume_fragments);
        c.set(STENCIL_FRAGMENTS, self.stencil_fragments);
        c.set(STENCIL_UPDATES, self.stencil_updates);
        c.set(VOLUME_TRIANGLES, self.volume_triangles);
        c.set(DRAWS, other_draws + self.draws);
    }
}

/// The counting copies of the bounded volume pipelines and their target.
pub struct VolumeTally {
    /// `[bounds test][depth test][cap]`: the bit-7 stencil test or none,
    /// the volume pass's `Less` (with the caps' bias) or no depth test.
    pipelines: [[[wgpu::RenderPipeline; 2]; 2]; 2],
    tally: Tally,
}

impl VolumeTally {
    /// `unclipped_depth` as the volume pass has it ([`BoundedVolumes::new`]).
    pub fn new(gpu: &Gpu, scene: &SceneGpu, unclipped_depth: bool) -> VolumeTally {
        let module = volume_shader_module(gpu, "bounded volume tally", "");
        let shader = TallyShader::new(gpu);
        let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
        let quads = [Some(QUAD_VERTEX_LAYOUT)];
        let make = |bounds_test: bool, depth_test: bool, cap: bool| {
            let mut stencil = Default::default();
            if bounds_test {
                stencil = bounded_volume_stencil(true);
                stencil.write_mask = 0;
            }
            let (compare, bias) = match depth_test {
                true if cap => (wgpu::CompareFunction::Less, CAP_DEPTH_BIAS),
                true => (wgpu::CompareFunction::Less, Default::default()),
                false => (wgpu::CompareFunction::Always, Default::default()),
            };
            let desc = wgpu::RenderPipelineDescriptor {
                label: Some("bounded volume tally"),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_volume_quads"),
                    compilation_options: Default::default(),
                    buffers: &quads,
                },
                primitive: wgpu::PrimitiveState {
                    unclipped_depth,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: scene.depth_format,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(compare),
                    stencil,
                    bias,
                }),
                multisample: Default::default(),
                fragment: Some(shader.fragment()),
                multiview_mask: None,
                cache: None,
            };
            gpu.device.create_render_pipeline(&desc)
        };
        VolumeTally {
            pipelines: [false, true]
                .map(|b| [false, true].map(|d| [false, true].map(|cap| make(b, d, cap)))),
            tally: Tally::new(gpu, scene.width, scene.height),
        }
    }

    /// The costs of `lights`' volume passes against the frame's depth in
    /// `targets` ([`BoundedCosts`]). Per light: the bounds marks first (a
    /// stencil pass of their own, as the volume pass draws them), then
    /// three tallies under the light's scissor: no test (rasterised), the
    /// bit-7 test (reaching the stencil), the bit-7 and depth tests (the
    /// difference is z-fail's stencil writes).
    pub fn count(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        volumes: &BoundedVolumes,
        lights: &[BoundedLight],
    ) -> Result<BoundedCosts> {
        let mut costs = BoundedCosts::default();
        for b in lights {
            let (calls, triangles) = volumes.volume_draws(b);
            if b.limits != Limits::default() && b.bounds == Some(None) {
                continue; // the volume pass draws nothing for this light
            }
            let bounded = b.limits.depth_bounds && b.bounds.flatten().is_some();
            if bounded {
                let mut enc = gpu.device.create_command_encoder(&Default::default());
                volumes.limit(
                    &mut targets.stencil_pass(&mut enc, "mark bounds", None, None),
                    b,
                );
                gpu.queue.submit([enc.finish()]);
            }
            let tally = |bounds_test: bool, depth_test: bool| {
                let p = &self.pipelines[bounds_test as usize][depth_test as usize];
                self.tally
                    .count(gpu, Some(targets.depth_attachment_loaded()), |pass| {
                        if let (true, Some(lb)) = (b.limits.scissor, b.bounds.flatten()) {
                            let s = lb.scissor;
                            pass.set_scissor_rect(s.x, s.y, s.width, s.height);
                        }
                        pass.set_stencil_reference(super::bounds_test::BOUNDS_BIT);
                        volumes.draw_volumes(pass, scene, b, [[&p[0], &p[1]]; 2]);
                    })
            };
            let rasterised = tally(false, false)?;
            let reaching = if bounded {
                tally(true, false)?
            } else {
                rasterised
            };
            costs.volume_fragments += rasterised;
            costs.stencil_fragments += reaching;
            costs.stencil_updates += reaching - tally(bounded, true)?;
            costs.volume_triangles += triangles;
            costs.draws += calls + if bounded { 2 } else { 0 };
        }
        Ok(costs)
    }
}
