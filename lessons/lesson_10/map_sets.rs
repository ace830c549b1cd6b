//! The shadow maps lesson 10's variants read, one set per map size and
//! shadow pass (the lesson's 1024² with lesson 02's bias; each renderer's
//! port on its renderer's size, drawn as its renderer draws it: three.js
//! 512² of back faces, Bevy's 2048² of front faces): the map, its variance
//! map, its min/max chain, their bindings and the shadow pipelines that
//! render it.

use common::gpu::bindings::{self, float_texture_entry, storage_entry};
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;

use super::casters;
use super::min_max::MinMaxChain;
use super::moments::MomentsMap;
use crate::lesson_01::shadow_map::{
    self, comparison_sampler, shadow_map_entries, ShadowMap, ShadowPassState,
};
use crate::lesson_02::bias::SlopeScaledBias;

/// How a map's shadow pass draws the casters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MapPass {
    /// Both faces with lesson 02's recommended slope-scaled bias: the map
    /// of every variant of the lesson's own.
    Lesson,
    /// The same, without the flat objects that hide nothing
    /// ([`super::casters`]): `pcss_min_max`'s.
    LessonHidingOnly,
    /// A renderer's shadow pass: the faces it culls and its hardware depth
    /// offset (none, for most).
    Renderer {
        cull: Option<wgpu::Face>,
        bias: wgpu::DepthBiasState,
    },
}

/// A shadow map of one size and pass, its variance map, their bindings and
/// the shadow pipelines that render it.
pub struct MapSet {
    pub size: u32,
    pub pass: MapPass,
    pub map: ShadowMap,
    pub moments: MomentsMap,
    pub min_max: MinMaxChain,
    /// Per light, per object: whether the shadow pass draws it (a
    /// caster, and with [`MapPass::LessonHidingOnly`] not a flat object
    /// that hides nothing).
    pub drawn: Vec<Vec<bool>>,
    /// Group 2 with nearest and with linear comparisons.
    pub nearest: wgpu::BindGroup,
    pub linear: wgpu::BindGroup,
    /// One pipeline per light: lesson 02's recommended bias.
    pub shadow_pipelines: Vec<wgpu::RenderPipeline>,
}

impl MapSet {
    pub fn new(
        gpu: &Gpu,
        scene: &SceneGpu,
        module: &wgpu::ShaderModule,
        layout: &wgpu::BindGroupLayout,
        size: u32,
        pass: MapPass,
    ) -> MapSet {
        let map = ShadowMap::new(gpu, size);
        let moments = MomentsMap::new(gpu, size);
        let min_max = MinMaxChain::new(gpu, &map);
        let shadow_pipelines = (0..scene.scene.lights.len())
            .map(|k| {
                let state = match pass {
                    MapPass::Lesson | MapPass::LessonHidingOnly => ShadowPassState {
                        cull: None,
                        ..SlopeScaledBias::RECOMMENDED.pass_state(gpu, &scene.scene, k, size)
                    },
                    MapPass::Renderer { cull, bias } => ShadowPassState { cull, bias },
                };
                shadow_map::shadow_pipeline(gpu, scene, module, state)
            })
            .collect();
        let drawn = (0..scene.scene.lights.len())
            .map(|k| match pass {
                MapPass::LessonHidingOnly => casters::drawn(&scene.scene, k),
                _ => scene.scene.objects.iter().map(|o| o.casts_shadow).collect(),
            })
            .collect();
        let nearest = map_group(
            gpu,
            layout,
            &map,
            &moments,
            &min_max,
            wgpu::FilterMode::Nearest,
        );
        let linear = map_group(
            gpu,
            layout,
            &map,
            &moments,
            &min_max,
            wgpu::FilterMode::Linear,
        );
        MapSet {
            size,
            pass,
            map,
            moments,
            min_max,
            drawn,
            nearest,
            linear,
            shadow_pipelines,
        }
    }

    /// Records light `light`'s shadow pass into the map; the casters drawn.
    pub fn shadow_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &SceneGpu,
        light: usize,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) -> u32 {
        let pipeline = &self.shadow_pipelines[light];
        let drawn = &self.drawn[light];
        shadow_map::shadow_pass_keeping(encoder, scene, pipeline, &self.map, light, ts, |i| {
            drawn[i]
        })
    }

    /// Group 2 for a technique's comparison sampler.
    pub fn group(&self, filter: wgpu::FilterMode) -> &wgpu::BindGroup {
        match filter {
            wgpu::FilterMode::Nearest => &self.nearest,
            _ => &self.linear,
        }
    }
}

/// The maps the variants read: one per size and pass some variant runs.
pub struct MapSets {
    sets: Vec<MapSet>,
}

impl MapSets {
    /// A set for each distinct `(size, pass)` of `keys`, in their order.
    pub fn new(
        keys: impl IntoIterator<Item = (u32, MapPass)>,
        mut make: impl FnMut(u32, MapPass) -> MapSet,
    ) -> MapSets {
        let mut sets: Vec<MapSet> = Vec::new();
        for (size, pass) in keys {
            if !sets.iter().any(|s| s.size == size && s.pass == pass) {
                sets.push(make(size, pass));
            }
        }
        MapSets { sets }
    }

    /// The index of the set of `size` and `pass` (made by [`MapSets::new`]).
    pub fn index(&self, size: u32, pass: MapPass) -> usize {
        self.sets
            .iter()
            .position(|s| s.size == size && s.pass == pass)
            .expect("a map set for every size and pass a variant runs")
    }

    pub fn at(&self, index: usize) -> &MapSet {
        &self.sets[index]
    }
}

/// Group 2's layout: lesson 03's map bindings, binding 3, the variance
/// map, and binding 4, the min/max chain.
pub fn map_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    let mut entries = shadow_map_entries();
    entries.push(float_texture_entry(2));
    entries.push(storage_entry(3, wgpu::ShaderStages::FRAGMENT, false, None));
    entries.push(storage_entry(4, wgpu::ShaderStages::FRAGMENT, false, None));
    bindings::layout(gpu, "soft shadow map", &entries)
}

/// Lesson 03's map bindings (group 2), binding 3, the variance map, and
/// binding 4, the min/max chain.
fn map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &ShadowMap,
    moments: &MomentsMap,
    min_max: &MinMaxChain,
    filter: wgpu::FilterMode,
) -> wgpu::BindGroup {
    let sampler = comparison_sampler(gpu, filter);
    let view = wgpu::BindingResource::TextureView(&map.view);
    let resources = [
        view.clone(),
        wgpu::BindingResource::Sampler(&sampler),
        view,
        moments.buffer.as_entire_binding(),
        min_max.buffer.as_entire_binding(),
    ];
    bindings::group(gpu, "soft shadow map", layout, &resources)
}
