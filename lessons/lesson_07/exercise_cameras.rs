//! The cameras of chapter 07's exercises: the scene seen through the
//! student's projection ([`super::exercises`]). The lesson's own variants
//! never use them.

use anyhow::Result;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;

use super::exercises;
use super::infinite_far::{infinite_perspective, projected_scene, INFINITE_EPSILON};

/// Exercise 1: the camera with `exercises::infinite_projection`.
pub fn infinite_projection_scene(gpu: &Gpu, scene: &SceneGpu) -> Result<SceneGpu> {
    projected_scene(gpu, scene, |fov_y, aspect, near| {
        exercises::infinite_projection(fov_y as f32, aspect as f32, near as f32).as_dmat4()
    })
}

/// The near distance `exercises::adaptive_near` picks for `scene`'s camera
/// and bounds (origin-relative, as the GPU sees them).
pub fn adapted_near(scene: &SceneGpu) -> f64 {
    let s = &scene.scene;
    let o = s.origin();
    let (lo, hi) = s.bounds();
    let c = &s.camera;
    let forward = (c.target - c.eye).normalize();
    exercises::adaptive_near(c.eye - o, forward, lo - o, hi - o, c.near)
}

/// Exercise 2: the lesson's infinite projection (ε) with the adapted near.
pub fn adaptive_near_scene(gpu: &Gpu, scene: &SceneGpu) -> Result<SceneGpu> {
    let near = adapted_near(scene);
    projected_scene(gpu, scene, |fov_y, aspect, _| {
        infinite_perspective(fov_y, aspect, near, INFINITE_EPSILON)
    })
}

/// How many scene vertices a near plane at view depth `near` clips that
/// the scene file's own near plane keeps (view depth in `[file near,
/// near)`): 0 for a near plane that loses nothing. Vertices the file's
/// near plane clips already (behind the camera, say) are not the
/// exercise's doing and are not counted.
pub fn vertices_before_near(scene: &SceneGpu, near: f64) -> u64 {
    let s = &scene.scene;
    let c = &s.camera;
    let forward = (c.target - c.eye).normalize();
    let depth = |p: common::glam::DVec3| (p - c.eye).dot(forward);
    s.objects
        .iter()
        .flat_map(|o| {
            o.mesh
                .positions
                .iter()
                .map(|p| o.model.transform_point3(p.as_dvec3()))
        })
        .filter(|&p| (c.near..near).contains(&depth(p)))
        .count() as u64
}
