//! How finely a depth buffer separates two surfaces (lesson 07).
//!
//! Four depth mappings (standard, reversed-Z, infinite far plane with the
//! Everitt–Kilgard ε, infinite reversed) × two formats (`Depth24PlusStencil8`,
//! `Depth32FloatStencil8`). Two ways to measure the same thing:
//!
//! - **GPU**: [`measure_gpu`] draws, into one pixel per (distance, gap),
//!   a far quad at `d·(1 + gap)` and then a near quad at `d`, both facing the
//!   camera, with the real depth test. The pixel shows the near quad only if
//!   the GPU's depth pipeline (f32 clip maths, rasteriser, format
//!   quantisation) kept the two depths apart and in the right order.
//! - **CPU model**: [`resolves_cpu`] repeats the f32 clip maths and quantises
//!   like the format does (24-bit unorm rounding, or the f32 itself). Which
//!   of the two a format does is asked of the adapter ([`storage_of`]):
//!   `Depth24PlusStencil8` is 32-bit float on some.
//!
//! One sample per cell would let rounding luck decide: whether two depths
//! land in different storage steps depends on where in a step the first
//! one falls. So every (distance, gap) cell holds [`SAMPLES`] distances
//! jittered across ±5 % of d, and a gap counts as resolved at d when at
//! least [`QUANTILE`] of them resolve. The figure of merit is the smallest
//! relative gap Δd/d from which every larger gap of the grid [`gaps`]
//! resolves. [`analytic_gap`] gives the curve it should follow: one storage
//! step divided by the slope of the mapping.

use anyhow::Result;
use common::gpu::bindings::{self, uniform_entry};
use common::gpu::depth_probe::{self, DepthStorage};
use common::gpu::Gpu;
use wgpu::util::DeviceExt;

use super::infinite_far::{DepthMapping, MAPPINGS};

/// The two depth-stencil formats the study compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthFormat {
    D24,
    D32F,
}

pub const FORMATS: [DepthFormat; 2] = [DepthFormat::D24, DepthFormat::D32F];

impl DepthFormat {
    pub fn name(self) -> &'static str {
        match self {
            DepthFormat::D24 => "Depth24PlusStencil8",
            DepthFormat::D32F => "Depth32FloatStencil8",
        }
    }

    pub fn wgpu(self) -> wgpu::TextureFormat {
        match self {
            DepthFormat::D24 => wgpu::TextureFormat::Depth24PlusStencil8,
            DepthFormat::D32F => wgpu::TextureFormat::Depth32FloatStencil8,
        }
    }
}

/// What `f` stores on this adapter, measured ([`depth_probe`]). Where the
/// adapter lacks the format, or the probe cannot tell or run (a web
/// page), what the name says.
pub fn storage_of(gpu: &Gpu, f: DepthFormat) -> Result<DepthStorage> {
    let has = f == DepthFormat::D24 || gpu.has(wgpu::Features::DEPTH32FLOAT_STENCIL8);
    let has = has && gpu.can_wait();
    let probed = match has {
        true => depth_probe::probe(gpu, f.wgpu())?.storage,
        false => DepthStorage::Unknown,
    };
    Ok(match (probed, f) {
        (DepthStorage::Unknown, DepthFormat::D24) => DepthStorage::Unorm24,
        (DepthStorage::Unknown, DepthFormat::D32F) => DepthStorage::Float32,
        (s, _) => s,
    })
}

// ANCHOR: quantise
/// The value a buffer of storage `s` keeps for window depth `z`, as an
/// ordered integer.
pub fn quantise(s: DepthStorage, z: f32) -> u32 {
    let z = z.clamp(0.0, 1.0);
    match s {
        // 24-bit unorm: round(z · (2²⁴ − 1)); one step is 6e-8 everywhere.
        DepthStorage::Unorm24 => (z as f64 * 16_777_215.0).round() as u32,
        // f32: the bits order like the values (z ≥ 0); steps shrink near 0.
        DepthStorage::Float32 | DepthStorage::Unknown => z.to_bits(),
    }
}
// ANCHOR_END: quantise

