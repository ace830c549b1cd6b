//! Lesson 09's harness: what the runner measures and shows besides the
//! frame that `main.rs` draws. The counters: the cascades' count and size,
//! a frame's draw calls, the shadow passes' depth writes and fragments
//! over every light and cascade (lesson 01's tally, in submits of their
//! own, each cascade drawing the casters it keeps), how far the boxes lie
//! off their texel grids and the texels per 100 m at four view depths
//! (perspective aliasing). Also the knobs (the cascade count, the split's
//! λ), the cascade each pixel samples (the window's buffer view, an extra
//! image and the report's error per cascade), every cascade's map as an
//! extra image, and the runner's sub-texel move of the maps (`--fragile`).

use std::path::Path;

use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;
use common::measure::counters::{
    Counter, Counts, CASCADES, CASTERS_DRAWN, DRAWS, FILTER_TAPS_PER_PIXEL,
    ORIGIN_OFF_GRID_MILLITEXELS, SHADOW_FRAGMENTS, SHADOW_MAP_SIZE, SHADOW_TEXELS_WRITTEN,
    TEXELS_PER_100M_AT_10M, TEXELS_PER_100M_AT_200M, TEXELS_PER_100M_AT_2M, TEXELS_PER_100M_AT_50M,
};
use common::measure::timing::Frame;
use common::run::instruments::{BufferView, Instruments};
use common::run::knobs::Knob;
use common::run::lesson::variant_name;
use common::scene::camera::light_view_proj;
use common::Result;
use workbook::lesson_01::tally::Tally;
use workbook::lesson_09::cascades::{self, Cascade};
use workbook::lesson_09::csm::{self, CascadeMaps};
use workbook::lesson_09::pipelines::Shape;
use workbook::lesson_09::setup::{self, Setup};
use workbook::lesson_09::{extras, knobs};

use super::{Csm, Variant};

/// The view depths the perspective-aliasing counters are taken at, in
/// metres, each with its counter.
const ALIASING_AT: [(u32, Counter); 4] = [
    (2, TEXELS_PER_100M_AT_2M),
    (10, TEXELS_PER_100M_AT_10M),
    (50, TEXELS_PER_100M_AT_50M),
    (200, TEXELS_PER_100M_AT_200M),
];

impl Instruments for Csm {
    /// The cascade each pixel samples ([`extras::cascade_view`]), light 0.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        let setup = self.setup(v);
        let (Some(m), Some(p)) = (
            self.find_maps(setup.resolution, setup.count),
            self.pipelines.get(Shape::of(&setup)),
        ) else {
            return Ok(None); // not drawn yet
        };
        let Some(group) = self.maps[m].1.first() else {
            return Ok(None); // no light: no cascades
        };
        extras::cascade_view(gpu, scene, &p.tint, group, setup.count).map(Some)
    }

    /// The cascade each pixel samples, from its view depth (light 0's
    /// cascades fitted to the camera now): the report's error per cascade.
    fn pixel_classes(
        &self,
        scene: &SceneGpu,
        variant: Variant,
        view_depth: &[f32],
    ) -> Option<(Vec<String>, Vec<u8>)> {
        let setup = self.setup(variant);
        let single = light_view_proj(&scene.scene, 0)?;
        let size = (scene.width, scene.height);
        let fit = (setup.fit(&scene.scene, &self.scene_box, single, size, 0)).ok()?;
        let names = (0..fit.len()).map(|i| format!("cascade {i}")).collect();
        let classes = view_depth
            .iter()
            .map(|&d| setup::cascade_of(&fit, d as f64) as u8)
            .collect();
        Some((names, classes))
    }

    /// The runner moved the camera or the light (`--fragile`): the shadow
    /// passes' depth writes are counted again on the next frame.
    fn count_again(&mut self, variant: Variant) {
        let v = &mut self.variants[variant];
        v.texels_written = None;
        v.caster_draws = None;
    }

    /// The cascades' count and size, the lookups per pixel, the frame's
    /// draws and the shadow passes' casters, texels and fragments, how far
    /// the boxes lie off their texel grids, and the texels per 100 m at
    /// [`ALIASING_AT`].
    fn counters(&self, variant: Variant) -> Counts {
        let setup = self.setup(variant);
        let v = &self.variants[variant];
        let mut c = Counts::from([
            (CASCADES, setup.count as u64),
            (SHADOW_MAP_SIZE, setup.resolution as u64),
            // A pixel in a blend band takes two lookups.
            (FILTER_TAPS_PER_PIXEL, if setup.blend > 0.0 { 2 } else { 1 }),
        ]);
        if let Some(casters) = v.caster_draws {
            c.set(DRAWS, self.draws(casters));
            c.set(CASTERS_DRAWN, casters);
        }
        if let Some((written, fragments)) = v.texels_written {
            c.set(SHADOW_TEXELS_WRITTEN, written);
            c.set(SHADOW_FRAGMENTS, fragments);
        }
        if let Some(fit) = &v.fitted {
            // How far the boxes' origins lie off their texel grids: 0 when
            // snapped (exercise 2's check).
            let off = fit
                .iter()
                .filter_map(|c| Some(cascades::off_grid(c.origin?, c.width, setup.resolution)))
                .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
            if let Some(off) = off {
                let milli = (off * 1000.0).round() as u64;
                c.set(ORIGIN_OFF_GRID_MILLITEXELS, milli);
            }
            for (d, counter) in ALIASING_AT {
                let cascade = &fit[setup::cascade_of(fit, d as f64)];
                // Per 100 m: whole numbers that still resolve the far cascades.
                let per_100m = 100.0 * setup.resolution as f64 / cascade.width;
                c.set(counter, per_100m.round() as u64);
            }
        }
        c
    }

    /// The cascade count and the split's λ ([`knobs::setup_knobs`]).
    fn knobs(&self, variant: Variant) -> Vec<Knob> {
        knobs::setup_knobs(variant.setup(), self.setup(variant))
    }

    /// The next frame fits the new cascades (every frame does), into an
    /// array of the new shape (made once per shape); the shadow pass's
    /// texels are counted again.
    fn set_knob(
        &mut self,
        _gpu: &Gpu,
        _scene: &SceneGpu,
        variant: Variant,
        name: &str,
        value: f64,
    ) -> Result<()> {
        let v = &mut self.variants[variant];
        knobs::set_setup_knob(&mut v.setup, name, value)?;
        v.fitted = None;
        self.count_again(variant);
        Ok(())
    }

    /// The cascade each pixel samples (`<variant>_cascades.png`) and every
    /// cascade's map, light 0.
    fn write_extras(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        variant: Variant,
        out: &Path,
    ) -> Result<()> {
        let setup = self.setup(variant);
        let (Some(m), Some(p)) = (
            self.find_maps(setup.resolution, setup.count),
            self.pipelines.get(Shape::of(&setup)),
        ) else {
            return Ok(());
        };
        let (maps, groups) = &self.maps[m];
        let Some(group) = groups.first() else {
            return Ok(()); // no light: nothing to picture
        };
        let name = variant_name(variant);
        let path = out.join(format!("{name}_cascades.png"));
        extras::write_cascade_png(gpu, scene, &p.tint, group, &path)?;
        extras::write_layers(gpu, maps, out, &name)
    }
}

