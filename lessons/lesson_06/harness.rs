//! Lesson 06's harness: what the runner measures and shows besides the
//! image. What each variant's plan chose (casters counted with z-pass,
//! with z-fail, left out) and the volumes' costs as counters (counted on a
//! variant's second frame, in lesson 05's
//! [`StencilLesson`](workbook::lesson_05::stencil_lesson::StencilLesson)),
//! the routes an adapter cannot hold left out, and the volume count in the
//! stencil as the window's buffer view.

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, CASTERS_DRAWN, CASTERS_SKIPPED, CASTERS_ZFAIL, CASTERS_ZPASS,
};
use common::run::instruments::{BufferView, Instruments};
use common::run::lesson::variant_name;
use common::Result;
use workbook::lesson_05::stencil::Method;
use workbook::lesson_05::volumes::CasterDraw;

use super::{Variant, ZFail};

/// What a variant's draws chose, over every light: casters counted with
/// z-pass, with z-fail, and left out.
#[derive(Clone, Copy, Debug, Default)]
struct Chosen {
    zpass: u64,
    zfail: u64,
    skipped: u64,
}

impl Chosen {
    /// Counted from the draws, `casters` casters per light.
    fn of(per_light: &[Vec<CasterDraw>], casters: usize) -> Chosen {
        let mut c = Chosen::default();
        for draws in per_light {
            let method = |m| draws.iter().filter(|d| d.method == m).count() as u64;
            c.zpass += method(Method::ZPass);
            c.zfail += method(Method::ZFail);
            c.skipped += (casters - draws.len()) as u64;
        }
        c
    }
}

impl Instruments for ZFail {
    /// A route whose buffers would pass the adapter's limits is left out.
    fn unavailable(&self, variant: Variant) -> Option<String> {
        (self.shadow).unavailable(&variant_name(variant), variant.extrusion())
    }

    /// The volumes' costs are counted again on the variant's second frame
    /// from now.
    fn count_again(&mut self, variant: Variant) {
        self.shadow.count_again(variant);
    }

    /// The scene's checks (mesh validation, the largest overlap), what the
    /// variant's plan chose, and the volumes' costs once counted.
    fn counters(&self, variant: Variant) -> Counts {
        let mut c = self.scene_counters.clone();
        let s = Chosen::of(&self.plans[variant], self.shadow.volumes.casters.len());
        c.set(CASTERS_ZPASS, s.zpass);
        c.set(CASTERS_ZFAIL, s.zfail);
        c.set(CASTERS_SKIPPED, s.skipped);
        c.set(CASTERS_DRAWN, s.zpass + s.zfail);
        (self.shadow).insert_counts(variant, &mut c, self.base_draws);
        c
    }

    /// The stencil: light N's count, N the last light.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, _: Variant) -> Result<Option<BufferView>> {
        let what = "volume count (z-pass and z-fail leave the same)";
        self.shadow.buffer_view(gpu, scene, what)
    }
}
