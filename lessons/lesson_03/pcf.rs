//! Percentage-closer filtering (lesson 03): the filters that turn the
//! shadow map into a fractional visibility, their parameters as the shader
//! reads them (`shaders/lesson_03/pcf.wgsl`), and the map's bindings with
//! the extra plain-float view that depth averaging reads.

use common::gpu::bindings::{self, float_texture_entry};
use common::gpu::Gpu;

use crate::lesson_01::shadow_map::{comparison_sampler, shadow_map_entries, ShadowMap};
use crate::lesson_02::bias::ShadowBias;

// ANCHOR: filter
/// How a variant turns the shadow map into a visibility.
#[derive(Clone, Copy, Debug)]
pub enum Filter {
    /// N×N nearest comparisons, averaged. `receiver_plane`: each tap
    /// compares with the receiver's plane there (receiver-plane depth bias).
    Grid { n: u32, receiver_plane: bool },
    /// One comparison through a linear-filtering comparison sampler: the
    /// hardware compares the 4 nearest texels and blends the answers.
    Hardware2x2,
    /// `taps` bilinear comparisons on a Poisson disk of `radius` texels,
    /// rotated per pixel.
    Poisson { taps: u32, radius: f32 },
    /// Average N×N stored depths, then compare once: filtering depth.
    DepthAverage { n: u32 },
    /// Adaptive: 4 bilinear probes on the disk's rim decide lit or umbra;
    /// only where they disagree, the full `taps` Poisson disk.
    AdaptivePoisson { taps: u32, radius: f32 },
    /// Castaño's 5×5 Gaussian from 9 bilinear comparisons (The Witness),
    /// as Bevy's default (`ShadowFilteringMethod::Gaussian`) runs it,
    /// ported from bevy_pbr/src/render/shadow_sampling.wgsl
    /// `sample_shadow_map_castano_thirteen`: `castano_5x5` on the lesson's
    /// bias, `bevy` with Bevy's.
    Castano13,
    // ... then the two exercises' filters (the chapter's end).
    // ANCHOR_END: filter
    /// Exercise 1 (`exercise_pcf_kernel` in `exercises.wgsl`): the
    /// student's smooth N×N grid with the receiver plane, radius N / 2:
    /// (N + 1)² comparisons at texel centres, bilinearly weighted.
    ExerciseGrid { n: u32 },
    /// Exercise 2 (`exercise_world_disk`): the student's 16 bilinear taps
    /// on a disk of `radius_m` metres (world units), rotated per pixel.
    ExerciseDisk { radius_m: f32 },
}

impl Filter {
    /// Depth comparisons per pixel and light, and texels they read.
    pub fn taps(self) -> (u64, u64) {
        match self {
            Filter::Grid { n, .. } => ((n * n) as u64, (n * n) as u64),
            Filter::Hardware2x2 => (1, 4),
            Filter::Poisson { taps, .. } => (taps as u64, 4 * taps as u64),
            Filter::DepthAverage { n } => (1, (n * n) as u64),
            // What the exercise asks for (the starter takes one tap).
            Filter::ExerciseGrid { n } => (((n + 1) * (n + 1)) as u64, ((n + 1) * (n + 1)) as u64),
            Filter::ExerciseDisk { .. } => (16, 64),
            Filter::Castano13 => (9, 36),
            // At most: 4 probes, then the full disk.
            Filter::AdaptivePoisson { taps, .. } => (4 + taps as u64, 4 * (4 + taps as u64)),
        }
    }

    /// The shader's `N` and `RECEIVER_PLANE`: the grid's (and the depth
    /// average's) side, and whether each tap compares with the receiver's
    /// plane there, compiled into the lit pipeline with its `MODE`.
    pub fn grid_constants(self) -> (u32, bool) {
        match self {
            Filter::Grid { n, receiver_plane } => (n, receiver_plane),
            Filter::DepthAverage { n } => (n, false),
            Filter::ExerciseGrid { n } => (n, true),
            Filter::Poisson { .. }
            | Filter::AdaptivePoisson { .. }
            | Filter::ExerciseDisk { .. } => (1, true),
            Filter::Hardware2x2 | Filter::Castano13 => (1, false),
        }
    }

    /// The shader's `MODE`: which filter the lit pipeline is compiled with.
    pub fn mode(self) -> u32 {
        match self {
            Filter::Grid { .. } => 0,
            Filter::Hardware2x2 => 1,
            Filter::Poisson { .. } => 2,
            Filter::DepthAverage { .. } => 3,
            Filter::ExerciseGrid { .. } => 4,
            Filter::ExerciseDisk { .. } => 5,
            Filter::Castano13 => 6,
            Filter::AdaptivePoisson { .. } => 7,
        }
    }

