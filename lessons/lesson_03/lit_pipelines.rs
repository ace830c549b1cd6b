//! Lesson 03's lit pipelines, one per filter's constants: `pcf.wgsl`'s
//! `MODE`, `RENDERER_BIAS`, `N` and `RECEIVER_PLANE`, fixed when the
//! pipeline is built, so that it holds only its filter's code and a grid's
//! loops unroll. A knob that changes the grid's side gets its own pipeline
//! the next time the variant draws.

use std::collections::HashMap;

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;

use super::pcf::Filter;

/// What a lit pipeline is compiled with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LitKey {
    pub mode: u32,
    pub renderer_bias: bool,
    pub n: u32,
    pub receiver_plane: bool,
}

impl LitKey {
    /// `filter`'s pipeline, with a renderer's receiver bias or without.
    pub fn new(filter: Filter, renderer_bias: bool) -> LitKey {
        let (n, receiver_plane) = filter.grid_constants();
        LitKey {
            mode: filter.mode(),
            renderer_bias,
            n,
            receiver_plane,
        }
    }

    fn constants(self) -> [(&'static str, f64); 4] {
        [
            ("MODE", self.mode as f64),
            ("RENDERER_BIAS", self.renderer_bias as u32 as f64),
            ("N", self.n as f64),
            ("RECEIVER_PLANE", self.receiver_plane as u32 as f64),
        ]
    }
}

/// `fs_lit` of one module, compiled per key when first asked for.
pub struct LitPipelines {
    module: wgpu::ShaderModule,
    /// Group 2 (the map) and group 3 (the filter's parameters).
    layouts: [wgpu::BindGroupLayout; 2],
    built: HashMap<LitKey, wgpu::RenderPipeline>,
}

impl LitPipelines {
    pub fn new(module: wgpu::ShaderModule, layouts: [wgpu::BindGroupLayout; 2]) -> Self {
        LitPipelines {
            module,
            layouts,
            built: HashMap::new(),
        }
    }

    /// Builds the pipeline of `key` if it was not yet.
    pub fn build(&mut self, gpu: &Gpu, scene: &SceneGpu, key: LitKey) {
        let (module, layouts) = (&self.module, &self.layouts);
        self.built.entry(key).or_insert_with(|| {
            scene.lit_pipeline_with_depth(
                gpu,
                module,
                "fs_lit",
                &[&layouts[0], &layouts[1]],
                scene.lit_depth_state(Default::default()),
                &key.constants(),
            )
        });
    }

    /// The pipeline of `key`, once [`LitPipelines::build`] made it.
    pub fn get(&self, key: LitKey) -> &wgpu::RenderPipeline {
        &self.built[&key]
    }
}
