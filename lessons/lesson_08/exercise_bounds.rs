//! The bounds of chapter 08's exercises: each spot light's bounds with one
//! of the two computed from its cone by the student's code
//! ([`super::exercises`]); point lights keep their range sphere's. The
//! lesson's own variants never use them.

use common::gpu::render::SceneGpu;

use super::range_sphere::{
    all_bounds, sphere_depth_bounds, sphere_scissor, LightBounds, RangeSphere,
};
use common::scene::LightKind;

/// Which bound the student's code computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Student {
    /// The scissor of `exercises::cone_sphere`, with the range sphere's
    /// depth bounds.
    Scissor,
    /// `exercises::cone_depth_bounds`, with the range sphere's scissor.
    DepthBounds,
}

/// As [`all_bounds`] (of the same `spheres`), a spot light's scissor or
/// depth bounds from the exercise.
pub fn exercise_bounds(
    scene: &SceneGpu,
    spheres: &[RangeSphere],
    student: Student,
) -> Vec<Option<Option<LightBounds>>> {
    let (cam, s) = (&scene.camera, &scene.scene);
    let (view, proj) = (cam.view.as_dmat4(), cam.proj.as_dmat4());
    let (near, w, h) = (s.camera.near, scene.width, scene.height);
    let mut out = all_bounds(scene, spheres);
    for ((b, l), sphere) in out.iter_mut().zip(&s.lights).zip(spheres) {
        let (
            LightKind::Spot {
                direction,
                range,
                spot_angle_deg,
                ..
            },
            Some((p, _)),
        ) = (l.kind, *sphere)
        else {
            continue;
        };
        let half = (0.5 * spot_angle_deg).to_radians();
        let c = view.transform_point3(p);
        let (depth, scissor) = match student {
            Student::Scissor => {
                let (centre, r) =
                    crate::exercise!(lesson_08::cone_sphere(p, direction, range, half));
                let centre = view.transform_point3(centre);
                (
                    sphere_depth_bounds(proj, near, c, range),
                    sphere_scissor(proj, near, centre, r, w, h),
                )
            }
            Student::DepthBounds => {
                let axis = view.transform_vector3(direction);
                (
                    crate::exercise!(lesson_08::cone_depth_bounds(
                        proj, near, c, axis, range, half
                    )),
                    sphere_scissor(proj, near, c, range, w, h),
                )
            }
        };
        *b = Some(
            depth
                .zip(scissor)
                .map(|(depth, scissor)| LightBounds { depth, scissor }),
        );
    }
    out
}
