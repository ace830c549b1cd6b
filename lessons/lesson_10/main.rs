//! # Lesson 10: soft shadows from area lights
//!
//! A light with a size (`radius` on a spot, `angular_radius_deg` on a
//! directional light) lights a point by the fraction of its emitter the
//! point sees; the exact reference casts rays to the emitter
//! (`common::reference::area`). Each variant estimates that fraction from
//! one shadow map: lesson 03's hard-edged PCF, fixed wide PCF disks,
//! percentage-closer soft shadows (PCSS: blocker search, penumbra width,
//! PCF of that width), variance maps plain, with a light-bleeding cut and
//! exponential; then the soft defaults of renderers people use, each
//! citing what it copies.
//!
//! The techniques are in [`soft`] and `shaders/lesson_10/soft.wgsl`, the
//! renderers' ports in [`peers`] and `peers.wgsl`, the variance map's
//! passes in [`moments`], the maps of each size in [`map_sets`], the knobs
//! in [`knobs`](workbook::lesson_10::knobs). What the runner measures and
//! shows besides the image (taps, texels read, draw calls, the knobs, the
//! shadow map) is in `harness.rs`.
//!
//! Run: `cargo run --release --bin lesson_10 -- --headless`
//! Book: chapter "10 Soft shadows" (`book/src/lesson_10.md`).

use std::collections::HashMap;

use clap::ValueEnum;
use common::gpu::bindings::{self, storage_entry};
use common::gpu::lit::LitPass;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::run::lesson::{Capabilities, Lesson};
use common::run::per_variant::PerVariant;
use common::scene::Scene;
use common::Result;
use workbook::lesson_01::shadow_map;
use workbook::lesson_10::exercise_shaders::Module;
use workbook::lesson_10::map_sets::{self, MapSet, MapSets};
use workbook::lesson_10::moments::MomentsPasses;
use workbook::lesson_10::peers::{self, Peer};
use workbook::lesson_10::soft::{LightGeometry, Pcss, SoftUniform, Technique, Variance};
use workbook::lesson_10::split::{lit_keys, LitKey};

mod harness;

