//! Soft shadows from one shadow map (lesson 10): how a variant turns the
//! map into the visible fraction of an area light, the light's geometry as
//! the shader needs it, and the parameters as `shaders/lesson_10/soft.wgsl`
//! reads them.

pub use super::light_geometry::LightGeometry;
use super::map_sets::MapPass;
pub use super::moments::Variance;
use super::peers::{Peer, PeerParams};
use crate::lesson_02::bias::ShadowBias;
use crate::lesson_03::pcf::{Filter, FilterUniform};

// ANCHOR: technique
/// How a variant turns the shadow map into a visibility.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Technique {
    /// Lesson 03's rotated 16-tap Poisson disk of 2.5 texels: a hard
    /// shadow's edge, filtered.
    HardPcf,
    /// `taps` bilinear comparisons on a disk of a fixed `radius_texels`.
    FixedDisk { taps: u32, radius_texels: f32 },
    /// Percentage-closer soft shadows: a blocker search, the penumbra's
    /// width from the blockers' distance, a PCF that wide.
    Pcss(Pcss),
    /// A variance map blurred over `(2 blur + 1)²` texels.
    Variance(Variance),
    /// A renderer's soft-shadow default, as its source runs it
    /// ([`super::peers`]).
    Peer(Peer),
}

/// A PCSS's choices: its taps, where it searches, its least width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pcss {
    pub search_taps: u32,
    pub filter_taps: u32,
    pub receiver_plane: bool,
    pub search: Search,
    /// The least filter radius, texels.
    pub min_filter_texels: f32,
    /// Step 3 probes the filter disk's rim first (4 taps): where they
    /// agree, the pixel is lit or in umbra without the full filter.
    pub adaptive: bool,
    /// The map's min/max chain first ([`super::min_max`]): where it shows
    /// the search region all behind the receiver (lit) or it and the
    /// widest filter all in front (umbra), the lit pass answers with no
    /// tap; a second draw takes the taps where it could not tell. Ours
    /// search only (with `LightSizeAtReceiver` the chain is not asked).
    pub min_max: bool,
    /// A map without the flat objects that hide nothing
    /// ([`super::casters`]), where the chain can tell.
    pub leave_out_flat: bool,
    /// With the chain: its answers only, the second draw left out, so
    /// that the pixels it cannot tell stay black (the `chain_only` knob).
    pub chain_only: bool,
}

/// Where the blocker search looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Search {
    /// Every blocker that can hide part of the emitter: the emitter seen
    /// from the receiver, on the plane of the nearest caster (ours).
    NearestCaster,
    /// Only the light's size at the receiver (Filament's and Bevy's choice;
    /// `pcss_search_at_receiver` in `peers.wgsl`).
    LightSizeAtReceiver,
}

// ANCHOR_END: technique

/// Lesson 03's map size: the techniques differ, the map does not (a
/// renderer's port runs its renderer's size).
pub const LESSON_MAP_SIZE: u32 = 1024;

impl Technique {
    /// Our PCSS: 16 search and 16 filter taps, the light's geometry.
    pub const PCSS: Pcss = Pcss {
        search_taps: 16,
        filter_taps: 16,
        receiver_plane: true,
        search: Search::NearestCaster,
        min_filter_texels: 0.0,
        adaptive: false,
        min_max: false,
        leave_out_flat: false,
        chain_only: false,
    };

    /// Depth comparisons per pixel and light (blocker-search taps and
    /// filter taps) and the texels they read: the counters. A PCSS that
    /// finds no blocker stops after its search; these are the most.
    pub fn taps(self) -> (u64, u64, u64) {
        match self {
            Technique::HardPcf => (0, 16, 64),
            Technique::FixedDisk { taps, .. } => (0, taps as u64, 4 * taps as u64),
            // Adaptive: at most 4 probes, then the full filter.
            // The chain: two regions of four blocks, each two depths.
            Technique::Pcss(p) => {
                let filter = p.filter_taps + 4 * p.adaptive as u32;
                (
                    p.search_taps as u64,
                    filter as u64,
                    (p.search_taps + 4 * filter + 16 * p.min_max as u32) as u64,
                )
            }
            // Four texels of the blurred moments; the blur reads its own.
            Technique::Variance(_) => (0, 1, 4),
            Technique::Peer(p) => p.taps(),
        }
    }

