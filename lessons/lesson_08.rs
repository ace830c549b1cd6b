//! # Lesson 08: depth bounds and scissor
//!
//! A point light of range r lights nothing outside its range sphere, yet
//! its shadow volumes run to infinity and cover much of the screen. Two
//! limits, both computed from the sphere, cut the volume pass's work:
//!
//! - a scissor rectangle: the sphere's image on screen (`set_scissor_rect`);
//! - depth bounds: the sphere's window-depth interval [zmin, zmax]. Where the
//!   depth *stored* at a pixel is outside it, the surface there is out of
//!   range and its count cannot matter. wgpu has no depth-bounds test, so
//!   it is emulated with stencil bit 7 (`common::depth_bounds`).
//!
//! Variants: `unbounded`, `scissor`, `depth_bounds`, `bounds_scissor`. The
//! pixels are the same in all four; the counters say how many volume
//! fragments each one rasterises and lets through to the stencil.
//!
//! Run: `cargo run --release --bin lesson_08 -- --headless`
//! Book: chapter "08 depth bounds" (`book/src/lesson_08.md`).

use std::collections::BTreeMap;

use common::app::{self, Lesson};
use common::depth_bounds::{self as db, BoundedVolumes, LightBounds, Limits};
use common::gpu::Gpu;
use common::render::{FrameTargets, SceneGpu};
use common::scene::{Far, LightKind, Scene};
use common::shadow_volume::{self, FarPlane, ShadowVolumes};
use common::timing::Frame;
use common::Result;

// ANCHOR: variants
const VARIANTS: [&str; 4] = ["unbounded", "scissor", "depth_bounds", "bounds_scissor"];

fn limits(variant: &str) -> Limits {
    Limits {
        scissor: variant.contains("scissor"),
        depth_bounds: variant.contains("bounds"),
    }
}
// ANCHOR_END: variants

// ANCHOR: light_bounds
/// Per light: `None` for a directional light (no range, no limits), else
/// the range sphere's bounds, `Some(None)` when it is off screen.
fn all_bounds(scene: &SceneGpu) -> Vec<Option<Option<LightBounds>>> {
    let (cam, s) = (&scene.camera, &scene.scene);
    let (view, proj) = (cam.view.as_dmat4(), cam.proj.as_dmat4());
    s.lights
        .iter()
        .map(|l| match l.kind {
            LightKind::Directional { .. } => None,
            LightKind::Point { position, range }
            | LightKind::Spot {
                position, range, ..
            } => {
                let centre = position - s.origin();
                Some(db::light_bounds(
                    view,
                    proj,
                    s.camera.near,
                    centre,
                    range,
                    scene.width,
                    scene.height,
                ))
            }
        })
        .collect()
}
// ANCHOR_END: light_bounds

struct DepthBounds {
    bounded: BoundedVolumes,
    volumes: ShadowVolumes,
    lit_pipeline: wgpu::RenderPipeline,
    bounds: Vec<Option<Option<LightBounds>>>,
    scene_counters: BTreeMap<String, u64>,
    counters: BTreeMap<String, BTreeMap<String, u64>>,
    frames: BTreeMap<String, u32>,
}

impl Lesson for DepthBounds {
    const NAME: &'static str = "lesson_08";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_08.toml");

    fn variants() -> Vec<String> {
        VARIANTS.iter().map(|v| v.to_string()).collect()
    }

    fn check_scene(scene: &Scene) -> Result<()> {
        if scene.camera.far != Far::Infinite {
            anyhow::bail!("camera.far: lesson_08 extrudes z-fail volumes to infinity; use far = \"infinite\" (lesson 07)");
        }
        Ok(())
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let volumes = ShadowVolumes::new(gpu, scene, FarPlane::Clip)?;
        let module = shadow_volume::volume_shader_module(
            gpu,
            "lesson_08",
            include_str!("../shaders/lesson_08.wgsl"),
        );
        Ok(DepthBounds {
            bounded: BoundedVolumes::new(gpu, scene, &volumes)?,
            lit_pipeline: scene.lit_pipeline(
                gpu,
                &module,
                "fs_lit_range",
                &[],
                db::bounded_lit_stencil(),
            ),
            bounds: all_bounds(scene),
            scene_counters: shadow_volume::scene_counters(scene),
            volumes,
            counters: BTreeMap::new(),
            frames: BTreeMap::new(),
        })
    }