// ANCHOR: variants
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    /// Lesson 03's rotated 16-tap Poisson disk (2.5 texels): the hard
    /// shadow's edge, filtered; no light size.
    #[value(name = "hard_pcf")]
    HardPcf,
    /// 16 bilinear taps on a fixed disk (8 texels): PCSS's filter taps,
    /// one width everywhere.
    #[value(name = "pcf_wide_16")]
    PcfWide16,
    /// 32 taps on the same disk: as many as PCSS's search and filter.
    #[value(name = "pcf_wide_32")]
    PcfWide32,
    /// Percentage-closer soft shadows (Fernando 2005): 16 search taps, the
    /// penumbra from the light's geometry, 16 filter taps, each compared
    /// with the receiver's plane.
    #[value(name = "pcss")]
    Pcss,
    /// The same PCSS with an adaptive filter: 4 probes on the filter
    /// disk's rim decide lit or umbra, the 16 taps only where they disagree.
    #[value(name = "pcss_adaptive")]
    PcssAdaptive,
    /// The same PCSS, asking the map's min/max mip chain first (Dmitriev
    /// and Uralsky 2007): where it proves a pixel lit or in umbra, PCSS's
    /// own answer without a tap; the taps only where it cannot.
    #[value(name = "pcss_min_max")]
    PcssMinMax,
    /// A variance map (Donnelly and Lauritzen 2006), blurred 9×9 texels.
    #[value(name = "vsm")]
    Vsm,
    /// The same with Lauritzen's light-bleeding cut, linstep(0.3, 1, p_max).
    #[value(name = "vsm_bleed_cut")]
    VsmBleedCut,
    /// Exponential variance map (Lauritzen and McCool 2008): the moments
    /// of exp(40 (2z − 1)) and of −exp(−5 (2z − 1)), z the linear depth,
    /// blurred 9×9, the lower bound of the two (EVSM4).
    #[value(name = "evsm")]
    Evsm,
    // Then the renderers' ports (peers.rs) and the chapter's exercises.
    // ANCHOR_END: variants
    /// Filament's default, `ShadowType::PCF` (`ShadowSample_PCF_Low`):
    /// Castaño's 3×3 from 4 bilinear comparisons, on its 1024² map of
    /// front faces with its polygon offset and 1 mm constant bias. Card:
    /// `port_cards.rs`.
    #[value(name = "filament_pcf")]
    FilamentPcf,
    /// Filament's PCSS, an option (`ShadowType::PCSS`,
    /// shaders/src/surface_shadowing.fs): the first 16 of its 64 Poisson
    /// points (all in one half of the disk) to search and to filter,
    /// turned per pixel; the blockers' mean reversed depth; its penumbra
    /// ratio; its bulb radius (the spot's radius, or its default 2 cm on a
    /// sun). Card: `port_cards.rs`.
    #[value(name = "filament_pcss")]
    FilamentPcss,
    /// Filament's VSM, an option (`ShadowType::VSM`): an EVSM (exponent
    /// 5.54 for its 16-bit moments, no blur, `lightBleedReduction` 0.15,
    /// least variance from `minVarianceScale` 0.5 and the exponent) of a
    /// map drawn without offsets. Card: `port_cards.rs`.
    #[value(name = "filament_evsm")]
    FilamentEvsm,
    /// Bevy's default filter, `ShadowFilteringMethod::Gaussian` (Castaño's
    /// 5×5, lesson 03's `bevy`) with its receiver offsets, on its 2048²
    /// map of front faces, spot and sun alike. Card: `port_cards.rs`.
    #[value(name = "bevy_gaussian")]
    BevyGaussian,
    /// Bevy's PCSS, an option (the `experimental_pbr_pcss` feature and
    /// `soft_shadows_enabled` on a spot): 8 D3D points to search in its
    /// reversed infinite depth, 8 spiral taps to filter, widths in its own
    /// texel units, on its 2048² map. On a sun, whose `soft_shadow_size` is
    /// not ported, Bevy's default (as `bevy_gaussian`). Card:
    /// `port_cards.rs`.
    #[value(name = "bevy_pcss_or_pcf")]
    BevyPcssOrPcf,
    /// Godot's default (a light size of 0): its PCF at Soft Low, 4 Vogel
    /// taps of bilinear comparisons on a disk of 2 texels. Card:
    /// `port_cards.rs`.
    #[value(name = "godot_pcf")]
    GodotPcf,
    /// Godot's soft shadow, an option (a light size above 0), at its
    /// default quality, Soft Low: 8 Vogel taps to search and the same 8
    /// to filter, its penumbra `(b − z) / (1 − b)` on reversed depth, no
    /// receiver-plane bias. Card: `port_cards.rs`.
    #[value(name = "godot_soft_low")]
    GodotSoftLow,
    /// three.js's default, `PCFShadowMap` (r182): 5 Vogel taps of bilinear
    /// comparisons on a disk of one texel, on its 512² map of back faces.
    /// Card: `port_cards.rs`.
    #[value(name = "threejs_pcf")]
    ThreejsPcf,
    /// three.js's `PCFSoftShadowMap`, an option until r182 deprecated it:
    /// a fixed 3×3-texel box, bilinearly smoothed, on its 512² map of back
    /// faces; it has no light size. Card: `port_cards.rs`.
    #[value(name = "threejs_pcf_soft")]
    ThreejsPcfSoft,
    /// three.js's `VSMShadowMap`, an option: the (mean, deviation) of its
    /// map's depth (front faces, no offsets), 8 samples over ±1 texel
    /// along y then x, on its 512² map, cut by linstep(0.3, 0.95, p).
    /// Card: `port_cards.rs`.
    #[value(name = "threejs_vsm")]
    ThreejsVsm,
    /// The chapter's exercises (`exercises.wgsl`), run only when named.
    #[value(name = "exercise_off_axis_radius")]
    ExerciseOffAxisRadius,
    #[value(name = "exercise_elliptic_footprint")]
    ExerciseEllipticFootprint,
}

// ANCHOR: techniques
impl Variant {
    /// The variant's technique, for a light of geometry `g`.
    fn technique(self, g: &LightGeometry) -> Technique {
        let disk = |taps| Technique::FixedDisk {
            taps,
            radius_texels: 8.0,
        };
        let ours = Technique::PCSS;
        let variance = |blur, exponent: Option<f32>, min_variance, bleed| {
            Technique::Variance(Variance {
                blur,
                exponent,
                negative: None,
                min_variance,
                bleed,
            })
        };
        match self {
            Variant::HardPcf => Technique::HardPcf,
            Variant::PcfWide16 => disk(16),
            Variant::PcfWide32 => disk(32),
            Variant::Pcss => Technique::Pcss(ours),
            Variant::PcssAdaptive => Technique::Pcss(Pcss {
                adaptive: true,
                ..ours
            }),
            Variant::PcssMinMax => Technique::Pcss(Pcss {
                min_max: true,
                leave_out_flat: true,
                ..ours
            }),
            Variant::Vsm => variance(4, None, 1e-6, (0.0, 1.0)),
            Variant::VsmBleedCut => variance(4, None, 1e-6, (0.3, 1.0)),
            Variant::Evsm => Technique::Variance(Variance {
                blur: 4,
                exponent: Some(40.0),
                negative: Some(5.0),
                min_variance: 1e-4,
                bleed: (0.0, 1.0),
            }),
            // The renderers' ports and the chapter's exercises (below).
            _ => self.port_or_exercise(g),
        }
    }
}
// ANCHOR_END: techniques