    /// The shader's `mode`.
    pub fn mode(self) -> u32 {
        match self {
            Technique::HardPcf => 0,
            Technique::FixedDisk { .. } => 1,
            // With the renderers' search: peers.wgsl's.
            Technique::Pcss(p) if p.search == Search::LightSizeAtReceiver => 4,
            Technique::Pcss(_) => 2,
            Technique::Variance(_) => 3,
            Technique::Peer(p) => p.mode(),
        }
    }

    /// Nearest comparisons (three.js's point taps) or bilinear ones.
    pub fn sampler(self) -> wgpu::FilterMode {
        match self {
            Technique::Peer(p) => p.sampler(),
            _ => wgpu::FilterMode::Linear,
        }
    }

    /// A variance map's moments (and three.js's blur), if the technique
    /// reads one.
    pub fn variance(self) -> Option<(Variance, Option<super::moments::ThreeVsmBlur>)> {
        match self {
            Technique::Variance(v) => Some((v, None)),
            Technique::Peer(p) => p.variance(),
            _ => None,
        }
    }

    /// The shadow map's side, texels: the lesson's, or the renderer's.
    pub fn map_size(self) -> u32 {
        match self {
            Technique::Peer(p) => p.map_size(),
            _ => LESSON_MAP_SIZE,
        }
    }

    /// How its map is drawn: the lesson's pass, or the renderer's.
    pub fn map_pass(self) -> MapPass {
        match self {
            Technique::Peer(p) => p.map_pass(),
            Technique::Pcss(p) if p.leave_out_flat => MapPass::LessonHidingOnly,
            _ => MapPass::Lesson,
        }
    }

    /// The receiver's offsets before the lookup (lesson 03's
    /// `peer_receiver`): none for the lesson's own, the renderer's for a port.
    pub fn receiver_bias(self) -> ShadowBias {
        match self {
            Technique::Peer(p) => p.receiver_bias(),
            _ => ShadowBias::NONE,
        }
    }

    /// Lesson 03's filter uniform for the lit pass: its Poisson disk (the
    /// hard baseline's filter) with the receiver's offsets.
    pub fn filter_uniform(self) -> FilterUniform {
        let poisson = Filter::Poisson {
            taps: 16,
            radius: 2.5,
        };
        let sin = match self {
            Technique::Peer(p) => p.receiver_normal_sin(),
            _ => 0.0,
        };
        FilterUniform::new(poisson, self.receiver_bias()).with_normal_sin(sin)
    }

    /// Whether the receiver moves before its lookup.
    pub fn moves_receiver(self) -> bool {
        let sin = match self {
            Technique::Peer(p) => p.receiver_normal_sin(),
            _ => 0.0,
        };
        self.receiver_bias() != ShadowBias::NONE || sin != 0.0
    }
}

/// What a variant's lit pipeline is built with: `soft.wgsl`'s `override`s
/// (and lesson 03's `RENDERER_BIAS`). The shader never reads a mode, a tap
/// count or a switch of the variant from a buffer: the compiler keeps only
/// the variant's own path and unrolls its loops.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SoftConstants {
    pub mode: u32,
    pub search_taps: u32,
    pub filter_taps: u32,
    pub receiver_plane: bool,
    pub adaptive: bool,
    pub min_max: bool,
    pub exponential: bool,
    pub negative_warp: bool,
    pub renderer_bias: bool,
}

impl SoftConstants {
    pub fn new(t: Technique) -> SoftConstants {
        // A count the variant's path does not read: 1, so that variants
        // that differ only there share a pipeline.
        let mut c = SoftConstants {
            mode: t.mode(),
            search_taps: 1,
            filter_taps: 1,
            receiver_plane: false,
            adaptive: false,
            min_max: false,
            exponential: false,
            negative_warp: false,
            renderer_bias: t.moves_receiver(),
        };
        let mut variance = |v: &Variance| {
            c.exponential = v.exponent.is_some();
            c.negative_warp = v.negative.is_some_and(|n| n > 0.0);
        };
        match t {
            Technique::HardPcf => c.receiver_plane = true,
            Technique::FixedDisk { taps, .. } => {
                c.filter_taps = taps;
                c.receiver_plane = true;
            }
            Technique::Pcss(p) => {
                c.search_taps = p.search_taps;
                c.filter_taps = p.filter_taps;
                c.receiver_plane = p.receiver_plane;
                c.adaptive = p.adaptive;
                c.min_max = p.min_max && p.search == Search::NearestCaster;
            }
            Technique::Variance(v) => variance(&v),
            Technique::Peer(p) => {
                let params = p.params();
                c.search_taps = params.taps.max(1);
                c.filter_taps = params.taps.max(1);
                c.receiver_plane = params.receiver_plane;
                if let Some(v) = &params.variance {
                    variance(v);
                }
            }
        }
        c
    }

