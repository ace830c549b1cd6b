//! The shadow maps lesson 10's variants read, one set per map size (the
//! lesson's 1024², and each size a renderer's port runs: three.js 512²,
//! Bevy's cascade 2048²): the map, its variance map, their bindings and
//! the shadow pipelines that render it.

use common::gpu::bindings::{self, float_texture_entry, storage_entry};
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;

use super::moments::MomentsMap;
use crate::lesson_01::shadow_map::{
    self, comparison_sampler, shadow_map_entries, ShadowMap, ShadowPassState,
};
use crate::lesson_02::bias::SlopeScaledBias;

/// A shadow map of one size, its variance map, their bindings and the
/// shadow pipelines that render it.
pub struct MapSet {
    pub size: u32,
    pub map: ShadowMap,
    pub moments: MomentsMap,
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
    ) -> MapSet {
        let map = ShadowMap::new(gpu, size);
        let moments = MomentsMap::new(gpu, size);
        let shadow_pipelines = (0..scene.scene.lights.len())
            .map(|k| {
                let b = SlopeScaledBias::RECOMMENDED;
                let state = ShadowPassState {
                    cull: None,
                    ..b.pass_state(gpu, &scene.scene, k, size)
                };
                shadow_map::shadow_pipeline(gpu, scene, module, state)
            })
            .collect();
        let nearest = map_group(gpu, layout, &map, &moments, wgpu::FilterMode::Nearest);
        let linear = map_group(gpu, layout, &map, &moments, wgpu::FilterMode::Linear);
        MapSet {
            size,
            map,
            moments,
            nearest,
            linear,
            shadow_pipelines,
        }
    }

    /// Group 2 for a technique's comparison sampler.
    pub fn group(&self, filter: wgpu::FilterMode) -> &wgpu::BindGroup {
        match filter {
            wgpu::FilterMode::Nearest => &self.nearest,
            _ => &self.linear,
        }
    }
}

/// Group 2's layout: lesson 03's map bindings and binding 3, the variance
/// map.
pub fn map_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    let mut entries = shadow_map_entries();
    entries.push(float_texture_entry(2));
    entries.push(storage_entry(3, wgpu::ShaderStages::FRAGMENT, false, None));
    bindings::layout(gpu, "soft shadow map", &entries)
}

/// Lesson 03's map bindings (group 2) and binding 3, the variance map.
fn map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &ShadowMap,
    moments: &MomentsMap,
    filter: wgpu::FilterMode,
) -> wgpu::BindGroup {
    let sampler = comparison_sampler(gpu, filter);
    let view = wgpu::BindingResource::TextureView(&map.view);
    let resources = [
        view.clone(),
        wgpu::BindingResource::Sampler(&sampler),
        view,
        moments.buffer.as_entire_binding(),
    ];
    bindings::group(gpu, "soft shadow map", layout, &resources)
}
