//! The lit pass's pipelines and the cascade picture's (lesson 09), one
//! pair per variant shape: the cascade count and the blend are `CASCADES`
//! and `BLEND` in `csm.wgsl`, constants of the pipeline, so a variant's
//! pipeline holds only its own path. A pair is made when a variant of its
//! shape first renders (a knob may ask for a new count at any time).

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;

use super::extras;
use super::setup::Setup;

/// What a variant's lit pass is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shape {
    pub count: usize,
    pub blend: bool,
}

impl Shape {
    pub fn of(setup: &Setup) -> Shape {
        Shape {
            count: setup.count,
            blend: setup.blend > 0.0,
        }
    }

    /// The override constants of `csm.wgsl`.
    pub fn constants(self) -> [(&'static str, f64); 2] {
        [
            ("CASCADES", self.count as f64),
            ("BLEND", self.blend as u32 as f64),
        ]
    }
}

/// A shape's lit pipeline (`fs_lit`) and its cascade picture's
/// (`fs_cascade_tint`).
pub struct ShapePipelines {
    pub lit: wgpu::RenderPipeline,
    pub tint: wgpu::RenderPipeline,
}

/// The pipelines made so far, from one module and the cascades' layout.
pub struct CsmPipelines {
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    made: Vec<(Shape, ShapePipelines)>,
}

impl CsmPipelines {
    pub fn new(module: &wgpu::ShaderModule, layout: &wgpu::BindGroupLayout) -> CsmPipelines {
        CsmPipelines {
            module: module.clone(),
            layout: layout.clone(),
            made: Vec::new(),
        }
    }

    /// Makes `shape`'s pair unless it exists.
    pub fn make(&mut self, gpu: &Gpu, scene: &SceneGpu, shape: Shape) {
        if self.get(shape).is_some() {
            return;
        }
        let constants = shape.constants();
        let lit = scene.lit_pipeline_with_depth(
            gpu,
            &self.module,
            "fs_lit",
            &[&self.layout],
            scene.lit_depth_state(Default::default()),
            &constants,
        );
        let tint = extras::tint_pipeline(gpu, scene, &self.module, &self.layout, &constants);
        self.made.push((shape, ShapePipelines { lit, tint }));
    }

    /// `shape`'s pair, once made.
    pub fn get(&self, shape: Shape) -> Option<&ShapePipelines> {
        self.made.iter().find(|(s, _)| *s == shape).map(|(_, p)| p)
    }
}
