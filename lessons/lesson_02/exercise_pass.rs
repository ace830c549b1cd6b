//! The lit passes of lesson 02's exercises (`exercise_slope_bias`,
//! `exercise_grazing_bias`): the student's WGSL ([`super::exercises`])
//! plugged into the lesson's lookup (`shaders/lesson_02/exercise_lit.wgsl`).
//! Compiled only when an exercise runs, so that the lesson's own variants
//! never depend on the exercise code.

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;

use crate::lesson_01::shadow_map;

/// Which exercise's lit pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exercise {
    SlopeBias,
    GrazingBias,
}

impl Exercise {
    fn entry(self) -> &'static str {
        match self {
            Exercise::SlopeBias => "fs_exercise_slope_bias",
            Exercise::GrazingBias => "fs_exercise_grazing_bias",
        }
    }
}

/// The exercise's lit pipeline: bias.wgsl, the exercises' WGSL and
/// `exercise_lit.wgsl` in one module, bound like the lesson's own lit pass
/// (`layouts`: the shadow map at group 2, the bias at group 3).
pub fn lit_pipeline(
    gpu: &Gpu,
    scene: &SceneGpu,
    exercise: Exercise,
    layouts: &[&wgpu::BindGroupLayout],
) -> anyhow::Result<wgpu::RenderPipeline> {
    let exercises_path = crate::exercises_wgsl_path("lesson_02");
    let files = [
        (
            "shaders/lesson_02/bias.wgsl",
            include_str!("../../shaders/lesson_02/bias.wgsl"),
        ),
        (
            exercises_path.as_str(),
            crate::exercise!(lesson_02::EXERCISES_WGSL),
        ),
        (
            "shaders/lesson_02/exercise_lit.wgsl",
            include_str!("../../shaders/lesson_02/exercise_lit.wgsl"),
        ),
    ];
    let module = shadow_map::shader_module_from_files(gpu, "lesson_02 exercises", &files)?;
    Ok(scene.lit_pipeline(gpu, &module, exercise.entry(), layouts, Default::default()))
}