impl Variant {
    /// A renderer's port ([`peers::port`]), or an exercise: our PCSS, whose
    /// shader module holds the student's function ([`Variant::module`]).
    fn port_or_exercise(self, g: &LightGeometry) -> Technique {
        match self.module() {
            Module::Lesson => Technique::Peer(self.peer(g)),
            Module::OffAxisRadius | Module::Footprint => Technique::Pcss(Technique::PCSS),
        }
    }

    /// The shader module its lit pass is from (`exercise_shaders.rs`).
    fn module(self) -> Module {
        match self {
            Variant::ExerciseOffAxisRadius => Module::OffAxisRadius,
            Variant::ExerciseEllipticFootprint => Module::Footprint,
            _ => Module::Lesson,
        }
    }

    /// A renderer's port, for a light of geometry `g` (`peers.rs`).
    fn peer(self, g: &LightGeometry) -> Peer {
        let name = self.to_possible_value().expect("a named variant");
        peers::port(name.get_name(), g).expect("a port has a card and a peer")
    }

    /// The lesson's own techniques have knobs; the renderers' defaults and
    /// the exercises keep theirs.
    fn has_knobs(self) -> bool {
        matches!(
            self,
            Variant::PcfWide16
                | Variant::PcfWide32
                | Variant::Pcss
                | Variant::PcssAdaptive
                | Variant::PcssMinMax
                | Variant::Vsm
                | Variant::VsmBleedCut
                | Variant::Evsm
        )
    }
}

/// One variant's state for one light: its technique, its map, its
/// parameters' group, and the variance map's passes if it has one.
struct PerLight {
    technique: Technique,
    /// Index into `Soft::maps`: the map of the technique's size.
    map: usize,
    group: wgpu::BindGroup,
    moments: Option<MomentsPasses>,
}

struct Soft {
    maps: MapSets,
    geometry: Vec<LightGeometry>,
    map_layout: wgpu::BindGroupLayout,
    params_layout: wgpu::BindGroupLayout,
    /// The lesson's module, then each exercise's.
    modules: [wgpu::ShaderModule; 3],
    /// fs_soft of a module, compiled with a variant's constants and a
    /// stencil role: built the first time a variant runs.
    lit_pipelines: HashMap<LitKey, wgpu::RenderPipeline>,
    /// Each variant's state, per light: `per_light[variant][light]`.
    per_light: PerVariant<Variant, Vec<PerLight>>,
    /// The scene's objects: the base pass draws each, and each lit draw.
    objects: u64,
}

impl Soft {
    /// Variant `v`'s state for light `k`, running technique `t`.
    fn per_light(&self, gpu: &Gpu, v: Variant, k: usize, t: Technique) -> PerLight {
        let g = &self.geometry[k];
        let u = SoftUniform::new(t, g);
        let soft = bindings::params_buffer(gpu, "soft", bytemuck::bytes_of(&u));
        // Lesson 03's Poisson disk (the hard baseline's filter), with a
        // renderer's receiver offsets (its peer_receiver) for a port.
        let f = t.filter_uniform();
        let filter = bindings::params_buffer(gpu, "lesson 03 filter", bytemuck::bytes_of(&f));
        let resources = [filter.as_entire_binding(), soft.as_entire_binding()];
        let name = format!("{v:?} light {k}");
        let map = self.maps.index(t.map_size(), t.map_pass());
        let set = self.maps.at(map);
        PerLight {
            technique: t,
            map,
            group: bindings::group(gpu, &name, &self.params_layout, &resources),
            moments: t
                .variance()
                .map(|(var, three)| set.moments.passes(gpu, &set.map, &var, three, g)),
        }
    }

