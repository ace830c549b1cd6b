//! `pcss_min_max`'s lit pass in two draws (lesson 10): the first asks the
//! min/max chain ([`super::min_max`]) and answers where it can tell, the
//! second takes PCSS's taps only where the stencil shows no answer. A
//! branch in one shader would not save the taps on a software rasteriser,
//! which runs a branch's code, masked, for pixels that skip it; the
//! stencil test rejects them before the shader runs.

use super::exercise_shaders::Module;
use super::soft::{SoftConstants, Technique};

// ANCHOR: split
/// A lit pipeline's part in the stencil: none, or one of `pcss_min_max`'s
/// two draws, each light's stencil reference its index plus one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stencil {
    None,
    /// The chain's answers: each pixel answered gets the reference.
    Answer,
    /// PCSS's taps, only where the stencil is not the reference: before
    /// the shader runs, not a branch in it.
    Rest,
}

impl Stencil {
    /// The lit pipeline's stencil state for this part.
    pub fn state(self) -> wgpu::StencilState {
        let face = |compare, pass_op| wgpu::StencilFaceState {
            compare,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op,
        };
        let (face, write_mask) = match self {
            Stencil::None => return Default::default(),
            Stencil::Answer => (
                face(
                    wgpu::CompareFunction::Always,
                    wgpu::StencilOperation::Replace,
                ),
                0xff,
            ),
            Stencil::Rest => (
                face(
                    wgpu::CompareFunction::NotEqual,
                    wgpu::StencilOperation::Keep,
                ),
                0,
            ),
        };
        wgpu::StencilState {
            front: face,
            back: face,
            read_mask: 0xff,
            write_mask,
        }
    }
}

/// A lit pipeline's key: its shader module, constants and stencil part.
pub type LitKey = (Module, SoftConstants, Stencil);

/// A technique's lit pipelines: its own, and for `pcss_min_max` the
/// plain PCSS after it (none with the knob `chain_only`).
pub fn lit_keys(module: Module, t: Technique) -> (LitKey, Option<LitKey>) {
    let c = SoftConstants::new(t);
    let chain_only = matches!(t, Technique::Pcss(p) if p.chain_only);
    let plain = SoftConstants {
        min_max: false,
        ..c
    };
    match c.min_max {
        false => ((module, c, Stencil::None), None),
        true => (
            (module, c, Stencil::Answer),
            (!chain_only).then_some((module, plain, Stencil::Rest)),
        ),
    }
}
// ANCHOR_END: split
