//! Lesson 08's harness: what the runner measures and shows besides the
//! image. The volume passes' exact costs (fragments rasterised, reaching
//! the stencil, writing it; triangles; draw calls), the scissor area and
//! which extreme cases the camera meets, as counters, counted on a
//! variant's second frame; the three limits as knobs; the count in stencil
//! bits 0–6 as the window's buffer view.

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, FRAGMENT_SHADER_INVOCATIONS, LIGHTS_AROUND_CAMERA, LIGHTS_CROSSING_NEAR_PLANE,
    LIGHTS_CULLED, SCISSOR_PIXELS,
};
use common::measure::timing::Frame;
use common::run::instruments::{BufferView, Instruments};
use common::run::knobs::{Knob, KnobRange};
use common::Result;
use workbook::lesson_05::count_view::count_view;
use workbook::lesson_05::volumes::base_and_lit_draws;
use workbook::lesson_08::bounds_test::{Limits, COUNT_BITS};
use workbook::lesson_08::range_sphere::LightBounds;

use super::{bounded_lights, DepthBounds, Variant};

/// What lesson 08 counts of one variant: on its second frame, against the
/// first one's depth.
#[derive(Clone, Debug, Default)]
pub(super) struct VariantCounts {
    /// Frames drawn since the variant was last (re)set.
    frames: u32,
    /// The counters ([`DepthBounds::count`]); `None` until counted.
    counts: Option<Counts>,
}

impl DepthBounds {
    /// After a frame of `variant`: the second call finds the first frame's
    /// depth in place, and counts then, untimed (in a web page the counts
    /// come back a frame or more later).
    pub(super) fn after_frame(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        let n = &mut self.counted[variant].frames;
        *n += 1;
        if *n >= 2 && self.counted[variant].counts.is_none() {
            frame.untimed(|gpu| later(|| self.count(gpu, scene, targets, variant)))?;
        }
        Ok(())
    }

    /// The counters: the volume passes' exact costs (fragments rasterised,
    /// reaching the stencil, writing it; triangles; draw calls: a tally, on
    /// every backend), fragment-shader invocations (pipeline statistics,
    /// where the adapter has them), the scissor area.
    fn count(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        let lim = self.limits[variant];
        let lights = bounded_lights(&self.spheres, &self.bounds, lim);
        let mut c = Counts::new();
        let costs = self
            .tally
            .count(gpu, scene, targets, &self.bounded, &lights)?;
        costs.insert_into(&mut c, base_and_lit_draws(scene));
        // Pipeline statistics: llvmpipe counts 16 per 4×4 block shaded.
        let invocations =
            self.bounded
                .count_rasterised(gpu, scene, self.volumes.counter(), &lights);
        if let Some(r) = invocations {
            c.set(FRAGMENT_SHADER_INVOCATIONS, r);
        }
        let full = scene.width as u64 * scene.height as u64;
        let area = |b: &Option<Option<LightBounds>>| match b {
            Some(Some(b)) if lim.scissor => b.scissor.area(),
            Some(None) if lim.scissor => 0,
            _ => full,
        };
        c.set(SCISSOR_PIXELS, self.bounds.iter().map(area).sum());
        // Which extreme cases this camera meets (range sphere in view space).
        let (view, near) = (scene.camera.view.as_dmat4(), scene.scene.camera.near);
        let (mut inside, mut crossing) = (0, 0);
        for &(centre, range) in self.spheres.iter().flatten() {
            let v = view.transform_point3(centre);
            inside += (v.length() <= range) as u64;
            crossing += (v.length() > range && v.z + range > -near) as u64;
        }
        c.set(LIGHTS_AROUND_CAMERA, inside);
        c.set(LIGHTS_CROSSING_NEAR_PLANE, crossing);
        c.set(
            LIGHTS_CULLED,
            self.bounds
                .iter()
                .filter(|b| lim != Limits::default() && **b == Some(None))
                .count() as u64,
        );
        self.counted[variant].counts = Some(c);
        Ok(())
    }
}

impl Instruments for DepthBounds {
    /// Forget what the variant counted: it is counted again on its second
    /// frame from now.
    fn count_again(&mut self, variant: Variant) {
        self.counted[variant] = VariantCounts::default();
    }

    /// The scene's checks (mesh validation, the largest overlap) and, once
    /// counted, the variant's costs.
    fn counters(&self, variant: Variant) -> Counts {
        let mut c = self.scene_counters.clone();
        if let Some(counts) = &self.counted[variant].counts {
            c.extend(counts);
        }
        c
    }

    /// The three limits as toggles, on each of the six variants; the
    /// exercises keep theirs (the student's bounds are what they measure).
    fn knobs(&self, variant: Variant) -> Vec<Knob> {
        if matches!(
            variant,
            Variant::ExerciseScissorRect | Variant::ExerciseDepthBounds
        ) {
            return Vec::new();
        }
        let l = self.limits[variant];
        let toggle = |name, doc, on: bool| Knob {
            name,
            doc,
            range: KnobRange::Toggle,
            value: on as u8 as f64,
        };
        vec![
            toggle(
                "scissor",
                "volumes (and the light) drawn only inside the range sphere's screen rectangle",
                l.scissor,
            ),
            toggle(
                "depth_bounds",
                "volume fragments count only over stored depths inside the sphere's depth interval",
                l.depth_bounds,
            ),
            toggle(
                "cull",
                "only casters whose bounding sphere reaches into the range cast volumes",
                l.cull,
            ),
        ]
    }

    /// The next frames use the new limits; the counters are taken again on
    /// the variant's second frame from now.
    fn set_knob(
        &mut self,
        _gpu: &Gpu,
        _scene: &SceneGpu,
        variant: Variant,
        name: &str,
        value: f64,
    ) -> Result<()> {
        let l = &mut self.limits[variant];
        let on = value != 0.0;
        match name {
            "scissor" => l.scissor = on,
            "depth_bounds" => l.depth_bounds = on,
            "cull" => l.cull = on,
            _ => anyhow::bail!("--knob {name}: lesson_08 has scissor, depth_bounds and cull"),
        }
        self.counted[variant] = VariantCounts::default();
        Ok(())
    }

    /// The stencil's bits 0–6: light N's z-fail count, N the last light.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, _: Variant) -> Result<Option<BufferView>> {
        let (Some(ds), Some(last)) = (&self.depth_stencil, scene.scene.lights.len().checked_sub(1))
        else {
            return Ok(None);
        };
        let what = "z-fail count in bits 0-6 (bit 7, the bounds mark, left out)";
        count_view(gpu, ds, last, COUNT_BITS as u8, what).map(Some)
    }
}
