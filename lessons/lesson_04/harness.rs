//! Lesson 04's harness: what the runner measures and shows besides the
//! image. What the report counts around the frame that `main.rs` draws
//! (the face passes' depth writes, counted once per variant in their own
//! submits, and the faces, draws and scissored texels of each frame), the
//! faces' rectangles with the knob that turns them off, and the cube map
//! as the window's buffer view and as an extra image (a cross).

use std::path::Path;

use common::glam::DVec3;
use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, CASTER_DRAWS, DRAWS, FACES_RENDERED, FILTER_TAPS_PER_PIXEL, NEAR_PLANE_MM,
    SHADOW_FRAGMENTS, SHADOW_TEXELS_SCISSORED, SHADOW_TEXELS_WRITTEN, SLOPE_BIAS_MILLITEXELS,
    UNCLIPPED_DEPTH,
};
use common::measure::timing::Frame;
use common::run::instruments::{BufferView, Instruments};
use common::run::knobs::{Knob, KnobRange};
use common::run::lesson::variant_name;
use common::Result;
use workbook::lesson_04::costs::{self, PCF3D_TAPS};
use workbook::lesson_04::cross::{cross_view, write_cross_png};
use workbook::lesson_04::culling::face_casters;
use workbook::lesson_04::faces::{point_light, FaceRects};
use workbook::lesson_04::footprint::lookup_footprint;

use super::{CubeShadows, Variant};

/// What a frame's face passes drew.
#[derive(Clone, Copy, Debug, Default)]
pub struct CubeStats {
    pub faces_rendered: u64,
    pub caster_draws: u64,
    /// Texels inside the drawn faces' scissor rectangles.
    pub texels_scissored: u64,
}

