//! Z-fail and its caps (lesson 06): Carmack's reverse counts the volume
//! faces *behind* the visible surface, out to infinity, where nothing
//! starts inside a volume. That needs closed volumes: a front cap (the
//! light-facing triangles) and a back cap (the same triangles at infinity,
//! reversed). Both are built with the sides by lesson 05's extrusion; this
//! module says how they are counted and drawn.

use crate::lesson_05::stencil::{count_face, two_sided, zpass_stencil, Counting, Method};
use crate::lesson_05::volumes::CasterDraw;

// ANCHOR: zfail_stencil
/// Z-fail: counted behind the surface (where the depth test fails):
/// leaving a volume (its back face) +1, entering it (its front face) −1.
pub fn zfail_stencil() -> wgpu::StencilState {
    use wgpu::StencilOperation::{DecrementWrap, IncrementWrap, Keep};
    two_sided(
        count_face(Keep, DecrementWrap),
        count_face(Keep, IncrementWrap),
    )
}
// ANCHOR_END: zfail_stencil

// ANCHOR: cap_bias
/// Caps are drawn pushed back by a hair. The front cap lies exactly on the
/// caster's lit faces, and z-fail needs it to *fail* there (equal depth
/// counts as behind). That holds only if the volume shader reproduces the
/// base pass's depth to the bit, which GL drivers do not promise across
/// programs: llvmpipe GL let a grazing front cap pass in stripes.
pub const CAP_DEPTH_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: 4,
    slope_scale: 2.0,
    clamp: 0.0,
};
// ANCHOR_END: cap_bias

// ANCHOR: zfail_draw
/// Sides and both caps, counted with z-fail.
pub fn zfail(object: usize) -> CasterDraw {
    CasterDraw {
        object,
        method: Method::ZFail,
        front_cap: true,
        back_cap: true,
    }
}

/// Volume pipelines that count z-pass and z-fail, caps pushed back by
/// [`CAP_DEPTH_BIAS`].
pub fn zfail_counting() -> Counting {
    Counting {
        zpass: zpass_stencil(),
        zfail: Some(zfail_stencil()),
        cap_bias: CAP_DEPTH_BIAS,
        unclipped_depth: false,
        finite_reach: false,
    }
}
// ANCHOR_END: zfail_draw