    // ANCHOR: render
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: &str,
    ) -> Result<()> {
        if !VARIANTS.contains(&variant) {
            anyhow::bail!("unknown variant {variant}");
        }
        let lim = limits(variant);
        // Per frame: the sphere → bounds and scissor of every light.
        let bounds = frame.cpu("bounds", || all_bounds(scene));
        for (k, b) in bounds.iter().enumerate() {
            if let Some(Some(b)) = b {
                self.bounded.write_bounds(frame.gpu, k, b);
            }
        }
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for (light, &b) in bounds.iter().enumerate() {
            frame.pass("volume", |enc, ts| {
                self.bounded
                    .volume_pass(enc, scene, targets, light, b, lim, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(enc, targets, light, &self.lit_pipeline, &[], 0, ts.render())
            });
        }
        self.bounds = bounds;
        // The second call finds the first frame's depth in place: count then.
        let n = self.frames.entry(variant.to_string()).or_default();
        *n += 1;
        if *n == 2 {
            self.count(frame.gpu, scene, targets, variant)?;
        }
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, variant: &str) -> BTreeMap<String, u64> {
        let mut c = self.scene_counters.clone();
        c.extend(self.counters.get(variant).cloned().unwrap_or_default());
        c
    }
}

impl DepthBounds {
    // ANCHOR: count
    /// The counters: fragments that reach the stencil update (occlusion
    /// queries; not on GL, where they only say "any"), fragments rasterised
    /// (pipeline statistics, where the adapter has them), the scissor area.
    fn count(
        &mut self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: &str,
    ) -> Result<()> {
        let lim = limits(variant);
        let mut c = BTreeMap::new();
        if let Some(s) =
            self.bounded
                .count_stencil_fragments(gpu, scene, targets, &self.bounds, lim)?
        {
            c.insert("stencil_fragments".to_string(), s.iter().sum());
        }
        let raster = self.bounded.count_rasterised(
            gpu,
            scene,
            self.volumes.counter(),
            &self.bounds,
            lim.scissor,
        );
        if let Some(r) = raster {
            c.insert("volume_fragments".to_string(), r);
        }
        let full = scene.width as u64 * scene.height as u64;
        let area = |b: &Option<Option<LightBounds>>| match b {
            Some(Some(b)) if lim.scissor => b.scissor.area(),
            Some(None) if lim.scissor => 0,
            _ => full,
        };
        c.insert(
            "scissor_pixels".to_string(),
            self.bounds.iter().map(area).sum(),
        );
        // Which extreme cases this camera meets (range sphere in view space).
        let (view, near) = (scene.camera.view.as_dmat4(), scene.scene.camera.near);
        let (mut inside, mut crossing) = (0, 0);
        for l in &scene.scene.lights {
            if let LightKind::Point { position, range }
            | LightKind::Spot {
                position, range, ..
            } = l.kind
            {
                let v = view.transform_point3(position - scene.scene.origin());
                inside += (v.length() <= range) as u64;
                crossing += (v.length() > range && v.z + range > -near) as u64;
            }
        }
        c.insert("lights_around_camera".to_string(), inside);
        c.insert("lights_crossing_near_plane".to_string(), crossing);
        c.insert(
            "lights_culled".to_string(),
            self.bounds
                .iter()
                .filter(|b| lim != Limits::default() && **b == Some(None))
                .count() as u64,
        );
        self.counters.insert(variant.to_string(), c);
        Ok(())
    }
    // ANCHOR_END: count
}

fn main() -> std::process::ExitCode {
    app::main::<DepthBounds>()
}
