//! Lesson 05's harness: what the runner measures and shows besides the
//! image. The casters drawn and the volumes' costs as counters (counted on
//! a variant's second frame, in
//! [`StencilLesson`](workbook::lesson_05::stencil_lesson::StencilLesson)),
//! the routes an adapter cannot hold left out, and the z-pass count in the
//! stencil as the window's buffer view.

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::counters::{Counts, CASTERS_DRAWN};
use common::run::instruments::{BufferView, Instruments};
use common::run::lesson::variant_name;
use common::Result;

use super::{Variant, ZPass};

impl Instruments for ZPass {
    /// A route whose buffers would pass the adapter's limits
    /// ([`fit`](workbook::lesson_05::fit)) is left out; the others run.
    fn unavailable(&self, variant: Variant) -> Option<String> {
        (self.shadow).unavailable(&variant_name(variant), variant.extrusion())
    }

    /// The volumes' costs are counted again on the variant's second frame
    /// from now.
    fn count_again(&mut self, variant: Variant) {
        self.shadow.count_again(variant);
    }

    /// The scene's checks (mesh validation, the largest overlap), the
    /// casters drawn, and the volumes' costs once counted.
    fn counters(&self, variant: Variant) -> Counts {
        let mut c = self.scene_counters.clone();
        c.set(CASTERS_DRAWN, self.casters_drawn);
        (self.shadow).insert_counts(variant, &mut c, self.base_draws);
        c
    }

    /// The stencil: light N's z-pass count, N the last light.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, _: Variant) -> Result<Option<BufferView>> {
        self.shadow.buffer_view(gpu, scene, "z-pass count")
    }
}
