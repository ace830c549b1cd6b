//! Lesson 03's harness: what the runner measures and shows besides the
//! image. The kernels' sizes as knobs; the filter's taps, the map's size
//! and the standard costs as counters, and what the report counts around
//! the frame that `main.rs` draws, each in its own submits, once: the
//! shadow pass's depth writes (per shadow pass and map size) and the
//! adaptive filter's paths. The map as the window's buffer view.

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, DRAWS, FILTER_TAPS, FILTER_TAPS_PER_PIXEL, FULL_DISK_PIXELS, PROBED_PIXELS,
    SHADOW_FRAGMENTS, SHADOW_MAP_SIZE, SHADOW_TEXELS_WRITTEN, TAPS, TEXELS_READ,
};
use common::run::instruments::{BufferView, Instruments};
use common::run::knobs::Knob;
use common::Result;
use workbook::lesson_01::shadow_map;
use workbook::lesson_03::adaptive_count::{self, CountPass};
use workbook::lesson_03::knobs;
use workbook::lesson_03::pcf::Filter;

use super::{Pcf, Variant, VariantFilter};

impl Instruments for Pcf {
    /// The shadow map, as the variant's last shadow pass left it.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        self.map(v).map.last_light_view(gpu, scene)
    }

    /// The runner moved the camera or the light (`--fragile`, whose
    /// sub-texel move of the map `render` applies): the shadow pass and
    /// the adaptive filter are counted again on the next frame.
    fn count_again(&mut self, variant: Variant) {
        let key = (variant.pass(), variant.map_size());
        self.texels_written.retain(|(k, _)| *k != key);
        self.variants[variant].adaptive_paths = None;
    }

    /// The filter's taps and texels read, the map's size; the standard
    /// costs: the shadow pass's depth writes, the taps per pixel, the
    /// frame's draw calls; the adaptive filter's paths.
    fn counters(&self, variant: Variant) -> Counts {
        let (taps, texels) = self.variants[variant].filter.taps();
        let mut c = Counts::from([
            (TAPS, taps),
            (FILTER_TAPS_PER_PIXEL, taps),
            (TEXELS_READ, texels),
            (SHADOW_MAP_SIZE, variant.map_size() as u64),
            (DRAWS, self.draws),
        ]);
        let key = (variant.pass(), variant.map_size());
        if let Some(&(_, (written, fragments))) =
            self.texels_written.iter().find(|(k, _)| *k == key)
        {
            c.set(SHADOW_TEXELS_WRITTEN, written);
            c.set(SHADOW_FRAGMENTS, fragments);
        }
        if let Some(paths) = self.variants[variant].adaptive_paths {
            c.set(PROBED_PIXELS, paths.probed);
            c.set(FULL_DISK_PIXELS, paths.full_disk);
            c.set(FILTER_TAPS, paths.taps());
        }
        c
    }

    /// The lesson's own filters have their kernel's size: the grids and the
    /// depth average `kernel_radius`, the disk `disk_radius_texels`. The
    /// renderers' defaults and the exercises keep theirs.
    fn knobs(&self, variant: Variant) -> Vec<Knob> {
        match variant {
            Variant::LearnOpenGlPcf
            | Variant::WgpuExampleHw2x2
            | Variant::Bevy
            | Variant::ExercisePcfKernel
            | Variant::ExerciseWorldDisk => Vec::new(),
            _ => knobs::filter_knobs(self.variants[variant].filter),
        }
    }

    /// A new filter uniform for the variant; a grid's new side gets its
    /// pipeline the next time the variant draws.
    fn set_knob(
        &mut self,
        gpu: &Gpu,
        _scene: &SceneGpu,
        variant: Variant,
        name: &str,
        value: f64,
    ) -> Result<()> {
        let mut filter = self.variants[variant].filter;
        knobs::set_filter_knob(&mut filter, name, value)?;
        self.variants[variant] = VariantFilter::new(gpu, &self.filter_layout, variant, filter);
        Ok(())
    }
}

impl Pcf {
    /// The variant's shadow pass's depth writes and fragments, counted
    /// once per shadow pass and map size.
    pub(super) fn count_texels_once(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<()> {
        let (pass, size) = (variant.pass(), variant.map_size());
        let counted = self.texels_written.iter().any(|(k, _)| *k == (pass, size));
        if !counted {
            // In a web page the count comes back a frame or more later.
            let n = later(|| {
                shadow_map::count_shadow_texels(gpu, scene, size, |k| {
                    &self.tally_pipelines[pass][k]
                })
            })?;
            if let Some(n) = n {
                self.texels_written.push(((pass, size), n));
            }
        }
        Ok(())
    }

    /// The adaptive filter's paths ([`adaptive_count`]), counted once per
    /// variant and knob setting in its own submit: untimed.
    pub(super) fn count_adaptive_once(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        v: Variant,
    ) -> Result<()> {
        let adaptive = matches!(self.variants[v].filter, Filter::AdaptivePoisson { .. });
        if !adaptive || self.variants[v].adaptive_paths.is_some() {
            return Ok(());
        }
        let count = CountPass {
            shadow_pipelines: &self.shadow_pipelines[v.pass()],
            map: &self.map(v).map,
            count_pipeline: &self.adaptive_count,
            groups: &[self.map_group(v), &self.variants[v].filter_group],
        };
        let paths = later(|| adaptive_count::count_adaptive_paths(gpu, scene, targets, count))?;
        self.variants[v].adaptive_paths = paths;
        Ok(())
    }
}
