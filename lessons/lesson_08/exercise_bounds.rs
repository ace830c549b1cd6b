//! The bounds of chapter 08's exercises: each light's range-sphere bounds
//! with one of the two computed by the student's code
//! ([`super::exercises`]). The lesson's own variants never use them.

use common::gpu::render::SceneGpu;

use super::exercises;
use super::range_sphere::{all_bounds, sphere_depth_bounds, sphere_scissor, LightBounds};
use common::scene::LightKind;

/// Which bound the student's code computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Student {
    /// `exercises::scissor_rect`, with the lesson's depth bounds.
    Scissor,
    /// `exercises::depth_bounds`, with the lesson's scissor.
    DepthBounds,
}

/// As [`all_bounds`], one of the two bounds from the exercise.
pub fn exercise_bounds(scene: &SceneGpu, student: Student) -> Vec<Option<Option<LightBounds>>> {
    let (cam, s) = (&scene.camera, &scene.scene);
    let (view, proj) = (cam.view.as_dmat4(), cam.proj.as_dmat4());
    let (near, w, h) = (s.camera.near, scene.width, scene.height);
    let mut out = all_bounds(scene);
    for (b, l) in out.iter_mut().zip(&s.lights) {
        let (LightKind::Point { position, range }
        | LightKind::Spot {
            position, range, ..
        }) = l.kind
        else {
            continue;
        };
        let c = view.transform_point3(position - s.origin());
        let (depth, scissor) = match student {
            Student::Scissor => (
                sphere_depth_bounds(proj, near, c, range),
                exercises::scissor_rect(proj, near, c, range, w, h),
            ),
            Student::DepthBounds => (
                exercises::depth_bounds(proj, near, c, range),
                sphere_scissor(proj, near, c, range, w, h),
            ),
        };
        *b = Some(
            depth
                .zip(scissor)
                .map(|(depth, scissor)| LightBounds { depth, scissor }),
        );
    }
    out
}