// ANCHOR: window_depth
/// Window depth of view distance `d` (> 0), in f32 like the GPU: the vertex
/// shader's clip z and w, then the divide.
pub fn window_depth_f32(rows: [f64; 4], d: f32) -> f32 {
    let [zz, tz, zw, tw] = rows.map(|r| r as f32);
    let (z, w) = (zz * -d + tz, zw * -d + tw);
    z / w
}
// ANCHOR_END: window_depth

/// Samples per (distance, gap) cell, and the share that must resolve.
pub const SAMPLES: usize = 32;
pub const QUANTILE: f64 = 0.95;

/// Sample `j` of the cell at distance `d`: spread evenly over d·[0.95, 1.05).
pub fn jittered(d: f64, j: usize) -> f64 {
    d * (1.0 + 0.1 * ((j as f64 + 0.5) / SAMPLES as f64 - 0.5))
}

// ANCHOR: analytic_gap
/// The analytic curve: the smallest Δd/d that one storage step can hold
/// at distance d, step(z) / (|dz/dd| · d). The step is 1/(2²⁴ − 1) for
/// 24-bit unorm and the f32 spacing at z for float. It leaves out the f32
/// rounding of the clip maths, which the measurement includes.
pub fn analytic_gap(m: DepthMapping, s: DepthStorage, near: f64, far: f64, d: f64) -> f64 {
    let [zz, tz, _, _] = m.rows(near, far);
    // z(d) = (zz·(−d) + tz)/d = −zz + tz/d, so |dz/dd| = |tz|/d².
    let z = -zz + tz / d;
    let step = match s {
        DepthStorage::Unorm24 => 1.0 / 16_777_215.0,
        _ => 2f64.powi((z.max(1e-38) as f32).log2().floor() as i32 - 23),
    };
    step / (tz.abs() / (d * d) * d)
}
// ANCHOR_END: analytic_gap

/// The CPU model: are surfaces at `d` and `d·(1 + gap)` stored in the right
/// order (and not equal), inside [0, 1]? A far surface past the far plane
/// is clipped, so the near one shows.
pub fn resolves_cpu(
    m: DepthMapping,
    s: DepthStorage,
    near: f64,
    far: f64,
    d: f64,
    gap: f64,
) -> bool {
    let rows = m.rows(near, far);
    let (za, zb) = (
        window_depth_f32(rows, d as f32),
        window_depth_f32(rows, (d * (1.0 + gap)) as f32),
    );
    let inside = |z: f32| (0.0..=1.0).contains(&z);
    if !inside(za) {
        return false;
    }
    // Beyond the far plane the far quad is clipped: the near one shows, as
    // on the GPU. (Only the largest gaps at far/2 get there.)
    if !inside(zb) {
        return true;
    }
    let (qa, qb) = (quantise(s, za), quantise(s, zb));
    if m.reversed() {
        qa > qb
    } else {
        qa < qb
    }
}

/// The relative gaps probed: 10⁻⁸ … 1, four per decade.
pub fn gaps() -> Vec<f64> {
    (0..=32)
        .map(|i| 10f64.powf(-8.0 + i as f64 / 4.0))
        .collect()
}

/// The distances probed for a near/far pair: log-spaced from 10·near, and
/// the two named ones last: √(near·far) and far/2.
pub fn distances(near: f64, far: f64) -> Vec<f64> {
    let (a, b) = ((10.0 * near).ln(), (0.5 * far).ln());
    let mut d: Vec<f64> = (0..12)
        .map(|i| (a + (b - a) * i as f64 / 11.0).exp())
        .collect();
    d.push((near * far).sqrt());
    d.push(0.5 * far);
    d
}

/// The smallest gap from which every larger gap of the grid resolves in
/// at least [`QUANTILE`] of its samples (`row`: the share resolved per gap).
pub fn min_resolvable_gap(row: &[f64], gaps: &[f64]) -> Option<f64> {
    let mut best = None;
    for i in (0..row.len()).rev() {
        if row[i] < QUANTILE {
            break;
        }
        best = Some(gaps[i]);
    }
    best
}

