//! # Lesson 07: depth clamp and infinite extrusion
//!
//! Z-fail (lesson 06) counts volume faces *behind* the visible surface, out
//! to the back cap, which lies at infinity (w = 0). A finite far plane clips
//! it away, and the counts come out wrong. Two cures, compared here:
//!
//! - `clamp`: keep the finite projection but clamp depth instead of
//!   clipping it (`unclipped_depth`, wgpu's `DEPTH_CLIP_CONTROL`, the
//!   GL_DEPTH_CLAMP of the original technique). Lavapipe has it; llvmpipe
//!   over GL does not, and there the variant fails with one line naming it.
//! - `infinite`: move the far plane to infinity (Everitt & Kilgard), with an
//!   ε that keeps points at infinity strictly inside depth 1.
//!
//! `neither` shows the failure. The lesson also measures what each choice
//! costs in depth precision (`depth_precision.md/.csv/.png`).
//!
//! Run: `cargo run --release --bin lesson_07 -- --headless`
//! Book: chapter "07 depth clamp and infinite extrusion" (`book/src/lesson_07.md`).

use std::cell::Cell;
use std::collections::BTreeMap;
use std::path::Path;

use common::app::{self, Lesson};
use common::depth_precision::{self as dp, DepthFormat, DepthMapping, INFINITE_EPSILON};
use common::glam::dcamera::rh::view::look_at_mat4;
use common::gpu::Gpu;
use common::render::{FrameTargets, SceneGpu};
use common::scene::{Far, Scene};
use common::shadow_volume::{self, CasterDraw, Extrusion, FarPlane, Method, ShadowVolumes};
use common::timing::Frame;
use common::{anyhow, Result};

// ANCHOR: variants
/// The three ways to treat the back cap at infinity.
const VARIANTS: [&str; 3] = ["neither", "clamp", "infinite"];

/// The depth mapping each variant's camera uses.
fn mapping(variant: &str) -> DepthMapping {
    if variant == "infinite" {
        DepthMapping::Infinite
    } else {
        DepthMapping::Standard
    }
}
// ANCHOR_END: variants

// ANCHOR: infinite_camera
/// The scene's camera with its far plane moved to infinity (with ε).
/// A second `SceneGpu` holds it: its own camera uniform, the same objects.
fn infinite_scene(gpu: &Gpu, scene: &SceneGpu) -> Result<SceneGpu> {
    let mut s = SceneGpu::new(gpu, scene.scene.clone(), scene.width, scene.height)?;
    let c = &s.scene.camera;
    let o = s.scene.origin();
    let view = look_at_mat4(c.eye - o, c.target - o, c.up);
    let aspect = s.width as f64 / s.height as f64;
    let proj = dp::infinite_perspective(c.fov_y_deg.to_radians(), aspect, c.near, INFINITE_EPSILON);
    s.camera.proj = proj.as_mat4();
    s.camera.view_proj = (proj * view).as_mat4();
    s.upload_uniforms(gpu);
    Ok(s)
}
// ANCHOR_END: infinite_camera

/// One way of drawing: the scene (camera), its volumes and lit pipeline.
struct Route {
    volumes: ShadowVolumes,
    lit: wgpu::RenderPipeline,
}

impl Route {
    fn new(gpu: &Gpu, scene: &SceneGpu, far: FarPlane) -> Result<Route> {
        Ok(Route {
            volumes: ShadowVolumes::new(gpu, scene, far)?,
            lit: shadow_volume::stencil_lit_pipeline(gpu, scene),
        })
    }
}

struct DepthClamp {
    finite: Route,
    /// `Err` (one line) where the adapter lacks DEPTH_CLIP_CONTROL.
    clamp: std::result::Result<Route, String>,
    infinite_scene: SceneGpu,
    infinite: Route,
    scene_counters: BTreeMap<String, u64>,
    /// Per variant: fragments rasterised (pipeline statistics) and precision.
    counters: BTreeMap<String, BTreeMap<String, u64>>,
    study_written: Cell<bool>,
}

/// Relative gap in parts per billion; 10⁹ means "not even Δd = d resolves".
fn ppb(g: Option<f64>) -> u64 {
    g.map_or(1_000_000_000, |g| (g * 1e9).round() as u64)
}

impl Lesson for DepthClamp {
    const NAME: &'static str = "lesson_07";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_07.toml");

    fn variants() -> Vec<String> {
        VARIANTS.iter().map(|v| v.to_string()).collect()
    }