    /// The pipeline's constants by name (lesson 03's `MODE` 2: its Poisson
    /// disk, which `HardPcf` calls).
    pub fn pairs(self) -> [(&'static str, f64); 10] {
        [
            ("MODE", 2.0),
            ("SOFT_MODE", self.mode as f64),
            ("SEARCH_TAPS", self.search_taps as f64),
            ("FILTER_TAPS", self.filter_taps as f64),
            ("RECEIVER_PLANE", self.receiver_plane as u32 as f64),
            ("ADAPTIVE", self.adaptive as u32 as f64),
            ("MIN_MAX", self.min_max as u32 as f64),
            ("EXPONENTIAL", self.exponential as u32 as f64),
            ("NEGATIVE_WARP", self.negative_warp as u32 as f64),
            ("RENDERER_BIAS", self.renderer_bias as u32 as f64),
        ]
    }
}

/// `Soft` in `soft.wgsl`: one light's geometry and a variant's continuous
/// parameters (its switches are [`SoftConstants`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SoftUniform {
    pub near: f32,
    pub far: f32,
    pub size: f32,
    pub nearest_caster: f32,
    pub uv_per: [f32; 2],
    pub fixed_radius_texels: f32,
    pub min_filter_texels: f32,
    pub min_variance: f32,
    pub bleed_lo: f32,
    pub bleed_hi: f32,
    pub exponent: f32,
    pub negative: f32,
    pub scale: f32,
    pub perspective: u32,
    pub _pad: u32,
    /// Vogel's disk, [`vogel_table`].
    pub disk: [[f32; 2]; 64],
}

/// The most taps a disk has: the knobs' limit, the table's length.
pub const DISK_POINTS: usize = 64;

/// Vogel's golden-angle spiral for n = 1, unturned: point i at radius
/// sqrt(i + 0.5) and angle i × 2.39996323. `soft.wgsl`'s `vogel` scales it
/// by 1/sqrt(n) and turns it once per pixel.
pub fn vogel_table() -> [[f32; 2]; DISK_POINTS] {
    std::array::from_fn(|i| {
        let (r, t) = ((i as f64 + 0.5).sqrt(), i as f64 * 2.39996323);
        [(r * t.cos()) as f32, (r * t.sin()) as f32]
    })
}

impl SoftUniform {
    pub fn new(t: Technique, g: &LightGeometry) -> SoftUniform {
        let mut u = SoftUniform {
            near: g.near,
            far: g.far,
            size: g.size,
            nearest_caster: g.nearest_caster,
            uv_per: g.uv_per,
            fixed_radius_texels: 0.0,
            min_filter_texels: 0.0,
            min_variance: 0.0,
            bleed_lo: 0.0,
            bleed_hi: 1.0,
            exponent: 0.0,
            negative: 0.0,
            scale: 0.0,
            perspective: g.perspective as u32,
            _pad: 0,
            disk: vogel_table(),
        };
        match t {
            Technique::FixedDisk { radius_texels, .. } => {
                u.fixed_radius_texels = radius_texels;
            }
            Technique::Pcss(p) => u.min_filter_texels = p.min_filter_texels,
            Technique::Variance(v) => u.set_variance(&v),
            Technique::Peer(p) => u.set_peer(p.params()),
            Technique::HardPcf => {}
        }
        u
    }

    /// A renderer's port's parameters.
    pub fn set_peer(&mut self, p: PeerParams) {
        if let Some(size) = p.size {
            self.size = size;
        }
        self.scale = p.scale;
        if let Some(v) = p.variance {
            self.set_variance(&v);
        }
    }

    /// A variance map's parameters.
    pub fn set_variance(&mut self, v: &Variance) {
        self.exponent = v.exponent.unwrap_or(0.0);
        self.negative = v.negative.unwrap_or(0.0);
        self.min_variance = v.min_variance;
        (self.bleed_lo, self.bleed_hi) = v.bleed;
    }
}
