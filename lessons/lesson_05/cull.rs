//! Leaving casters out (lesson 05's second exercise, and lesson 06's plan):
//! the draws of the casters whose volume a test says can matter. The view
//! frustum's planes are in `volumes` (the CPU path gives them to lesson
//! 05's first exercise).

use common::glam::DVec3;
use common::gpu::render::SceneGpu;
use common::scene::LightKind;

pub use super::frustum::frustum_planes;
use super::silhouette::LightDir;
use super::volumes::{CasterDraw, ShadowVolumes};

/// A test "can this caster's volume matter?" (lesson 05's exercise
/// `volume_can_matter`): the caster's bounding sphere (centre, radius), the
/// light, its range (`None`: directional), and the view frustum's planes,
/// all origin-relative world space.
pub type CanMatterFn = fn(DVec3, f64, LightDir, Option<f64>, &[(DVec3, f64)]) -> bool;

/// Per light, z-pass draws of the casters `can_matter` keeps.
pub fn kept_draws(
    volumes: &ShadowVolumes,
    scene: &SceneGpu,
    can_matter: CanMatterFn,
) -> Vec<Vec<CasterDraw>> {
    let frustum = frustum_planes(scene.camera.view_proj.as_dmat4());
    (0..scene.scene.lights.len())
        .map(|k| {
            let light = volumes.light(scene, k);
            let range = match scene.scene.lights[k].kind {
                LightKind::Directional { .. } => None,
                LightKind::Point { range, .. } | LightKind::Spot { range, .. } => Some(range),
            };
            volumes
                .casters
                .iter()
                .filter(|c| can_matter(c.center, c.radius, light, range, &frustum))
                .map(|c| CasterDraw::zpass(c.object))
                .collect()
        })
        .collect()
}
