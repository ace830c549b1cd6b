//! The plumbing of lesson 01's exercises: the light matrix of
//! `exercise_tight_frustum` (the student's [`fit_light_box`], fitted to
//! the camera's view) and the lit
//! pipeline of `exercise_depth_compare` (the student's `depth_compare`,
//! `shaders/lesson_01/exercises.wgsl`). The lesson's own variants use
//! neither.
//!
//! [`fit_light_box`]: super::exercises::fit_light_box

use common::glam::dcamera::rh::proj::directx as webgpu;
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DVec3, Mat4};
use common::gpu::bindings::{self, float_texture_entry};
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::scene::camera::{directional_light_view, light_view_proj};
use common::scene::{LightKind, Scene};

use super::shadow_map;

use super::view_frustum::CameraFrustum;

/// Light `light`'s view-projection with the box the student fits
/// ([`exercises::fit_light_box`](super::exercises::fit_light_box)) to what the camera sees: every vertex of
/// every object, and the camera's frustum for a `width × height` image. The
/// light's view is the lesson's (`common::scene::camera::directional_light_view_proj`);
/// only the box differs. Spot lights keep the lesson's matrix.
pub fn tight_light_view_proj(scene: &Scene, light: usize, width: u32, height: u32) -> Option<Mat4> {
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
    let c = &scene.camera;
    let camera = CameraFrustum {
        view: look_at_mat4(c.eye - o, c.target - o, c.up),
        tan_half_fov_y: (c.fov_y_deg.to_radians() * 0.5).tan(),
        aspect: width.max(1) as f64 / height.max(1) as f64,
        near: c.near,
    };
    let (a, b) = crate::exercise!(lesson_01::fit_light_box(view, &points, &camera));
    let proj = webgpu::orthographic(a.x, b.x, a.y, b.y, -b.z, -a.z);
    Some((proj * view).as_mat4())
}

/// The lit pipeline of `exercise_depth_compare`: shadow_map.wgsl, the
/// student's WGSL and `exercise_lit.wgsl`, bound like the lesson's own lit
/// pass (the shadow map at group 2, `layout`), plus the same map as plain
/// floats at group 3 (`depths_layout`: GL cannot `textureLoad` through a
/// depth binding).
pub fn depth_compare_pipeline(
    gpu: &Gpu,
    scene: &SceneGpu,
    layout: &wgpu::BindGroupLayout,
    depths_layout: &wgpu::BindGroupLayout,
) -> anyhow::Result<wgpu::RenderPipeline> {
    let exercises_path = crate::exercises_wgsl_path("lesson_01");
    let files = [
        (
            exercises_path.as_str(),
            crate::exercise!(lesson_01::EXERCISES_WGSL),
        ),
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
        &[layout, depths_layout],
        Default::default(),
    ))
}

// ANCHOR: shadow_depths_layout
/// Group 3 of exercise 2's lit pass: the map as floats, one entry, an
/// unfilterable-float 2D texture at binding 0 (`shadow_depths`).
pub fn depths_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    bindings::layout(gpu, "shadow map as floats", &[float_texture_entry(0)])
}

/// Group 3 for `map`: the same view of the same depth texture as group 2.
pub fn depths_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &shadow_map::ShadowMap,
) -> wgpu::BindGroup {
    let view = wgpu::BindingResource::TextureView(&map.view);
    bindings::group(gpu, "shadow map as floats", layout, &[view])
}
// ANCHOR_END: shadow_depths_layout
