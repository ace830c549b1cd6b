//! Lesson 04's harness: what the report counts around the frame that
//! `main.rs` draws (the face passes' depth writes, counted once per
//! variant in their own submits, and the faces and draws of each frame).

use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::Result;
use workbook::lesson_04::costs;
use workbook::lesson_04::culling::face_casters;
use workbook::lesson_04::faces::point_light;

use super::{CubeShadows, Variant};

/// What a frame's face passes drew.
#[derive(Clone, Copy, Debug, Default)]
pub struct CubeStats {
    pub faces_rendered: u64,
    pub caster_draws: u64,
}

impl CubeShadows {
    /// The face passes' depth writes and fragments, counted on the
    /// variant's first frame (its own submits, left out of the frame's
    /// times).
    pub(super) fn count_texels_once(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<()> {
        if self.texels_written[variant as usize].is_none() && frame.gpu.can_wait() {
            let n = frame.untimed(|gpu| self.count_texels(gpu, scene, variant))?;
            self.texels_written[variant as usize] = Some(n);
        }
        Ok(())
    }

    /// The faces rendered and caster draws of a frame, from what
    /// [`CubeShadows::draw`] returned (each light's draws per face).
    pub(super) fn record_draws(&mut self, scene: &SceneGpu, drawn: &[[u32; 6]]) {
        let faces = drawn.iter().flatten();
        self.stats = CubeStats {
            faces_rendered: faces.clone().filter(|&&d| d > 0).count() as u64,
            caster_draws: faces.map(|&d| u64::from(d)).sum(),
        };
        self.draws = costs::frame_draws(scene, self.stats.caster_draws);
    }

    /// Every light's face passes for `variant`, counted ([`costs::count_light_texels`]).
    fn count_texels(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<(u64, u64)> {
        let (v, p) = (variant.settings(), &self.prepared[variant as usize]);
        let mut total = (0, 0);
        for light in 0..scene.scene.lights.len() {
            self.faces.write(gpu, &scene.scene, light, p.near, p.far);
            let at = point_light(&scene.scene, self.faces.origin, light)
                .expect("check_scene allows point and spot lights");
            let (written, fragments) = costs::count_light_texels(
                gpu,
                scene,
                &self.tally_pipelines[p.pipeline],
                &self.faces,
                v.size,
                light,
                |face| face_casters(scene, &self.spheres, at, v.cull, face),
            )?;
            total = (total.0 + written, total.1 + fragments);
        }
        Ok(total)
    }
}
