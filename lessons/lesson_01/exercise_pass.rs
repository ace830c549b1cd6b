//! The plumbing of lesson 01's exercises: the light matrix of
//! `exercise_tight_frustum` (the student's [`fit_light_box`]) and the lit
//! pipeline of `exercise_depth_compare` (the student's `depth_compare`,
//! `shaders/lesson_01/exercises.wgsl`). The lesson's own variants use
//! neither.
//!
//! [`fit_light_box`]: super::exercises::fit_light_box

use common::glam::dcamera::rh::proj::directx as webgpu;
use common::glam::{DVec3, Mat4};
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::scene::camera::{directional_light_view, light_view_proj};
use common::scene::{LightKind, Scene};

use super::exercises;
use super::shadow_map;

/// Light `light`'s view-projection with the box the student fits
/// ([`exercises::fit_light_box`]) around every vertex of every object. The
/// light's view is the lesson's (`common::scene::camera::directional_light_view_proj`);
/// only the box differs. Spot lights keep the lesson's matrix.
pub fn tight_light_view_proj(scene: &Scene, light: usize) -> Option<Mat4> {
    let LightKind::Directional { direction } = scene.lights[light].kind else {
        return light_view_proj(scene, light);
    };
    let o = scene.origin();
    let (view, _, _) = directional_light_view(scene, direction);
    let points: Vec<DVec3> = scene
        .objects
        .iter()
        .flat_map(|ob| {
            let m = ob.model;
            ob.mesh
                .positions
                .iter()
                .map(move |p| m.transform_point3(p.as_dvec3()) - o)
        })
        .collect();
    if points.is_empty() {
        return light_view_proj(scene, light);
    }
    let (a, b) = exercises::fit_light_box(view, &points);
    let proj = webgpu::orthographic(a.x, b.x, a.y, b.y, -b.z, -a.z);
    Some((proj * view).as_mat4())
}

/// The lit pipeline of `exercise_depth_compare`: shadow_map.wgsl, the
/// student's WGSL and `exercise_lit.wgsl`, bound like the lesson's own lit
/// pass (the shadow map at group 2, `layout`).
pub fn depth_compare_pipeline(
    gpu: &Gpu,
    scene: &SceneGpu,
    layout: &wgpu::BindGroupLayout,
) -> anyhow::Result<wgpu::RenderPipeline> {
    let exercises_path = crate::exercises_wgsl_path("lesson_01");
    let files = [
        (exercises_path.as_str(), exercises::EXERCISES_WGSL),
        (
            "shaders/lesson_01/exercise_lit.wgsl",
            include_str!("../../shaders/lesson_01/exercise_lit.wgsl"),
        ),
    ];
    let module = shadow_map::shader_module_from_files(gpu, "lesson_01 exercises", &files)?;
    Ok(scene.lit_pipeline(
        gpu,
        &module,
        "fs_exercise_depth_compare",
        &[layout],
        Default::default(),
    ))
}
