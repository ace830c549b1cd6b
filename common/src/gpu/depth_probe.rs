//! What a depth format really stores, asked of the adapter.
//!
//! wgpu's `Depth24PlusStencil8` is 24-bit unorm (D24_UNORM_S8) where the
//! driver has it and 32-bit float (D32F + S8) where it does not, so the
//! name does not say how finely the scene's depth buffer separates two
//! surfaces. The probe draws, into one pixel each, a surface at window
//! depth z and then one at z − δ with the `Less` test, where z ≈ 1e-3 and
//! δ = 2⁻³⁰ ≈ 9.3e-10: eight f32 steps there, but 1/64 of a 24-bit step.
//! Float32 keeps every pair apart (the second surface wins); a 24-bit
//! format merges nearly all of them (the first one stays). Three control
//! pixels check the test itself: a tie and the reverse order must keep the
//! first surface, a gap of z/2 must let the second win.

use anyhow::{Context, Result};
use wgpu::util::DeviceExt;

use crate::gpu::readback::read_texture;
use crate::gpu::targets::render_texture;
use crate::gpu::Gpu;

/// What a depth format stores, as measured by [`probe`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthStorage {
    /// 24-bit unsigned normalised: steps of 1/(2²⁴ − 1) everywhere.
    Unorm24,
    /// 32-bit float: steps that shrink towards 0 (2⁻²⁴ just below 1).
    Float32,
    /// The probe's pixels fit neither (its controls failed, or some but
    /// not all pairs were kept apart).
    Unknown,
}

impl DepthStorage {
    /// `"unorm24"`, `"float32"` or `"unknown"`, as report.json writes it.
    pub fn name(self) -> &'static str {
        match self {
            DepthStorage::Unorm24 => "unorm24",
            DepthStorage::Float32 => "float32",
            DepthStorage::Unknown => "unknown",
        }
    }
}

/// What the probe saw: the storage, and the pixels it was read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DepthProbe {
    pub storage: DepthStorage,
    /// Pairs (z, z − δ) whose second surface won, of [`PAIRS`].
    pub separated: u32,
    /// The tie, the reverse order and the wide gap behaved.
    pub controls_ok: bool,
}

/// Pairs probed, spread over z ∈ [1e-3, 1.9e-3).
pub const PAIRS: u32 = 32;
/// The gap of a pair: 2⁻³⁰, exact in f32 at these depths.
pub const DELTA: f32 = 1.0 / (1u64 << 30) as f32;
/// At most this many pairs kept apart still reads as 24-bit unorm: a
/// boundary between two 24-bit steps falls inside a pair with chance 1/64.
pub const UNORM24_MAX_SEPARATED: u32 = 8;

/// The probe quads (`shaders/depth_storage.wgsl`).
const PROBE_WGSL: &str = include_str!("../../../shaders/depth_storage.wgsl");

/// The probe's draws, in order: `(column, depth, value)`. Every column's
/// first surface (value 0) is drawn before any second one (value 1).
fn instances() -> Vec<(u32, f32, f32)> {
    let z = |j: u32| 1e-3_f32 * (1.0 + 0.9 * j as f32 / PAIRS as f32);
    let (c, z0) = (PAIRS, 1e-3_f32);
    // Controls: a tie, the reverse order, a wide gap.
    let controls = [(z0, z0), (z0 - DELTA, z0), (z0, 0.5 * z0)];
    let mut first: Vec<(u32, f32, f32)> = (0..PAIRS).map(|j| (j, z(j), 0.0)).collect();
    let mut second: Vec<(u32, f32, f32)> = (0..PAIRS).map(|j| (j, z(j) - DELTA, 1.0)).collect();
    for (k, (a, b)) in controls.into_iter().enumerate() {
        first.push((c + k as u32, a, 0.0));
        second.push((c + k as u32, b, 1.0));
    }
    first.extend(second);
    first
}

/// Classifies the probe's pixels (`won[i]`: column i shows the second
/// surface): `PAIRS` pairs, then the tie, the reverse order, the wide gap.
pub fn classify(won: &[bool]) -> DepthProbe {
    let p = PAIRS as usize;
    let separated = won[..p].iter().filter(|&&w| w).count() as u32;
    let controls_ok = !won[p] && !won[p + 1] && won[p + 2];
    let storage = match (controls_ok, separated) {
        (false, _) => DepthStorage::Unknown,
        (true, s) if s == PAIRS => DepthStorage::Float32,
        (true, s) if s <= UNORM24_MAX_SEPARATED => DepthStorage::Unorm24,
        _ => DepthStorage::Unknown,
    };
    DepthProbe {
        storage,
        separated,
        controls_ok,
    }
}

// ANCHOR: probe
/// One draw of a depth-test probe ([`draw_probe`]).
pub struct ProbeDraw<'a> {
    pub label: &'a str,
    /// WGSL with `vs_probe` (instance `[f32; 4]` at location 0, four
    /// strip vertices a quad) and `fs_probe` (R8 colour).
    pub module: &'a wgpu::ShaderModule,
    /// The depth (or depth-stencil) format under test.
    pub format: wgpu::TextureFormat,
    pub compare: wgpu::CompareFunction,
    /// The depth the buffer is cleared to.
    pub clear: f32,
    /// The R8 target's size.
    pub size: (u32, u32),
    /// The quads, drawn in this order (one draw: the API keeps the
    /// instances' order at every pixel).
    pub instances: &'a [[f32; 4]],
    /// Bind group 0 and its layout, if the shader has one.
    pub group: Option<(&'a wgpu::BindGroupLayout, &'a wgpu::BindGroup)>,
}

