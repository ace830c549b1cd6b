//! Lesson 01's harness: what the runner measures and shows besides the
//! image. The map's size as a knob, the shadow pass's depth writes and the
//! texel's size as counters, the map as the window's buffer view and as an
//! extra image.

use std::path::Path;

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, DRAWS, FILTER_TAPS_PER_PIXEL, SHADOW_FRAGMENTS, SHADOW_TEXELS_WRITTEN, TEXEL_UM_U,
    TEXEL_UM_V,
};
use common::run::instruments::{BufferView, Instruments};
use common::run::knobs::{Knob, KnobRange};
use common::Result;

use super::{DepthMap, Variant, VariantMap};

impl Instruments for DepthMap {
    /// The variant's shadow map, as its last shadow pass left it.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        self.maps[v].map.last_light_view(gpu, scene)
    }

    /// The runner moved the camera or the light (`--fragile`): the shadow
    /// pass's depth writes are counted again on the next frame.
    fn count_again(&mut self, variant: Variant) {
        self.maps[variant].texels_written = None;
    }

    /// The texel's two sides, in micrometres: the acne's depth error, up to
    /// half a texel × tan θ (chapter 01), scales with them.
    /// Also the standard costs: the shadow pass's depth writes, one tap
    /// per pixel, the frame's draw calls.
    fn counters(&self, variant: Variant) -> Counts {
        let mut c = Counts::from([(FILTER_TAPS_PER_PIXEL, 1), (DRAWS, self.draws)]);
        if let Some((written, fragments)) = self.maps[variant].texels_written {
            c.set(SHADOW_TEXELS_WRITTEN, written);
            c.set(SHADOW_FRAGMENTS, fragments);
        }
        let texel = match variant {
            Variant::ExerciseTightFrustum => self.tight_texel_at_1,
            _ => self.texel_at_1,
        };
        if let Some((u, v)) = texel {
            let um = |x: f64| (x * 1e6 / self.resolution(variant) as f64).round() as u64;
            c.set(TEXEL_UM_U, um(u));
            c.set(TEXEL_UM_V, um(v));
        }
        c
    }

    /// The `res_*` variants: the map's size, 2^`map_size_log2` texels on a
    /// side, 256 to 4096 (the sweep's range); the exercises keep 1024².
    fn knobs(&self, variant: Variant) -> Vec<Knob> {
        if matches!(
            variant,
            Variant::ExerciseTightFrustum | Variant::ExerciseDepthCompare
        ) {
            return Vec::new();
        }
        vec![Knob {
            name: "map_size_log2",
            doc: "the shadow map is 2^map_size_log2 texels on a side (8: 256², 12: 4096²)",
            range: KnobRange::Int { min: 8, max: 12 },
            value: self.resolution(variant).ilog2() as f64,
        }]
    }

    /// A new map of the new size replaces the variant's (the old one is
    /// dropped); its texels are counted again on its next frame.
    fn set_knob(
        &mut self,
        gpu: &Gpu,
        _scene: &SceneGpu,
        variant: Variant,
        name: &str,
        value: f64,
    ) -> Result<()> {
        if name != "map_size_log2" {
            anyhow::bail!("--knob {name}: lesson_01 has only map_size_log2");
        }
        self.maps[variant] = VariantMap::new(gpu, &self.map_layout, 1 << value as u32);
        Ok(())
    }

    fn write_extras(&self, gpu: &Gpu, _: &SceneGpu, variant: Variant, out: &Path) -> Result<()> {
        let name = common::run::lesson::variant_name(variant);
        self.maps[variant]
            .map
            .write_png(gpu, &out.join(format!("{name}_depth_map.png")))
    }
}
