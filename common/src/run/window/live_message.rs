//! What the web page and its reference worker send each other
//! ([`super::live_page`], [`super::live_worker`]). The worker loads the
//! lesson's scene itself, from the page's own flags, so a job carries only
//! what the window changes (the camera and the lights) beside the frame's
//! images (each pixel's object id, and one visibility image per light);
//! an answer carries its figure and its two images (the difference image
//! and the signed ΔV image of light 0).
//! Headers go as JSON, the arrays as typed arrays moved, not copied,
//! between the two threads.

use anyhow::{bail, Result};
use image::RgbaImage;

use super::live_job::{Answer, Job, Level, Stamp};
use crate::gpu::targets::FrameImages;
use crate::reference::metrics::ErrorStats;
use crate::scene::{Camera, Light, Scene};

/// A job, less its arrays.
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JobHeader {
    pub stamp: Stamp,
    pub view_proj: [f32; 16],
    pub camera: Camera,
    pub lights: Vec<Light>,
    pub width: u32,
    pub height: u32,
}

impl JobHeader {
    pub fn of(job: &Job) -> JobHeader {
        JobHeader {
            stamp: job.stamp,
            view_proj: job.view_proj.to_cols_array(),
            camera: job.scene.camera.clone(),
            lights: job.scene.lights.clone(),
            width: job.frame.width,
            height: job.frame.height,
        }
    }

    /// The job on the worker's side: its own copy of the lesson's scene
    /// (`base`) with the window's camera and lights, and the frame's arrays
    /// (one visibility image per light).
    pub fn into_job(self, base: &Scene, id: Vec<u32>, visibility: Vec<Vec<f32>>) -> Result<Job> {
        let pixels = self.width as usize * self.height as usize;
        if base.lights.len() != self.lights.len() {
            bail!(
                "the page's scene has {} lights, the reference worker's {}: not the same scene",
                self.lights.len(),
                base.lights.len()
            );
        }
        if id.len() != pixels || visibility.iter().any(|v| v.len() != pixels) {
            bail!(
                "a {}×{} frame came with {} ids and visibility images of {:?} pixels",
                self.width,
                self.height,
                id.len(),
                visibility.iter().map(Vec::len).collect::<Vec<_>>()
            );
        }
        let mut scene = base.clone();
        scene.camera = self.camera;
        scene.lights = self.lights;
        Ok(Job {
            stamp: self.stamp,
            scene,
            view_proj: glam::Mat4::from_cols_array(&self.view_proj),
            frame: FrameImages {
                width: self.width,
                height: self.height,
                color: Vec::new(),
                id,
                visibility,
            },
        })
    }
}

/// An answer, less its images.
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct AnswerHeader {
    pub stamp: Stamp,
    pub level: Level,
    pub error: ErrorStats,
    pub ms: f64,
    pub last: bool,
    /// The size of both images (a coarse answer's are the coarse pass's).
    pub width: u32,
    pub height: u32,
}

impl AnswerHeader {
    pub fn of(a: &Answer) -> AnswerHeader {
        AnswerHeader {
            stamp: a.stamp,
            level: a.level,
            error: a.error.clone(),
            ms: a.ms,
            last: a.last,
            width: a.diff.width(),
            height: a.diff.height(),
        }
    }