impl Instruments for CubeShadows {
    /// The variant's cube map, as a cross ([`cross_view`]).
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        let Some(last) = scene.scene.lights.len().checked_sub(1) else {
            return Ok(None); // no light: no face passes
        };
        let map = &self.maps[self.prepared[v].map];
        cross_view(gpu, map, last).map(Some)
    }

    /// The runner moved the camera or the light (`--fragile`): the face
    /// passes' depth writes are counted again on the next frame.
    fn count_again(&mut self, variant: Variant) {
        self.prepared[variant].texels_written = None;
    }

    /// The standard costs and the lesson's own ([`CubeShadows::cube_counters`]).
    fn counters(&self, variant: Variant) -> Counts {
        self.cube_counters(variant)
    }

    fn knobs(&self, variant: Variant) -> Vec<Knob> {
        self.scissor_knob(variant)
    }

    /// `face_scissor` on or off; the face passes are counted again.
    fn set_knob(&mut self, _: &Gpu, _: &SceneGpu, v: Variant, _: &str, value: f64) -> Result<()> {
        self.prepared[v].scissor = value == 1.0;
        self.count_again(v);
        Ok(())
    }

    /// The variant's cube map, unfolded as a cross (`NAME_cube_map.png`).
    fn write_extras(&self, gpu: &Gpu, _: &SceneGpu, variant: Variant, out: &Path) -> Result<()> {
        let map = &self.maps[self.prepared[variant].map];
        if map.faces {
            return Ok(()); // no cube view to unfold
        }
        let path = out.join(format!("{}_cube_map.png", variant_name(variant)));
        write_cross_png(gpu, map, 128, &path)
    }
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
        if self.prepared[variant].texels_written.is_none() {
            // In a web page the count comes back a frame or more later.
            let n = frame.untimed(|gpu| later(|| self.count_texels(gpu, scene, variant)))?;
            self.prepared[variant].texels_written = n;
        }
        Ok(())
    }

    /// The report's counters: the standard costs (the face passes' depth
    /// writes and fragments, the lit pass's taps per pixel, the frame's
    /// draw calls) and the lesson's own (faces, caster draws, scissored
    /// texels, the faces' planes and bias).
    pub(super) fn cube_counters(&self, variant: Variant) -> Counts {
        let p = &self.prepared[variant];
        let v = variant.settings();
        let taps = v
            .peer
            .taps()
            .unwrap_or(if v.pcf > 0.0 { PCF3D_TAPS } else { 1 });
        let mut c = Counts::from([
            (FILTER_TAPS_PER_PIXEL, taps),
            (DRAWS, self.draws),
            (FACES_RENDERED, self.stats.faces_rendered),
            (CASTER_DRAWS, self.stats.caster_draws),
            (UNCLIPPED_DEPTH, u64::from(p.unclipped)),
            (NEAR_PLANE_MM, (p.near * 1000.0).round() as u64),
            // The slope bias, in thousandths of a texel per unit of tan θ.
            (
                SLOPE_BIAS_MILLITEXELS,
                (variant.settings().slope * 1000.0).round() as u64,
            ),
        ]);
        if let Some((written, fragments)) = p.texels_written {
            c.set(SHADOW_TEXELS_WRITTEN, written);
            c.set(SHADOW_FRAGMENTS, fragments);
        }
        c.set(SHADOW_TEXELS_SCISSORED, self.stats.texels_scissored);
        c
    }

    /// The faces rendered, caster draws and scissored texels of a frame,
    /// from what [`CubeShadows::draw`] returned (each light's draws and
    /// rectangle per face).
    pub(super) fn record_draws(&mut self, scene: &SceneGpu, drawn: &[([u32; 6], FaceRects)]) {
        let faces = drawn.iter().flat_map(|(d, r)| d.iter().zip(r));
        let drawn_into = faces.clone().filter(|(&d, _)| d > 0);
        self.stats = CubeStats {
            faces_rendered: drawn_into.clone().count() as u64,
            caster_draws: faces.map(|(&d, _)| u64::from(d)).sum(),
            texels_scissored: drawn_into.filter_map(|(_, r)| r.map(|r| r.area())).sum(),
        };
        self.draws = costs::frame_draws(scene, self.stats.caster_draws);
    }

    /// Light `light`'s face rectangles for `variant` (at `at`, with this
    /// range): the texels its visible receivers can look up
    /// ([`workbook::lesson_04::face_rects`]), or whole faces with the knob
    /// off and for the unculled frame (`nocull_1024` leaves out nothing).
    pub(super) fn face_rects(
        &mut self,
        scene: &SceneGpu,
        variant: Variant,
        light: usize,
        (at, range): (DVec3, f64),
    ) -> FaceRects {
        let v = variant.settings();
        let peer = (v.peer, v.bias_world);
        let far = v.far.unwrap_or(range);
        let footprint = lookup_footprint(v.storage, v.pcf, peer, v.size, far)
            .filter(|_| self.prepared[variant].scissor && v.cull.is_some());
        let receivers: Vec<_> = self.spheres.iter().map(|s| s.bounds()).collect();
        let camera = (scene.camera.view_proj, scene.camera.eye);
        self.rects
            .get((light, at), v.size, &receivers, camera, footprint)
    }

    /// The knob `face_scissor` (on by default): each face drawn only over
    /// its rectangle. The unculled frame and the exercise's lookup, whose
    /// texels the student's function picks, keep whole faces and have none.
    pub(super) fn scissor_knob(&self, variant: Variant) -> Vec<Knob> {
        if variant.settings().cull.is_none() || variant == Variant::ExerciseCubeFaces {
            return Vec::new();
        }
        vec![Knob {
            name: "face_scissor",
            doc: "each cube face drawn only over the texels a visible receiver's lookup can read (off: whole faces)",
            range: KnobRange::Toggle,
            value: f64::from(u8::from(self.prepared[variant].scissor)),
        }]
    }

    /// Every light's face passes for `variant`, counted ([`costs::count_light_texels`]).
    fn count_texels(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
    ) -> Result<(u64, u64)> {
        let v = variant.settings();
        let (near, far, pipeline) = {
            let p = &self.prepared[variant];
            (p.near, p.far, p.pipeline)
        };
        let mut total = (0, 0);
        for light in 0..scene.scene.lights.len() {
            self.faces.write(gpu, &scene.scene, light, near, far);
            let at = point_light(&scene.scene, self.faces.origin, light)
                .expect("check_scene allows point and spot lights");
            let rects = self.face_rects(scene, variant, light, at);
            let (written, fragments) = costs::count_light_texels(
                gpu,
                scene,
                &self.tally_pipelines[pipeline],
                &self.faces,
                v.size,
                (light, &rects),
                |face| face_casters(scene, &self.spheres, at, v.cull, face),
            )?;
            total = (total.0 + written, total.1 + fragments);
        }
        Ok(total)
    }
}
