//! Exact fragment counts on every backend (lessons 01–08's cost counters).
//!
//! wgpu's GL backend implements occlusion queries as ANY_SAMPLES_PASSED
//! (0 or 1), and pipeline statistics exist on Vulkan only (llvmpipe counts
//! 16 per 4×4 block there). A [`Tally`] counts instead with blending: a
//! copy of the pass under test, with the same depth-stencil state, draws
//! 1.0 per fragment that survives its tests into an `R16Float` target with
//! additive blending; the sum of the target, read back, is the count. The
//! same fixed-function tests decide, so the count is the pass's own, on
//! Vulkan and GL alike. Exact while no pixel gets more than 2048 fragments
//! (the largest run of integers an f16 holds): [`Tally::count`] says when
//! a pixel reached it.
//!
//! Counting is untimed work with its own submit and readback: lessons run
//! it once per variant, after a frame, never inside a timed pass.

use anyhow::{bail, Result};
use common::gpu::readback::read_texture;
use common::gpu::targets::render_texture;
use common::gpu::Gpu;

/// The format of the tally target.
pub const TALLY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;

/// The largest exact count per pixel: 2^11 (f16 has an 11-bit significand).
pub const TALLY_PIXEL_MAX: u64 = 2048;

const TALLY_WGSL: &str =
    "@fragment fn fs_tally() -> @location(0) vec4<f32> { return vec4<f32>(1.0); }";

/// The additive blend: every fragment adds its 1.0.
const ADD: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// The one colour target of every counting pipeline: `R16Float`, added.
pub const TALLY_TARGETS: [Option<wgpu::ColorTargetState>; 1] = [Some(wgpu::ColorTargetState {
    format: TALLY_FORMAT,
    blend: Some(ADD),
    write_mask: wgpu::ColorWrites::RED,
})];

/// The fragment shader every counting pipeline uses (`fs_tally`: 1.0 into
/// one `R16Float` target, added). Pipelines pair it with their own vertex
/// shader and depth-stencil state.
pub struct TallyShader {
    module: wgpu::ShaderModule,
}

impl TallyShader {
    pub fn new(gpu: &Gpu) -> TallyShader {
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("tally"),
                source: wgpu::ShaderSource::Wgsl(TALLY_WGSL.into()),
            });
        TallyShader { module }
    }

    /// The fragment state of a counting pipeline.
    pub fn fragment(&self) -> wgpu::FragmentState<'_> {
        wgpu::FragmentState {
            module: &self.module,
            entry_point: Some("fs_tally"),
            compilation_options: Default::default(),
            targets: &TALLY_TARGETS,
        }
    }
}

/// A `width × height` tally target and its count.
pub struct Tally {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

impl Tally {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Tally {
        let texture = render_texture(
            gpu,
            "tally",
            width,
            height,
            TALLY_FORMAT,
            wgpu::TextureUsages::COPY_SRC,
        );
        let view = texture.create_view(&Default::default());
        Tally { texture, view }
    }

    /// Clears the target, records `draw` (pipelines with
    /// [`TallyShader::fragment`]) in one pass with `depth` (or none), submits,
    /// and returns the fragments that passed. An error when a pixel reached
    /// [`TALLY_PIXEL_MAX`], past which the count is no longer exact.
    pub fn count(
        &self,
        gpu: &Gpu,
        depth: Option<wgpu::RenderPassDepthStencilAttachment<'_>>,
        draw: impl FnOnce(&mut wgpu::RenderPass<'_>),
    ) -> Result<u64> {
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("tally"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: depth,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            draw(&mut pass);
        }
        gpu.queue.submit([enc.finish()]);
        let bytes = read_texture(gpu, &self.texture, 2)?;
        let mut sum = 0;
        for c in bytes.chunks_exact(2) {
            let n = f16_integer(u16::from_le_bytes([c[0], c[1]]));
            if n >= TALLY_PIXEL_MAX {
                bail!("tally: a pixel got {TALLY_PIXEL_MAX} or more fragments, past an exact f16 count");
            }
            sum += n;
        }
        Ok(sum)
    }
}

/// A non-negative integer-valued f16 as an integer (0 for anything else:
/// the target only ever holds sums of 1.0).
pub fn f16_integer(bits: u16) -> u64 {
    let exp = (bits >> 10) & 0x1f;
    let frac = u64::from(bits & 0x3ff);
    if bits & 0x8000 != 0 || exp == 0 {
        return 0;
    }
    if exp == 0x1f {
        return u64::MAX; // infinity: past any exact count
    }
    let m = frac | 0x400; // 1.frac × 2^(exp − 15), 10 fraction bits
    let e = exp as i32 - 15 - 10;
    if e >= 0 {
        m << e
    } else {
        m >> (-e)
    }
}

#[cfg(test)]
mod tests {
    use super::f16_integer;

    #[test]
    fn f16_integers_decode() {
        // 1.0 = 0x3c00, 2.0 = 0x4000, 3.0 = 0x4200, 1024 = 0x6400, 2048 = 0x6800.
        for (bits, n) in [
            (0x3c00, 1),
            (0x4000, 2),
            (0x4200, 3),
            (0x6400, 1024),
            (0x6800, 2048),
        ] {
            assert_eq!(f16_integer(bits), n);
        }
        assert_eq!(f16_integer(0), 0);
    }
}