    /// The variant's lit pipelines for every light, built if not yet.
    fn build_lit_pipelines(&mut self, gpu: &Gpu, scene: &SceneGpu, variant: Variant) {
        let module = variant.module();
        for state in &self.per_light[variant] {
            let (first, then) = lit_keys(module, state.technique);
            for key in std::iter::once(first).chain(then) {
                self.lit_pipelines.entry(key).or_insert_with(|| {
                    scene.lit_pipeline_with_depth(
                        gpu,
                        &self.modules[module as usize],
                        "fs_soft",
                        &[&self.map_layout, &self.params_layout],
                        scene.lit_depth_state(key.2.state()),
                        &key.1.pairs(),
                    )
                });
            }
        }
    }

    /// The map the variant's first light reads.
    fn first_map(&self, variant: Variant) -> &MapSet {
        let k = self.per_light[variant].first().map_or(0, |p| p.map);
        self.maps.at(k)
    }
}

impl Lesson for Soft {
    const NAME: &'static str = "lesson_10";
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_10.toml");
    type Variant = Variant;
    const CAPABILITIES: Capabilities = Capabilities {
        area_lights: true,
        ..Capabilities::BASIC
    };

    fn check_scene(scene: &Scene) -> Result<()> {
        shadow_map::refuse_point_lights(scene, Self::NAME)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        // The lesson's module, then each exercise's (without the lesson's
        // function it asks for).
        let [module, radius, footprint] = Module::ALL.map(|m| m.compile(gpu));
        let modules = [module?, radius?, footprint?];
        let map_layout = map_sets::map_layout(gpu);
        let stage = wgpu::ShaderStages::FRAGMENT;
        let params_layout = bindings::layout(
            gpu,
            "soft params",
            &[
                storage_entry(0, stage, false, None),
                storage_entry(1, stage, false, None),
            ],
        );
        let geometry = (0..scene.scene.lights.len())
            .map(|k| {
                LightGeometry::new(&scene.scene, k)
                    .ok_or_else(|| anyhow::anyhow!("light {k}: lesson_10 has no point lights"))
            })
            .collect::<Result<Vec<_>>>()?;
        // One map of each size and pass some variant runs on some light.
        let keys = (Variant::value_variants().iter()).flat_map(|v| {
            geometry.iter().map(|g| {
                let t = v.technique(g);
                (t.map_size(), t.map_pass())
            })
        });
        let maps = MapSets::new(keys, |size, pass| {
            MapSet::new(gpu, scene, &modules[0], &map_layout, size, pass)
        });
        let mut soft = Soft {
            maps,
            geometry,
            map_layout,
            params_layout,
            modules,
            lit_pipelines: HashMap::new(),
            per_light: PerVariant::new(|_| Vec::new()),
            objects: scene.scene.objects.len() as u64,
        };
        soft.per_light = PerVariant::new(|v: Variant| {
            (0..soft.geometry.len())
                .map(|k| soft.per_light(gpu, v, k, v.technique(&soft.geometry[k])))
                .collect()
        });
        Ok(soft)
    }

    // ANCHOR: render
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        self.build_lit_pipelines(frame.gpu, scene, variant);
        // The runner's sub-texel move of the map (`--fragile`), drawn and read.
        shadow_map::jitter_light_maps(frame.gpu, scene, self.first_map(variant).size);
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for light in 0..scene.scene.lights.len() {
            let state = &self.per_light[variant][light];
            let set = self.maps.at(state.map);
            frame.pass("shadow", |enc, ts| {
                set.shadow_pass(enc, scene, light, ts.render())
            });
            let (first, then) = lit_keys(variant.module(), state.technique);
            if first.1.min_max || state.moments.is_some() {
                frame.render_output_ready_for_compute();
            }
            if first.1.min_max {
                frame.pass("min_max", |enc, ts| set.min_max.record(enc, ts.compute()));
            }
            if let Some(passes) = &state.moments {
                frame.pass("moments", |enc, ts| {
                    set.moments.record(enc, passes, false, ts.compute())
                });
                frame.pass("blur", |enc, ts| {
                    set.moments.record(enc, passes, true, ts.compute())
                });
            }
            let map_group = set.group(state.technique.sampler());
            frame.pass("lighting", |enc, ts| {
                let groups = [map_group, &state.group];
                let pipeline = &self.lit_pipelines[&first];
                let mut pass = LitPass::new(light, pipeline, &groups);
                if let Some(then) = then {
                    pass = pass.then(&self.lit_pipelines[&then], light as u32 + 1);
                }
                scene.lit_pass(enc, targets, pass, ts.render())
            });
        }
        Ok(())
    }
    // ANCHOR_END: render
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<Soft>()
}
