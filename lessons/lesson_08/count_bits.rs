//! How deep the count may go (lesson 08): stencil bit 7 holds the
//! depth-bounds mark, so the shadow-volume count has bits 0–6 only and
//! wraps modulo 128, not 256 as in lessons 05–07. A pixel inside exactly
//! 128 volumes reads 0 and is lit by mistake.

use common::gpu::render::SceneGpu;
use common::measure::counters::{Counts, MAX_VOLUME_OVERLAP};

use super::bounds_test::COUNT_BITS;
use crate::lesson_05::stencil::caster_counters;

// ANCHOR: count_wrap
/// The count's modulus: 128 (bits 0–6).
pub const COUNT_MODULUS: u32 = COUNT_BITS + 1;

/// Lesson 05's checks of the scene (mesh validation, and
/// [`MAX_VOLUME_OVERLAP`]: the most volumes over one point of a 64 × 36
/// pixel grid), with the warning where *this* lesson's count wraps: at
/// 128 overlapping volumes.
pub fn scene_counters(scene: &SceneGpu) -> Counts {
    let c = caster_counters(scene);
    let overlap = c.get(MAX_VOLUME_OVERLAP).unwrap_or(0);
    if overlap >= u64::from(COUNT_MODULUS) {
        eprintln!(
            "warning: up to {overlap} shadow volumes overlap: lesson_08 counts in stencil bits 0-6, which wrap at {COUNT_MODULUS} (a count of {COUNT_MODULUS} reads as 0, lit); lessons 06 and 07 count to 255"
        );
    }
    c
}
// ANCHOR_END: count_wrap