    fn check_scene(scene: &Scene) -> Result<()> {
        if scene.camera.far == Far::Infinite {
            anyhow::bail!("camera.far: lesson_07 compares a finite far plane with clamping and an infinite one; give a finite far");
        }
        Ok(())
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let infinite_scene = infinite_scene(gpu, scene)?;
        let clamp = Route::new(gpu, scene, FarPlane::Unclipped).map_err(|e| {
            format!("variant \"clamp\" needs unclipped_depth: {e}; run --variant neither --variant infinite")
        });
        // Depth precision for this scene's near/far, each variant's mapping.
        let Far::Finite(far) = scene.scene.camera.far else {
            unreachable!("checked")
        };
        let near = scene.scene.camera.near;
        let format = if scene.depth_format == DepthFormat::D32F.wgpu() {
            DepthFormat::D32F
        } else {
            DepthFormat::D24
        };
        let mut counters = BTreeMap::new();
        for v in VARIANTS {
            let row = dp::study_one(gpu, format, mapping(v), near, far)?;
            let n = row.distances.len();
            let c: BTreeMap<String, u64> = [
                (
                    "depth_gap_ppb_at_sqrt_near_far".to_string(),
                    ppb(row.best(n - 2)),
                ),
                (
                    "depth_gap_ppb_at_half_far".to_string(),
                    ppb(row.best(n - 1)),
                ),
            ]
            .into();
            counters.insert(v.to_string(), c);
        }
        Ok(DepthClamp {
            finite: Route::new(gpu, scene, FarPlane::Clip)?,
            clamp,
            infinite: Route::new(gpu, &infinite_scene, FarPlane::Clip)?,
            infinite_scene,
            scene_counters: shadow_volume::scene_counters(scene),
            counters,
            study_written: Cell::new(false),
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
        let (sg, route) = match variant {
            "neither" => (scene, &self.finite),
            "clamp" => (
                scene,
                self.clamp.as_ref().map_err(|e| anyhow::anyhow!("{e}"))?,
            ),
            "infinite" => (&self.infinite_scene, &self.infinite),
            _ => anyhow::bail!("unknown variant {variant}"),
        };
        // Z-fail everywhere, both caps: the back cap is the one at infinity.
        let draws: Vec<Vec<CasterDraw>> = (0..sg.scene.lights.len())
            .map(|_| route.volumes.all(Method::ZFail))
            .collect();
        frame.pass("base", |enc, ts| sg.base_pass(enc, targets, ts.render()));
        for (light, d) in draws.iter().enumerate() {
            frame.pass("volume", |enc, ts| {
                route
                    .volumes
                    .volume_pass(enc, sg, targets, light, Extrusion::Quads, d, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                sg.lit_pass(enc, targets, light, &route.lit, &[], 0, ts.render())
            });
        }
        let c = self.counters.entry(variant.to_string()).or_default();
        if !c.contains_key("casters_drawn") {
            c.insert(
                "casters_drawn".into(),
                draws.iter().map(|d| d.len() as u64).sum(),
            );
            if let Some(f) = route
                .volumes
                .count_fragments(frame.gpu, sg, Extrusion::Quads, &draws)
            {
                c.insert("volume_fragments".into(), f);
            }
        }
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, variant: &str) -> BTreeMap<String, u64> {
        let mut c = self.scene_counters.clone();
        c.extend(self.counters.get(variant).cloned().unwrap_or_default());
        c
    }

    // ANCHOR: precision_study
    /// The depth-precision study, once per run: both formats, four
    /// mappings, far/near from 1e2 to 1e8 (near = 1e-3).
    fn write_extras(&self, gpu: &Gpu, _scene: &SceneGpu, _variant: &str, out: &Path) -> Result<()> {
        if self.study_written.replace(true) {
            return Ok(());
        }
        let rows = dp::study(gpu, 1e-3, &[1e2, 1e4, 1e6, 1e8])?;
        let write = |name: &str, text: String| {
            std::fs::write(out.join(name), text)
                .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", out.join(name).display()))
        };
        write("depth_precision.csv", dp::csv(&rows))?;
        write("depth_precision.md", dp::markdown(&rows))?;
        app::save(&dp::grid_image(&rows, 3), &out.join("depth_precision.png"))
    }
    // ANCHOR_END: precision_study
}

fn main() -> std::process::ExitCode {
    app::main::<DepthClamp>()
}