impl Csm {
    /// The runner's sub-texel move of every cascade's map (`--fragile`):
    /// each light's cascades `fits`, as `fit_cascades` uploaded them, are
    /// uploaded again moved, for the shadow passes and the lit pass alike
    /// (the later writes land last). Nothing unless the runner moves them.
    pub(super) fn jitter_cascades(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        setup: Setup,
        fits: &[Vec<Cascade>],
    ) {
        let jitter = scene.light_jitter.matrix(setup.resolution).as_dmat4();
        if jitter == common::glam::DMat4::IDENTITY {
            return;
        }
        let (b, size) = (&self.scene_box, (scene.width, scene.height));
        let lights = self.lights.iter_mut().zip(&self.params).enumerate();
        for ((light, (lights, params)), fit) in lights.zip(fits) {
            let mut moved = fit.clone();
            for c in &mut moved {
                c.view_proj = jitter * c.view_proj;
            }
            lights.write(gpu, scene, light, &moved);
            let p = setup.params(&scene.scene, b, size, &moved);
            gpu.queue.write_buffer(params, 0, bytemuck::bytes_of(&p));
        }
    }

    /// Draw calls of a frame whose shadow passes drew `casters` times: the
    /// base pass and each light's lit pass draw every object.
    pub(super) fn draws(&self, casters: u64) -> u64 {
        let lights = self.lights.len() as u64;
        self.objects * (1 + lights) + casters
    }

    /// Once per variant (and again after the runner or a knob moved
    /// something): this frame's caster draws, and, where the GPU can be
    /// waited on, its shadow passes' texels, in submits of their own that
    /// are left out of the frame's times.
    pub(super) fn count_once(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        setup: Setup,
        variant: Variant,
    ) -> Result<()> {
        if self.variants[variant].caster_draws.is_none() {
            let rects = self.kept.iter().flatten().flatten();
            self.variants[variant].caster_draws = Some(rects.map(|r| r.len() as u64).sum());
        }
        if self.variants[variant].texels_written.is_none() {
            let (size, k) = (setup.resolution, setup.count);
            // In a web page the count comes back a frame or more later.
            let n = frame.untimed(|gpu| later(|| self.count_texels(gpu, scene, size, k)))?;
            self.variants[variant].texels_written = n;
        }
        Ok(())
    }

    /// The shadow passes' depth writes and rasterised fragments over every
    /// light and cascade, counted through lesson 01's tally. Untimed.
    fn count_texels(&self, gpu: &Gpu, scene: &SceneGpu, size: u32, k: usize) -> Result<(u64, u64)> {
        let scratch = CascadeMaps::new(gpu, size, 1);
        let tally = Tally::new(gpu, size, size);
        let mut total = [0u64; 2];
        for (which, total) in total.iter_mut().enumerate() {
            for (lights, kept) in self.lights.iter().zip(&self.kept) {
                for (i, kept) in kept.iter().enumerate().take(k) {
                    let depth = wgpu::RenderPassDepthStencilAttachment {
                        view: &scratch.layer_views[0],
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Discard,
                        }),
                        stencil_ops: None,
                    };
                    *total += tally.count(gpu, Some(depth), |pass| {
                        pass.set_pipeline(&self.tally_pipeline[which]);
                        lights.bind(pass, i);
                        csm::draw_kept(pass, scene, kept);
                    })?;
                }
            }
        }
        Ok((total[0], total[1]))
    }
}