    /// Every `MODE` value, one lit pipeline each.
    pub const MODES: u32 = 8;

    /// Linear filtering for the taps that blend 2×2 texels.
    pub fn sampler(self) -> wgpu::FilterMode {
        match self {
            Filter::Hardware2x2
            | Filter::Poisson { .. }
            | Filter::ExerciseDisk { .. }
            | Filter::Castano13
            | Filter::AdaptivePoisson { .. } => wgpu::FilterMode::Linear,
            _ => wgpu::FilterMode::Nearest,
        }
    }
}

/// LearnOpenGL's 3×3 (`learnopengl_pcf`): nearest taps one texel apart,
/// all compared with the centre's depth (no receiver plane).
pub const LEARNOPENGL_3X3: Filter = Filter::Grid {
    n: 3,
    receiver_plane: false,
};
/// The wgpu example's comparison sampler, linear (`wgpu_example_hw2x2`).
pub const WGPU_EXAMPLE_HW2X2: Filter = Filter::Hardware2x2;
/// Bevy's default, `ShadowFilteringMethod::Gaussian` (`bevy`).
pub const BEVY_GAUSSIAN: Filter = Filter::Castano13;

/// `Filter` in `pcf.wgsl`: the filter, and the receiver-side bias of a
/// renderer's defaults (lesson 02's [`ShadowBias`]: LearnOpenGL's depth,
/// Bevy's offsets; zero for the lesson's own filters).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FilterUniform {
    /// Where the grid's N, the receiver-plane switch and the disk's taps
    /// were: the lit pipeline's constants now ([`Filter::grid_constants`]).
    _pad_abc: [u32; 3],
    radius: f32,
    depth: f32,
    depth_slope: f32,
    toward_light_world: f32,
    normal_flat: f32,
    /// Texels along the normal × (1 − cos θ) (Godot's normal bias).
    normal: f32,
    /// Texels along the normal × sin θ (Filament's normal bias).
    normal_sin: f32,
    _pad: [f32; 2],
}

impl FilterUniform {
    /// `filter` after the receiver-side bias `b` (its `depth`,
    /// `depth_slope`, `toward_light_world` and `normal_flat`).
    pub fn new(filter: Filter, b: ShadowBias) -> Self {
        FilterUniform {
            depth: b.depth,
            depth_slope: b.depth_slope,
            toward_light_world: b.toward_light_world,
            normal_flat: b.normal_flat,
            normal: b.normal,
            ..FilterUniform::from(filter)
        }
    }

    /// The same with `texels × sin θ` along the normal too (Filament's
    /// normal bias, which lesson 02's `ShadowBias` has no field for).
    pub fn with_normal_sin(self, texels: f32) -> Self {
        FilterUniform {
            normal_sin: texels,
            ..self
        }
    }
}

impl From<Filter> for FilterUniform {
    fn from(f: Filter) -> Self {
        let u = FilterUniform {
            _pad_abc: [0; 3],
            radius: 0.0,
            depth: 0.0,
            depth_slope: 0.0,
            toward_light_world: 0.0,
            normal_flat: 0.0,
            normal: 0.0,
            normal_sin: 0.0,
            _pad: [0.0; 2],
        };
        match f {
            Filter::Poisson { radius, .. } | Filter::AdaptivePoisson { radius, .. } => {
                FilterUniform { radius, ..u }
            }
            // The shader's `radius` carries metres here.
            Filter::ExerciseDisk { radius_m } => FilterUniform {
                radius: radius_m,
                ..u
            },
            _ => u,
        }
    }
}

/// The shadow map's bindings (lesson 01's group 2) plus binding 2: the
/// same texture read as plain floats, for depth averaging (GLSL cannot
/// `textureLoad` through a depth binding).
pub fn pcf_map_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    let mut entries = shadow_map_entries();
    entries.push(float_texture_entry(2));
    bindings::layout(gpu, "pcf shadow map", &entries)
}

/// The bind group of [`pcf_map_layout`] for `map`, sampled with `filter`.
pub fn pcf_map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &ShadowMap,
    filter: wgpu::FilterMode,
) -> wgpu::BindGroup {
    let sampler = comparison_sampler(gpu, filter);
    let view = wgpu::BindingResource::TextureView(&map.view);
    let resources = [view.clone(), wgpu::BindingResource::Sampler(&sampler), view];
    bindings::group(gpu, "pcf shadow map", layout, &resources)
}
