//! Lesson 10's harness: what the runner measures and shows besides the
//! image. The counters: each lookup's blocker-search taps, filter taps and
//! texels read, the map's size and the frame's draw calls; the knobs of the
//! lesson's own techniques (a disk's radius, PCSS's taps and receiver
//! plane, a variance map's blur and bleed cut); the shadow map as the
//! window's buffer view.

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, BLOCKER_SEARCH_TAPS, DRAWS, FILTER_TAPS_PER_PIXEL, SHADOW_MAP_SIZE, TEXELS_READ,
};
use common::run::instruments::{BufferView, Instruments};
use common::run::knobs::Knob;
use common::Result;
use workbook::lesson_10::knobs;
use workbook::lesson_10::split::lit_keys;

use super::{Soft, Variant};

impl Instruments for Soft {
    /// The shadow map, as the last light's shadow pass left it.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        let Some(last) = scene.scene.lights.len().checked_sub(1) else {
            return Ok(None);
        };
        self.first_map(v).map.buffer_view(gpu, last).map(Some)
    }

    /// A lookup's search taps, filter taps and texels read (the most over
    /// the lights), the first light's map size, and the frame's draws.
    fn counters(&self, variant: Variant) -> Counts {
        // The most over the lights (the same technique on each).
        let (mut search, mut filter, mut texels) = (0, 0, 0);
        // The base pass, then per light its shadow pass and lit draws.
        let mut draws = self.objects;
        for (k, s) in self.per_light[variant].iter().enumerate() {
            let (a, b, c) = s.technique.taps();
            (search, filter, texels) = (search.max(a), filter.max(b), texels.max(c));
            let casters = self.maps.at(s.map).drawn[k].iter().filter(|&&d| d).count() as u64;
            let then = lit_keys(variant.module(), s.technique).1;
            draws += casters + self.objects * (1 + then.is_some() as u64);
        }
        Counts::from([
            (BLOCKER_SEARCH_TAPS, search),
            (FILTER_TAPS_PER_PIXEL, filter),
            (TEXELS_READ, texels),
            (SHADOW_MAP_SIZE, self.first_map(variant).size as u64),
            (DRAWS, draws),
        ])
    }

    /// The technique's knobs ([`knobs::technique_knobs`]), for the lesson's
    /// own techniques only.
    fn knobs(&self, variant: Variant) -> Vec<Knob> {
        match self.per_light[variant].first() {
            Some(s) if variant.has_knobs() => knobs::technique_knobs(s.technique),
            _ => Vec::new(),
        }
    }

    /// New parameters (and variance-map passes) for the variant on every
    /// light; a knob that changes a constant (taps, the receiver plane, the
    /// search) gets its pipeline the next time the variant renders.
    fn set_knob(
        &mut self,
        gpu: &Gpu,
        _scene: &SceneGpu,
        variant: Variant,
        name: &str,
        value: f64,
    ) -> Result<()> {
        for k in 0..self.geometry.len() {
            let mut t = self.per_light[variant][k].technique;
            knobs::set_technique_knob(&mut t, name, value)?;
            self.per_light[variant][k] = self.per_light(gpu, variant, k, t);
        }
        Ok(())
    }
}