/// The probe quads (`shaders/lesson_07/depth_probe.wgsl`).
const PROBE_WGSL: &str = include_str!("../../shaders/lesson_07/depth_probe.wgsl");

// ANCHOR: probe_quads
/// The probe's quads, one pixel each: column `c` is the gap `gaps[c]`,
/// row `r` the `r`-th jittered distance d ([`SAMPLES`] per distance).
/// All the far quads at d·(1 + gap) first (value 0), then the near ones
/// at d (value 1).
fn probe_quads(dists: &[f64], gaps: &[f64]) -> Vec<[f32; 4]> {
    let mut inst = Vec::new();
    for (value, far_side) in [(0.0, true), (1.0, false)] {
        for (r, d) in dists
            .iter()
            .flat_map(|&d| (0..SAMPLES).map(move |j| jittered(d, j)))
            .enumerate()
        {
            for (c, &g) in gaps.iter().enumerate() {
                let dist = if far_side { d * (1.0 + g) } else { d };
                inst.push([c as f32, r as f32, dist as f32, value]);
            }
        }
    }
    inst
}
// ANCHOR_END: probe_quads

/// The probe's shader, and its uniform (`rows`, the image size `size`)
/// bound at group 0.
fn probe_program(
    gpu: &Gpu,
    rows: [f32; 4],
    (w, h): (u32, u32),
) -> (wgpu::ShaderModule, wgpu::BindGroupLayout, wgpu::BindGroup) {
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("depth precision probe"),
        source: wgpu::ShaderSource::Wgsl(PROBE_WGSL.into()),
    });
    let uniform: [f32; 8] = [
        rows[0], rows[1], rows[2], rows[3], w as f32, h as f32, 0.0, 0.0,
    ];
    let ubuf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("probe"),
        contents: bytemuck::cast_slice(&uniform),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let entry = uniform_entry(0, wgpu::ShaderStages::VERTEX, false, None);
    let layout = bindings::layout(gpu, "probe", &[entry]);
    let group = bindings::group(gpu, "probe", &layout, &[ubuf.as_entire_binding()]);
    (module, layout, group)
}

// ANCHOR: measure_gpu
/// The GPU measurement: `result[row][column]` is the share of the
/// [`SAMPLES`] jittered distances d around `distances[row]` where the near
/// quad at d won against the far one at d·(1 + `gaps[column]`).
pub fn measure_gpu(
    gpu: &Gpu,
    format: wgpu::TextureFormat,
    m: DepthMapping,
    near: f64,
    far: f64,
) -> Result<Vec<Vec<f64>>> {
    let (gaps, dists) = (gaps(), distances(near, far));
    // One pixel row per jittered sample: SAMPLES rows per distance.
    let (w, h) = (gaps.len() as u32, (dists.len() * SAMPLES) as u32);
    // The mapping's rows and the image size, for the probe's vertex shader.
    let rows = m.rows(near, far).map(|r| r as f32);
    let (module, layout, group) = probe_program(gpu, rows, (w, h));
    let inst = probe_quads(&dists, &gaps);
    // The far quads first, then the near ones, with the mapping's test.
    let px = depth_probe::draw_probe(
        gpu,
        &depth_probe::ProbeDraw {
            label: "depth precision probe",
            module: &module,
            format,
            compare: m.compare(),
            clear: m.clear_depth(),
            size: (w, h),
            instances: &inst,
            group: Some((&layout, &group)),
        },
    )?;
    Ok(near_won(&px, w as usize))
}
// ANCHOR_END: measure_gpu

// ANCHOR: near_won
/// Per distance and gap, the share of its [`SAMPLES`] pixel rows where the
/// near quad (255) won: `px` is the probe's image, `w` pixels wide.
fn near_won(px: &[u8], w: usize) -> Vec<Vec<f64>> {
    px.chunks(w * SAMPLES)
        .map(|cell| {
            (0..w)
                .map(|c| {
                    let won = (0..SAMPLES).filter(|&j| cell[j * w + c] > 127).count();
                    won as f64 / SAMPLES as f64
                })
                .collect()
        })
        .collect()
}
// ANCHOR_END: near_won