    /// The answer, its difference and ΔV images' RGBA bytes given back.
    pub fn into_answer(self, diff: Vec<u8>, dv: Vec<u8>) -> Result<Answer> {
        let image = |bytes: Vec<u8>, what: &str| {
            let n = bytes.len();
            RgbaImage::from_raw(self.width, self.height, bytes).ok_or_else(|| {
                anyhow::anyhow!(
                    "the {what} image of a {}×{} answer came with {n} bytes",
                    self.width,
                    self.height
                )
            })
        };
        Ok(Answer {
            stamp: self.stamp,
            level: self.level,
            error: self.error.clone(),
            diff: image(diff, "difference")?,
            dv: image(dv, "ΔV")?,
            ms: self.ms,
            last: self.last,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::window::live_server::Server;

    const SCENE: &str = r#"
        [camera]
        eye = [0.0, 4.0, 6.0]
        target = [0.0, 0.0, 0.0]
        fov_y_deg = 50.0
        [[lights]]
        type = "directional"
        direction = [-0.3, -1.0, -0.2]
        [[objects]]
        mesh = "plane"
        scale = [8.0, 1.0, 8.0]
        [[objects]]
        mesh = "cube"
        translate = [0.0, 1.0, 0.0]
    "#;

    /// The window's job, moved camera and light included, reaches the
    /// worker whole, and its answers come back whole: the worker, given
    /// the page's scene as loaded, answers what the window's own server
    /// would.
    #[test]
    fn a_job_and_its_answers_cross_to_the_worker_and_back() {
        let base = Scene::parse(SCENE, "test", std::path::Path::new(".")).unwrap();
        let mut scene = base.clone();
        scene.camera.eye = glam::DVec3::new(1.0, 3.0, 5.0);
        if let crate::scene::LightKind::Directional { direction } = &mut scene.lights[0].kind {
            *direction = glam::DVec3::new(0.2, -1.0, 0.1).normalize();
        }
        let (w, h) = (16u32, 12u32);
        let view_proj = crate::scene::camera::camera_matrices(&scene, w, h).view_proj;
        let reference = crate::reference::try_render_reference(&scene, view_proj, w, h).unwrap();
        // The frame: the reference's own ids and visibility, one receiver wrong.
        let id: Vec<u32> = (reference.hits.iter())
            .map(|hit| hit.map_or(0, |hit| hit.object + 1))
            .collect();
        let mut visibility: Vec<f32> = reference.visibility[0].clone();
        let p = id.iter().position(|&i| i != 0).unwrap();
        visibility[p] = 1.0 - visibility[p];
        let frame = || FrameImages {
            width: w,
            height: h,
            color: Vec::new(),
            id: id.clone(),
            visibility: vec![visibility.clone()],
        };
        let stamp = Stamp {
            scene_gen: 7,
            image_gen: 9,
        };
        let job = Job {
            stamp,
            scene: scene.clone(),
            view_proj,
            frame: frame(),
        };

        let header = JobHeader::of(&job);
        let wire: JobHeader =
            serde_json::from_str(&serde_json::to_string(&header).unwrap()).unwrap();
        assert_eq!(wire, header);
        let crossed = wire
            .into_job(&base, frame().id, frame().visibility)
            .unwrap();
        assert_eq!(crossed.scene.camera, scene.camera);
        assert_eq!(crossed.scene.lights, scene.lights);
        assert_eq!(crossed.view_proj, view_proj);

        let (mut here, mut there) = (Server::default(), Server::default());
        for (a, b) in [
            (here.take(job).unwrap(), there.take(crossed).unwrap()),
            (here.full().unwrap(), there.full().unwrap()),
        ] {
            let header = AnswerHeader::of(&b);
            let wire: AnswerHeader =
                serde_json::from_str(&serde_json::to_string(&header).unwrap()).unwrap();
            let back = wire
                .into_answer(b.diff.into_raw(), b.dv.into_raw())
                .unwrap();
            assert_eq!(
                (back.stamp, back.level, back.last),
                (a.stamp, a.level, a.last)
            );
            assert_eq!(back.error, a.error);
            assert_eq!(back.diff, a.diff);
            assert_eq!(back.dv, a.dv);
        }
    }

    /// A frame of the wrong size, or a scene with another number of
    /// lights, is refused with a line, not compared.
    #[test]
    fn a_job_that_does_not_fit_the_workers_scene_is_refused() {
        let base = Scene::parse(SCENE, "test", std::path::Path::new(".")).unwrap();
        let header = |lights: Vec<Light>| JobHeader {
            stamp: Stamp {
                scene_gen: 1,
                image_gen: 1,
            },
            view_proj: glam::Mat4::IDENTITY.to_cols_array(),
            camera: base.camera.clone(),
            lights,
            width: 4,
            height: 2,
        };
        let e = header(base.lights.clone()).into_job(&base, vec![0; 7], vec![vec![0.0; 8]]);
        let e = e.err().expect("refused");
        assert!(
            format!("{e:#}").contains("4×2 frame came with 7 ids"),
            "{e:#}"
        );
        let two = vec![base.lights[0]; 2];
        let e = header(two).into_job(&base, vec![0; 8], vec![vec![0.0; 8]; 2]);
        let e = e.err().expect("refused");
        assert!(format!("{e:#}").contains("has 2 lights"), "{e:#}");
    }
}
