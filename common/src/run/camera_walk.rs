//! The camera path's walk (a scene's `[camera_path]`, chapter 09's
//! shimmer): a variant rendered at each camera of the path, untimed, and
//! its flips from frame to frame counted against the reference's.

use anyhow::Result;

use crate::gpu::render::SceneGpu;
use crate::gpu::targets::{FrameImages, FrameTargets};
use crate::gpu::Gpu;
use crate::measure::report::CameraPathReport;
use crate::measure::timing::Timer;
use crate::reference::cache;
use crate::reference::metrics::{pixel_states, PixelState, ReferenceStates};
use crate::run::instruments::Instruments;
use crate::scene::camera_path::{path_cameras, CameraPath, Shimmer};

/// Every light's [`PixelState`]s of a frame's images.
pub(crate) fn light_states(
    reference: &ReferenceStates,
    images: &FrameImages,
) -> Vec<Vec<PixelState>> {
    let lights = images.visibility.iter();
    let states = lights
        .enumerate()
        .map(|(k, vis)| pixel_states(reference, k, &images.id, vis));
    states.collect()
}

/// What rendering a variant along the scene's camera path needs.
pub(crate) struct PathWalk<'a> {
    pub gpu: &'a Gpu,
    pub sg: &'a mut SceneGpu,
    pub targets: &'a FrameTargets,
    pub timer: &'a mut Timer,
    /// The reference of each frame so far, and which of its pixels' surfaces
    /// the next frame's view holds: the same for every variant.
    pub references: &'a mut Vec<(ReferenceStates, Vec<bool>)>,
}

impl PathWalk<'_> {
    /// Renders `variant` at each camera of `path` (untimed), counts its
    /// flips against the reference's, and puts the scene's camera back.
    pub(crate) fn measure<L: Instruments>(
        &mut self,
        lesson: &mut L,
        variant: L::Variant,
        path: &CameraPath,
    ) -> Result<(CameraPathReport, Shimmer)> {
        let base = self.sg.scene.camera.clone();
        let mut shimmer = Shimmer::new(self.sg.width, self.sg.height);
        let cameras = path_cameras(&base, path);
        let walked = (0..cameras.len()).try_for_each(|i| {
            let next = cameras.get(i + 1);
            let states = self.frame_at(&cameras[i], next, i, lesson, variant)?;
            if let Some(next) = next {
                // The probe: this view, the next frame's fit.
                let probe = self.probe(next, i, lesson, variant)?;
                shimmer.add_probe(&states, &probe, &self.references[i].1);
            }
            shimmer.add_frame(states);
            Ok::<(), anyhow::Error>(())
        });
        self.sg.scene.camera = base;
        self.sg.set_camera(self.gpu);
        walked?;
        Ok((shimmer.report(), shimmer))
    }

    /// Path frame `i`, seen from `camera`: every light's pixel states.
    /// The first variant also makes the frame's reference, and marks the
    /// pixels whose surface `next`'s view holds too.
    fn frame_at<L: Instruments>(
        &mut self,
        camera: &crate::scene::Camera,
        next: Option<&crate::scene::Camera>,
        i: usize,
        lesson: &mut L,
        variant: L::Variant,
    ) -> Result<Vec<Vec<PixelState>>> {
        let sg = &mut *self.sg;
        sg.scene.camera = camera.clone();
        sg.set_camera(self.gpu);
        if self.references.len() == i {
            let r = cache::reference(&sg.scene, sg.camera.view_proj, sg.width, sg.height)?;
            let seen = match next {
                Some(next) => {
                    sg.scene.camera = next.clone();
                    let m = crate::scene::camera::camera_matrices(&sg.scene, sg.width, sg.height);
                    sg.scene.camera = camera.clone();
                    in_view(&r, m.view_proj)
                }
                None => Vec::new(),
            };
            self.references.push((ReferenceStates::new(&r), seen));
        }
        self.render_states(i, lesson, variant)
    }

    /// The probe after frame `i`: frame `i`'s view (its matrices stay in
    /// the scene's uniforms), the lesson fitting to `next` (the scene's
    /// camera, which the lessons with `Capabilities::camera_path` re-read every frame).
    fn probe<L: Instruments>(
        &mut self,
        next: &crate::scene::Camera,
        i: usize,
        lesson: &mut L,
        variant: L::Variant,
    ) -> Result<Vec<Vec<PixelState>>> {
        self.sg.scene.camera = next.clone();
        self.render_states(i, lesson, variant)
    }

    /// Renders one untimed frame and reads every light's pixel states
    /// against path frame `i`'s reference.
    fn render_states<L: Instruments>(
        &mut self,
        i: usize,
        lesson: &mut L,
        variant: L::Variant,
    ) -> Result<Vec<Vec<PixelState>>> {
        let mut frame = self.timer.frame(self.gpu);
        lesson.render(&mut frame, self.sg, self.targets, variant)?;
        frame.finish()?;
        let images = self.targets.read(self.gpu)?;
        Ok(light_states(&self.references[i].0, &images))
    }
}

/// Per pixel of `r`: its surface projects inside the view of `view_proj`
/// (origin-relative), in front of the eye.
fn in_view(r: &crate::reference::Reference, view_proj: glam::Mat4) -> Vec<bool> {
    r.hits
        .iter()
        .map(|h| {
            h.as_ref().is_some_and(|h| {
                let c = view_proj * h.position.extend(1.0);
                c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w
            })
        })
        .collect()
}