/// Draws `d`'s quads with the real depth test and reads back the R8
/// target: at each pixel, the value of the last quad that passed. Shared
/// by [`probe`] and lesson 07's precision study.
pub fn draw_probe(gpu: &Gpu, d: &ProbeDraw) -> Result<Vec<u8>> {
    let device = &gpu.device;
    let ibuf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(d.label),
        contents: bytemuck::cast_slice(d.instances),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> =
        d.group.iter().map(|(l, _)| Some(*l)).collect();
    let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(d.label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(d.label),
        layout: Some(&pl),
        vertex: wgpu::VertexState {
            module: d.module,
            entry_point: Some("vs_probe"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 16,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &wgpu::vertex_attr_array![0 => Float32x4],
            })],
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleStrip,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: d.format,
            depth_write_enabled: Some(true),
            depth_compare: Some(d.compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: d.module,
            entry_point: Some("fs_probe"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::TextureFormat::R8Unorm.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let (w, h) = d.size;
    let none = wgpu::TextureUsages::empty();
    let r8 = wgpu::TextureFormat::R8Unorm;
    let color = render_texture(gpu, "probe colour", w, h, r8, none);
    let depth = render_texture(gpu, "probe depth", w, h, d.format, none);
    let (cv, dv) = (
        color.create_view(&Default::default()),
        depth.create_view(&Default::default()),
    );
    let stencil_ops = d.format.has_stencil_aspect().then_some(wgpu::Operations {
        load: wgpu::LoadOp::Clear(0),
        store: wgpu::StoreOp::Store,
    });
    let mut enc = device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(d.label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &cv,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &dv,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(d.clear),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        if let Some((_, g)) = d.group {
            pass.set_bind_group(0, g, &[]);
        }
        pass.set_vertex_buffer(0, ibuf.slice(..));
        pass.draw(0..4, 0..d.instances.len() as u32);
    }
    gpu.queue.submit([enc.finish()]);
    read_texture(gpu, &color, 1).with_context(|| format!("{} readback", d.label))
}

/// Asks the adapter what `format` (a depth or depth-stencil format)
/// stores: renders the probe into a `(PAIRS + 3)`×1 target and reads
/// back which surface each pixel kept.
pub fn probe(gpu: &Gpu, format: wgpu::TextureFormat) -> Result<DepthProbe> {
    let w = PAIRS + 3;
    let inst: Vec<[f32; 4]> = instances()
        .iter()
        .map(|&(c, z, v)| [c as f32, z, v, w as f32])
        .collect();
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("depth storage probe"),
            source: wgpu::ShaderSource::Wgsl(PROBE_WGSL.into()),
        });
    let px = draw_probe(
        gpu,
        &ProbeDraw {
            label: "depth storage probe",
            module: &module,
            format,
            compare: wgpu::CompareFunction::Less,
            clear: 1.0,
            size: (w, 1),
            instances: &inst,
            group: None,
        },
    )?;
    let won: Vec<bool> = px.iter().map(|&v| v > 127).collect();
    Ok(classify(&won))
}
// ANCHOR_END: probe

#[cfg(test)]
mod tests {
    use super::*;

    /// The probe's pixels as a format would leave them: the second surface
    /// wins where its stored value is below the first's.
    fn simulate(store: impl Fn(f32) -> u64) -> DepthProbe {
        let mut stored = vec![u64::MAX; PAIRS as usize + 3];
        let mut won = vec![false; stored.len()];
        for (c, z, v) in instances() {
            let s = store(z);
            if s < stored[c as usize] {
                stored[c as usize] = s;
                won[c as usize] = v > 0.5;
            }
        }
        classify(&won)
    }

    #[test]
    fn float32_keeps_every_pair_apart_and_unorm24_almost_none() {
        let f32_probe = simulate(|z| z.to_bits() as u64);
        assert_eq!(f32_probe.storage, DepthStorage::Float32, "{f32_probe:?}");
        // 24-bit unorm, rounded to nearest and truncated.
        for round in [f64::round, f64::floor] {
            let p = simulate(|z| round(z as f64 * 16_777_215.0) as u64);
            assert_eq!(p.storage, DepthStorage::Unorm24, "{p:?}");
        }
    }

    #[test]
    fn a_broken_depth_test_is_unknown() {
        // No depth test: the second surface always wins (the tie too).
        let mut won = vec![true; PAIRS as usize + 3];
        assert_eq!(classify(&won).storage, DepthStorage::Unknown);
        // Half the pairs apart: neither format.
        for (i, w) in won.iter_mut().enumerate() {
            *w = i % 2 == 0;
        }
        let n = PAIRS as usize;
        (won[n], won[n + 1], won[n + 2]) = (false, false, true);
        assert_eq!(classify(&won).storage, DepthStorage::Unknown);
    }

    #[test]
    fn the_pairs_are_exact_f32_steps_apart() {
        for (_, z, _) in instances()
            .iter()
            .filter(|d| d.2 > 0.5)
            .take(PAIRS as usize)
        {
            let up = z + DELTA;
            assert_eq!(up - DELTA, *z, "δ is exact at {z}");
            assert_eq!(((up.to_bits() - z.to_bits()) as f32).log2(), 3.0);
        }
    }
}
