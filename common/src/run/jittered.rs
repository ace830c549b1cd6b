//! The headless runner's `--fragile` frames: a variant drawn again with the
//! camera, the lights' shadow maps or the lights moved by less than two
//! rasterisers disagree on, against its measured frame
//! ([`crate::reference::fragile`] says what each move finds).

use std::collections::BTreeMap;

use anyhow::Result;

use crate::gpu::render::SceneGpu;
use crate::gpu::targets::{FrameImages, FrameTargets};
use crate::gpu::Gpu;
use crate::measure::timing::Timer;
use crate::reference::fragile::{self, JITTERS};
use crate::reference::Reference;
use crate::run::instruments::Instruments;

/// What a variant's measured frame gave, for [`fragile_of`].
pub struct Measured<'a> {
    pub reference: &'a Reference,
    pub images: &'a FrameImages,
    pub counters: &'a BTreeMap<String, u64>,
    pub classes: Option<&'a (Vec<String>, Vec<u8>)>,
}

/// The variant drawn again at each of [`JITTERS`], with the camera moved
/// by [`fragile::JITTER_PX`] of a pixel and every light's shadow map by
/// [`fragile::LIGHT_JITTER_TEXELS`] of a texel; where the lesson moved no
/// map (stencil volumes), 3 times more with every light turned
/// ([`fragile::turned_lights`]). Against the frame `measured`: which
/// receivers a rasteriser could flip, and how far each counter moved. The
/// camera, the maps and the lights are put back afterwards.
pub fn fragile_of<L: Instruments>(
    gpu: &Gpu,
    sg: &mut SceneGpu,
    targets: &FrameTargets,
    timer: &mut Timer,
    lesson: &mut L,
    variant: L::Variant,
    measured: Measured,
) -> Result<fragile::Fragile> {
    let (w, h) = (sg.width, sg.height);
    let mut moved = Moved::default();
    for [x, y] in JITTERS {
        let (px, texels) = (fragile::JITTER_PX, fragile::LIGHT_JITTER_TEXELS);
        sg.light_jitter.set([x * texels, y * texels]);
        sg.set_jitter(gpu, fragile::jitter_matrix([x * px, y * px], w, h));
        moved.draw(gpu, sg, targets, timer, lesson, variant)?;
    }
    let map_moved = sg.light_jitter.used();
    sg.light_jitter.set([0.0; 2]);
    sg.set_jitter(gpu, glam::Mat4::IDENTITY);
    sg.upload_uniforms(gpu);
    if !map_moved {
        let lights = sg.scene.lights.clone();
        let angle = fragile::light_turn(&sg.scene, h);
        for j in JITTERS {
            sg.scene.lights = lights.clone();
            sg.scene.lights = fragile::turned_lights(&sg.scene, angle, j);
            sg.upload_uniforms(gpu);
            moved.draw(gpu, sg, targets, timer, lesson, variant)?;
        }
        sg.scene.lights = lights;
        sg.upload_uniforms(gpu);
    }
    lesson.count_again(variant);
    Ok(moved.tally(sg, measured, map_moved))
}

/// The moved frames' images and counters.
#[derive(Default)]
struct Moved {
    images: Vec<FrameImages>,
    counters: Vec<BTreeMap<String, u64>>,
}

impl Moved {
    /// One moved frame of `variant`, counted again (some lessons count on
    /// their second frame).
    fn draw<L: Instruments>(
        &mut self,
        gpu: &Gpu,
        sg: &SceneGpu,
        targets: &FrameTargets,
        timer: &mut Timer,
        lesson: &mut L,
        variant: L::Variant,
    ) -> Result<()> {
        lesson.count_again(variant);
        for _ in 0..L::CAPABILITIES.counted_on_frame {
            let mut frame = timer.frame(gpu);
            lesson.render(&mut frame, sg, targets, variant)?;
            frame.finish()?;
        }
        self.images.push(targets.read(gpu)?);
        self.counters.push(lesson.counters(variant).to_report());
        Ok(())
    }

    /// The bounds ([`fragile::Tally`]) and the counters' moves, over every
    /// light.
    fn tally(&self, sg: &SceneGpu, measured: Measured, map_moved: bool) -> fragile::Fragile {
        let mut tally = match measured.classes {
            Some((names, _)) => fragile::Tally::with_classes(names),
            None => fragile::Tally::default(),
        };
        let class_of = measured.classes.map(|(_, c)| c.as_slice());
        fn at(f: &FrameImages, k: usize) -> fragile::Images<'_> {
            fragile::Images {
                id: &f.id,
                visibility: &f.visibility[k],
            }
        }
        for k in 0..sg.scene.lights.len() {
            let moved: Vec<fragile::Images> = self.images.iter().map(|f| at(f, k)).collect();
            let base = at(measured.images, k);
            tally.add(measured.reference, k, base, &moved, class_of);
        }
        let mut out = tally.finish(self.images.len(), map_moved);
        out.counters = fragile::counter_moves(measured.counters, &self.counters);
        out
    }
}