/// The CPU model over the same grid and samples as [`measure_gpu`].
pub fn model_cpu(s: DepthStorage, m: DepthMapping, near: f64, far: f64) -> Vec<Vec<f64>> {
    let g = gaps();
    distances(near, far)
        .iter()
        .map(|&d| {
            g.iter()
                .map(|&gap| {
                    let ok = (0..SAMPLES)
                        .filter(|&j| resolves_cpu(m, s, near, far, jittered(d, j), gap))
                        .count();
                    ok as f64 / SAMPLES as f64
                })
                .collect()
        })
        .collect()
}

/// One configuration of the study: the smallest resolvable relative gap at
/// every probed distance, measured on the GPU (`None` where the format is
/// missing), modelled on the CPU, and the analytic curve. `None` inside
/// means "no gap up to 1".
#[derive(Clone, Debug)]
pub struct PrecisionRow {
    pub format: DepthFormat,
    /// What the format stores here ([`storage_of`]): the model's and the curve's.
    pub storage: DepthStorage,
    pub mapping: DepthMapping,
    pub near: f64,
    pub far: f64,
    pub distances: Vec<f64>,
    pub gpu: Option<Vec<Option<f64>>>,
    pub cpu: Vec<Option<f64>>,
    pub analytic: Vec<f64>,
    /// The GPU's share resolved (rows = distances, columns = gaps).
    pub grid: Option<Vec<Vec<f64>>>,
}

impl PrecisionRow {
    /// The GPU figure when measured, else the CPU model's, at distance index `i`.
    pub fn best(&self, i: usize) -> Option<f64> {
        match &self.gpu {
            Some(g) => g[i],
            None => self.cpu[i],
        }
    }
}

/// Measures one configuration (GPU when the adapter has the format),
/// modelled as storage `s`.
pub fn study_one(
    gpu: &Gpu,
    (f, s): (DepthFormat, DepthStorage),
    m: DepthMapping,
    near: f64,
    far: f64,
) -> Result<PrecisionRow> {
    let g = gaps();
    let has = f == DepthFormat::D24 || gpu.has(wgpu::Features::DEPTH32FLOAT_STENCIL8);
    let grid = if has {
        Some(measure_gpu(gpu, f.wgpu(), m, near, far)?)
    } else {
        None
    };
    let gpu_gaps = grid
        .as_ref()
        .map(|gr| gr.iter().map(|r| min_resolvable_gap(r, &g)).collect());
    let cpu = model_cpu(s, m, near, far)
        .iter()
        .map(|r| min_resolvable_gap(r, &g))
        .collect();
    Ok(PrecisionRow {
        format: f,
        storage: s,
        mapping: m,
        near,
        far,
        analytic: distances(near, far)
            .iter()
            .map(|&d| analytic_gap(m, s, near, far, d))
            .collect(),
        distances: distances(near, far),
        gpu: gpu_gaps,
        cpu,
        grid,
    })
}

// ANCHOR: study
/// The whole study: both formats, four mappings, far/near = 1e2 … 1e8:
/// each cell measured on the GPU, modelled on the CPU and bounded
/// analytically (`study_one`).
pub fn study(gpu: &Gpu, near: f64, ratios: &[f64]) -> Result<Vec<PrecisionRow>> {
    let mut rows = Vec::new();
    let formats = FORMATS.iter().map(|&f| Ok((f, storage_of(gpu, f)?)));
    let formats = formats.collect::<Result<Vec<_>>>()?;
    for &ratio in ratios {
        for &fs in &formats {
            for m in MAPPINGS {
                rows.push(study_one(gpu, fs, m, near, near * ratio)?);
            }
        }
    }
    Ok(rows)
}
// ANCHOR_END: study

#[cfg(test)]
#[path = "unit_tests/precision_study.rs"]
mod tests;
