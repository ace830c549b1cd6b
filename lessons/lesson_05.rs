//! # Lesson 05: z-pass stencil shadow volumes
//!
//! Each caster's silhouette, seen from the light, is extruded to infinity
//! (w = 0) into a closed *shadow volume*. Counting, along the view ray, the
//! volume faces in front of the visible surface (front faces +1, back
//! faces −1) gives the number of volumes the surface is inside: 0 is lit.
//! Exact while the eye is outside every volume; the report measures what
//! happens when it is not (`--scene scenes/volume_eye_in_umbra.toml`).
//!
//! Two ways to build the volumes, timed against each other: silhouettes on
//! the CPU every frame (`zpass_cpu`), and degenerate quads built once and
//! extruded in the vertex shader (`zpass_quads`).
//!
//! Run: `cargo run --release --bin lesson_05 -- --headless`
//! Book: chapter "05 z-pass stencil shadow volumes" (`book/src/lesson_05.md`).

use std::collections::BTreeMap;

use common::app::{self, Lesson};
use common::gpu::Gpu;
use common::render::{FrameTargets, SceneGpu};
use common::shadow_volume::{self, CasterDraw, Extrusion, FarPlane, Method, ShadowVolumes};
use common::timing::Frame;
use common::Result;

// ANCHOR: variants
/// The variants differ in how the volume geometry is built, not in what
/// it is: both count with z-pass.
fn extrusion(variant: &str) -> Option<Extrusion> {
    match variant {
        "zpass_cpu" => Some(Extrusion::Cpu),
        "zpass_quads" => Some(Extrusion::Quads),
        _ => None,
    }
}
// ANCHOR_END: variants

struct ZPass {
    volumes: ShadowVolumes,
    lit_pipeline: wgpu::RenderPipeline,
    /// `draws[light]`: every caster, z-pass, sides only.
    draws: Vec<Vec<CasterDraw>>,
    /// Computed once: mesh validation and the largest stencil count.
    scene_counters: BTreeMap<String, u64>,
    fragments: Option<u64>,
    casters_drawn: u64,
}

impl Lesson for ZPass {
    const NAME: &'static str = "lesson_05";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_05.toml");

    fn variants() -> Vec<String> {
        vec!["zpass_cpu".into(), "zpass_quads".into()]
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let volumes = ShadowVolumes::new(gpu, scene, FarPlane::Clip)?;
        let draws = vec![volumes.all(Method::ZPass); scene.scene.lights.len()];
        Ok(ZPass {
            lit_pipeline: shadow_volume::stencil_lit_pipeline(gpu, scene),
            scene_counters: shadow_volume::scene_counters(scene),
            volumes,
            draws,
            fragments: None,
            casters_drawn: 0,
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
        let ext = extrusion(variant).ok_or_else(|| anyhow::anyhow!("unknown variant {variant}"))?;
        if ext == Extrusion::Cpu {
            // Doom 3's way: find every silhouette on the CPU, every frame.
            self.volumes.prepare_cpu(frame, scene, &self.draws);
        }
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        let mut drawn = 0;
        for light in 0..scene.scene.lights.len() {
            let draws = &self.draws[light];
            // Clear the stencil, count the volumes into it...
            drawn += frame.pass("volume", |enc, ts| {
                self.volumes
                    .volume_pass(enc, scene, targets, light, ext, draws, ts.render())
            });
            // ...and add the light where the count is 0.
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(enc, targets, light, &self.lit_pipeline, &[], 0, ts.render())
            });
        }
        self.casters_drawn = drawn as u64;
        self.fragments = self
            .volumes
            .count_fragments(frame.gpu, scene, ext, &self.draws);
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, _variant: &str) -> BTreeMap<String, u64> {
        let mut c = self.scene_counters.clone();
        c.insert("casters_drawn".into(), self.casters_drawn);
        if let Some(f) = self.fragments {
            c.insert("volume_fragments".into(), f);
        }
        c
    }
}

fn main() -> std::process::ExitCode {
    app::main::<ZPass>()
}
