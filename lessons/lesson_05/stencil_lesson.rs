//! [`StencilLesson`]: lessons 05 and 06's frame around
//! [`ShadowVolumes::shadow_frame`], with what their harnesses read of it:
//! the exercises' parts of the CPU route, the counts taken on a variant's
//! second frame, and the stencil the "buffer" view reads. No chapter
//! prints it; lesson 06 imports it rather than copy it.

use anyhow::Result;
use clap::ValueEnum;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::Counts;
use common::measure::timing::Frame;
use common::run::instruments::BufferView;
use common::run::per_variant::PerVariant;

use super::count_view::count_view;
use super::extrusion::{CpuParts, Extrusion};
use super::volumes::{CasterDraw, SecondFrameCounts, ShadowVolumes};

/// A variant's frame as the harness draws it: the variant (the counts are
/// per variant), its extrusion, and the CPU parts an exercise builds.
#[derive(Clone, Copy, Debug)]
pub struct VariantFrame<V> {
    pub variant: V,
    pub extrusion: Extrusion,
    pub parts: CpuParts,
}

/// The volumes and the lit pipeline of a lesson whose variants are `V`,
/// with what the harness keeps of them.
pub struct StencilLesson<V> {
    pub volumes: ShadowVolumes,
    pub lit_pipeline: wgpu::RenderPipeline,
    /// Each variant's counts, taken on its second frame.
    counts: PerVariant<V, SecondFrameCounts>,
    /// The last frame's depth-stencil texture, for the "buffer" view.
    depth_stencil: Option<wgpu::Texture>,
}

impl<V: ValueEnum + Copy + PartialEq> StencilLesson<V> {
    /// Nothing counted yet.
    pub fn new(volumes: ShadowVolumes, lit_pipeline: wgpu::RenderPipeline) -> StencilLesson<V> {
        StencilLesson {
            volumes,
            lit_pipeline,
            counts: PerVariant::new(|_| SecondFrameCounts::default()),
            depth_stencil: None,
        }
    }

    /// One frame of `draws` ([`ShadowVolumes::shadow_frame`]), counted on
    /// the variant's second frame. Returns the casters drawn.
    pub fn frame(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        v: VariantFrame<V>,
        draws: &[Vec<CasterDraw>],
    ) -> Result<u32> {
        let (ext, lit) = (v.extrusion, &self.lit_pipeline);
        self.volumes.set_cpu_parts(v.parts);
        let drawn = (self.volumes).shadow_frame(frame, scene, targets, ext, draws, lit)?;
        self.depth_stencil = Some(targets.depth.clone());
        let volumes = &self.volumes;
        self.counts[v.variant].after_frame(frame, |gpu| {
            volumes.count_all(gpu, scene, targets, ext, draws)
        })?;
        Ok(drawn)
    }

    /// Why variant `name`'s route cannot run here (its buffers would pass
    /// the adapter's limits), or `None`.
    pub fn unavailable(&self, name: &str, ext: Extrusion) -> Option<String> {
        let why = self.volumes.unfit(ext)?;
        Some(format!("{name}: {why}"))
    }

    /// Count `variant` again on its second frame from now.
    pub fn count_again(&mut self, variant: V) {
        self.counts[variant].again();
    }

    /// `variant`'s counts into `c`; `other_draws`: the base and lit
    /// passes' draw calls.
    pub fn insert_counts(&self, variant: V, c: &mut Counts, other_draws: u64) {
        self.counts[variant].insert_into(c, other_draws);
    }

    /// The stencil after the last light's volume pass, `what` its count.
    pub fn buffer_view(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        what: &str,
    ) -> Result<Option<BufferView>> {
        let (Some(ds), Some(last)) = (&self.depth_stencil, scene.scene.lights.len().checked_sub(1))
        else {
            return Ok(None);
        };
        count_view(gpu, ds, last, 0xff, what).map(Some)
    }
}
