//! The cameras of chapter 07's exercises: the scene seen through the
//! student's projection ([`super::exercises`]). The lesson's own variants
//! never use them.

use anyhow::Result;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::scene::Camera;

use super::infinite_far::{
    infinite_perspective, projected_scene, scene_with_projection, INFINITE_EPSILON,
};

/// The near-plane rectangle `[left, right, bottom, top]` of `camera` for
/// an image of `aspect` (width / height): the symmetric one of its field
/// of view, moved by its lens shift. The shift adds `shift` to NDC x, y,
/// so the view-space window that lands on [−1, 1] is [−1 − s, 1 − s]
/// times the half-size.
pub fn near_rectangle(camera: &Camera, aspect: f64) -> [f64; 4] {
    let half_h = camera.near * (0.5 * camera.fov_y_deg.to_radians()).tan();
    let half_w = half_h * aspect;
    let s = camera.shift;
    [
        half_w * (-1.0 - s.x),
        half_w * (1.0 - s.x),
        half_h * (-1.0 - s.y),
        half_h * (1.0 - s.y),
    ]
}

/// Exercise 1: the camera with `exercises::infinite_frustum` of the
/// scene camera's near-plane rectangle (its shift included: the matrix
/// is used as it is).
pub fn infinite_projection_scene(gpu: &Gpu, scene: &SceneGpu) -> Result<SceneGpu> {
    let c = &scene.scene.camera;
    let aspect = scene.width as f64 / scene.height as f64;
    let [l, r, b, t] = near_rectangle(c, aspect).map(|x| x as f32);
    let proj = crate::exercise!(lesson_07::infinite_frustum(l, r, b, t, c.near as f32)).as_dmat4();
    scene_with_projection(gpu, scene, proj)
}

/// The near distance `exercises::adaptive_near` picks for `scene`'s camera
/// and bounds (origin-relative, as the GPU sees them).
pub fn adapted_near(scene: &SceneGpu) -> f64 {
    let s = &scene.scene;
    let o = s.origin();
    let (lo, hi) = s.bounds();
    let c = &s.camera;
    let forward = (c.target - c.eye).normalize();
    crate::exercise!(lesson_07::adaptive_near(
        c.eye - o,
        forward,
        lo - o,
        hi - o,
        c.near
    ))
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
