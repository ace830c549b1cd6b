//! Lesson 02's harness: what the runner measures and shows besides the
//! image. The bias sizes as knobs; the map's size, the casters drawn and
//! the shadow pass's depth writes as counters, those counted once per
//! variant (their own submits); the map as the window's buffer view. And
//! around the frame that `main.rs` draws, the exercises' lit pipelines,
//! compiled when an exercise first runs.

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, CASTERS_DRAWN, DRAWS, FILTER_TAPS_PER_PIXEL, SHADOW_FRAGMENTS, SHADOW_MAP_SIZE,
    SHADOW_TEXELS_WRITTEN,
};
use common::run::instruments::{BufferView, Instruments};
use common::run::knobs::Knob;
use common::run::lesson::variant_name;
use common::Result;
use workbook::lesson_01::shadow_map;
use workbook::lesson_02::{exercise_pass, knobs};

use super::{bias_group, hardware_pipelines, Bias, Fix, Variant};

impl Instruments for Bias {
    /// The shadow map, as the variant's last shadow pass left it.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        self.map(v).0.last_light_view(gpu, scene)
    }

    /// The runner moved the camera or the light (`--fragile`): the shadow
    /// pass's depth writes are counted again on the next frame.
    fn count_again(&mut self, variant: Variant) {
        self.variants[variant].texels_written = None;
    }

    /// The map's size and the casters the frame drew; the standard costs:
    /// the shadow pass's depth writes, one tap per pixel, the frame's draw
    /// calls.
    fn counters(&self, variant: Variant) -> Counts {
        let mut c = Counts::from([
            (SHADOW_MAP_SIZE, variant.map_size() as u64),
            (CASTERS_DRAWN, self.casters_drawn),
            (FILTER_TAPS_PER_PIXEL, 1),
            (DRAWS, self.draws),
        ]);
        if let Some((written, fragments)) = self.variants[variant].texels_written {
            c.set(SHADOW_TEXELS_WRITTEN, written);
            c.set(SHADOW_FRAGMENTS, fragments);
        }
        c
    }

    /// A receiver bias's sizes, or a hardware bias's ([`knobs`]); the
    /// exercises have none.
    fn knobs(&self, variant: Variant) -> Vec<Knob> {
        if variant.exercise().is_some() {
            return Vec::new();
        }
        match (variant.fix(), self.variants[variant].fix) {
            (Fix::Receiver(named), Fix::Receiver(now)) => knobs::receiver_knobs(named, now),
            (_, Fix::Hardware(now, _)) => knobs::hardware_knobs(now),
            _ => Vec::new(),
        }
    }

    /// A receiver bias: a new uniform for the variant. A hardware bias: its
    /// shadow pipelines (one per light) and their counting copies, rebuilt;
    /// its texels are counted again on its next frame.
    fn set_knob(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
        name: &str,
        value: f64,
    ) -> Result<()> {
        if variant.exercise().is_some() {
            anyhow::bail!("--knob {name}: {} has no knobs", variant_name(variant));
        }
        let state = &mut self.variants[variant];
        match &mut state.fix {
            Fix::Receiver(b) => {
                knobs::set_receiver(b, name, value)?;
                state.bias_group = bias_group(gpu, &self.layouts[1], variant, b);
            }
            Fix::Hardware(slope, cull) => {
                knobs::set_hardware(slope, name, value)?;
                let shaders = (&self.module, &self.tally);
                let (size, hw) = (variant.map_size(), (*slope, *cull));
                let (pipelines, tallies) = hardware_pipelines(gpu, scene, shaders, hw, size);
                state.slope_shadow = Some(pipelines);
                state.tally_slope = Some(tallies);
                state.texels_written = None;
            }
            _ => anyhow::bail!("--knob {name}: {} has no knobs", variant_name(variant)),
        }
        Ok(())
    }
}

impl Bias {
    /// The variant's shadow pass's depth writes and fragments, counted on
    /// its first frame through the counting copy of its pipeline.
    pub(super) fn count_texels_once(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<()> {
        if self.variants[variant].texels_written.is_some() {
            return Ok(());
        }
        let tally_slope = &self.variants[variant].tally_slope;
        let size = variant.map_size();
        // In a web page the count comes back a frame or more later.
        let n = later(|| {
            shadow_map::count_shadow_texels(gpu, scene, size, |k| {
                match (variant.fix(), tally_slope) {
                    (Fix::CullFrontFaces, _) => &self.tally_cull,
                    (_, Some(hw)) => &hw[k],
                    _ => &self.tally_plain,
                }
            })
        })?;
        self.variants[variant].texels_written = n;
        Ok(())
    }

    /// An exercise's lit pipeline, compiled on its first frame.
    pub(super) fn compile_exercise(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<()> {
        if let Some(e) = variant.exercise() {
            if !self.exercise_lit.iter().any(|(x, _)| *x == e) {
                let [map, bias] = &self.layouts;
                let p = exercise_pass::lit_pipeline(gpu, scene, e, &[map, bias])?;
                self.exercise_lit.push((e, p));
            }
        }
        Ok(())
    }

    /// The variant's lit pipeline: the lesson's, or its exercise's.
    pub(super) fn lit_for(&self, variant: Variant) -> &wgpu::RenderPipeline {
        let exercise = variant.exercise();
        (self.exercise_lit.iter())
            .find(|(x, _)| Some(*x) == exercise)
            .map_or(&self.lit_pipeline, |(_, p)| p)
    }
}
