//! # Lesson 07: depth clamp and infinite extrusion
//!
//! Z-fail (lesson 06) counts volume faces *behind* the visible surface, out
//! to the back cap, which lies at infinity (w = 0). A finite far plane clips
//! it away, and the counts come out wrong. Two cures, compared here:
//!
//! - `clamp`: keep the finite projection but clamp depth instead of
//!   clipping it (`unclipped_depth`, wgpu's `DEPTH_CLIP_CONTROL`, the
//!   GL_DEPTH_CLAMP of the original technique). Where the adapter lacks
//!   it, the variant fails with one line naming it.
//! - `infinite`: move the far plane to infinity (Everitt & Kilgard), with an
//!   ε that keeps points at infinity strictly inside depth 1
//!   ([`infinite_far`](workbook::lesson_07::infinite_far)).
//!
//! `neither` shows the failure. The lesson also measures what each choice
//! costs in depth precision ([`precision_study`](workbook::lesson_07::precision_study):
//! `depth_precision.md/.csv/.png/.svg`), and `reversed_z` keeps the far
//! plane at infinity with reversed depth in Depth32Float
//! ([`reversed_z`](workbook::lesson_07::reversed_z)), exact on deep ranges.
//!
//! Run: `cargo run --release --bin lesson_07 -- --headless`
//! Book: chapter "07 depth clamp and infinite extrusion" (`book/src/lesson_07.md`).

use std::cell::Cell;
use std::collections::BTreeMap;
use std::path::Path;

use clap::ValueEnum;
use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::run::files::save;
use common::run::lesson::{is_exercise, BufferView, Lesson};
use common::scene::{Far, Scene};
use common::{anyhow, Result};
use workbook::lesson_05::count_view::count_view;
use workbook::lesson_05::extrusion::Extrusion;
use workbook::lesson_05::stencil::{self, Counting};
use workbook::lesson_05::volumes::{base_and_lit_draws, CasterDraw, ShadowVolumes};
use workbook::lesson_06::caps::{self, zfail_counting};
use workbook::lesson_07::exercise_cameras as cameras;
use workbook::lesson_07::infinite_far::{infinite_scene, DepthMapping};
use workbook::lesson_07::precision_study::{self as study, DepthFormat};
use workbook::lesson_07::precision_table;
use workbook::lesson_07::reversed_z::ReversedZ;

// ANCHOR: variants
/// The three ways to treat the back cap at infinity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Variant {
    /// A finite far plane clips the back cap.
    #[value(name = "neither")]
    Neither,
    /// Depth clamped instead of clipped.
    #[value(name = "clamp")]
    Clamp,
    /// The far plane at infinity.
    #[value(name = "infinite")]
    Infinite,
    /// Reversed-Z in Depth32Float, far plane at infinity.
    #[value(name = "reversed_z")]
    ReversedZ,
    // ANCHOR_END: variants
    /// Exercise 1: your off-centre infinite projection (`exercises::infinite_frustum`).
    #[value(name = "exercise_infinite_projection")]
    ExerciseInfiniteProjection,
    /// Exercise 2: the infinite far plane, near fitted to the scene
    /// (`exercises::adaptive_near`).
    #[value(name = "exercise_adaptive_near")]
    ExerciseAdaptiveNear,
}

impl Variant {
    /// The depth mapping of the variant's camera.
    fn mapping(self) -> DepthMapping {
        match self {
            Variant::Infinite => DepthMapping::Infinite,
            Variant::ReversedZ => DepthMapping::InfiniteReversed,
            Variant::Neither | Variant::Clamp => DepthMapping::Standard,
            Variant::ExerciseInfiniteProjection | Variant::ExerciseAdaptiveNear => {
                DepthMapping::Infinite
            }
        }
    }

    /// The exercise's slot in `DepthClamp::exercises`, and its camera.
    fn exercise(self) -> Option<(usize, ExerciseCamera)> {
        match self {
            Variant::ExerciseInfiniteProjection => Some((0, cameras::infinite_projection_scene)),
            Variant::ExerciseAdaptiveNear => Some((1, cameras::adaptive_near_scene)),
            _ => None,
        }
    }
}

/// Makes an exercise's camera: a second `SceneGpu` with its projection.
type ExerciseCamera = fn(&Gpu, &SceneGpu) -> Result<SceneGpu>;

/// One way of drawing: the scene (camera), its volumes and lit pipeline.
struct Route {
    volumes: ShadowVolumes,
    lit: wgpu::RenderPipeline,
}

// ANCHOR: render
/// One frame of lesson 06's z-fail with pre-built quads, both caps for
/// every caster, seen through `sg`'s camera and drawn with `route`'s
/// volumes: lesson 05's frame. Returns the draws, per light.
fn zfail_frame(
    frame: &mut Frame,
    sg: &SceneGpu,
    targets: &FrameTargets,
    route: &mut Route,
) -> Result<Vec<Vec<CasterDraw>>> {
    // Z-fail everywhere, both caps: the back cap is the one at infinity.
    let draws: Vec<Vec<CasterDraw>> = (0..sg.scene.lights.len())
        .map(|_| route.volumes.all(caps::zfail))
        .collect();
    let (ext, lit) = (Extrusion::Quads, &route.lit);
    (route.volumes).shadow_frame(frame, sg, targets, ext, &draws, lit)?;
    Ok(draws)
}
// ANCHOR_END: render

impl Route {
    /// Z-fail volumes; `unclipped_depth` clamps depth instead of clipping.
    fn new(gpu: &Gpu, scene: &SceneGpu, unclipped_depth: bool) -> Result<Route> {
        let counting = Counting {
            unclipped_depth,
            ..zfail_counting()
        };
        let volumes = ShadowVolumes::new(gpu, scene, &counting)?;
        if let Some(why) = volumes.unfit(Extrusion::Quads) {
            // Every variant here draws the quads.
            anyhow::bail!("{why}: lesson_05's zpass_cpu builds volumes this size");
        }
        Ok(Route {
            volumes,
            lit: stencil::stencil_lit_pipeline(gpu, scene),
        })
    }
}

struct DepthClamp {
    finite: Route,
    /// `Err` (one line) where the adapter lacks DEPTH_CLIP_CONTROL.
    clamp: std::result::Result<Route, String>,
    infinite_scene: SceneGpu,
    infinite: Route,
    /// `Err` (one line) where the adapter lacks Depth32FloatStencil8.
    reversed: std::result::Result<ReversedZ, String>,
    scene_counters: BTreeMap<String, u64>,
    /// Per variant, in variant order: fragments rasterised (pipeline
    /// statistics) and depth precision.
    counters: Vec<BTreeMap<String, u64>>,
    study_written: Cell<bool>,
    /// Per variant: the exact volume costs are still to count.
    pending: Vec<bool>,
    /// The exercises' cameras and volumes, made when first drawn.
    exercises: [Option<(SceneGpu, Route)>; 2],
    /// The last frame's depth-stencil texture (the runner's), for
    /// [`Lesson::buffer_view`]; `reversed_z` draws into its own.
    depth_stencil: Option<wgpu::Texture>,
}

/// Relative gap in parts per billion; 10⁹ means "not even Δd = d resolves".
fn ppb(g: Option<f64>) -> u64 {
    g.map_or(1_000_000_000, |g| (g * 1e9).round() as u64)
}

impl Lesson for DepthClamp {
    const NAME: &'static str = "lesson_07";
    /// Costs are counted on a variant's second frame ([`Lesson::count_again`]).
    const COUNTED_ON_FRAME: u32 = 2;
    const DEFAULT_SCENE: &'static str = include_str!("../../scenes/lesson_07.toml");
    type Variant = Variant;

    fn check_scene(scene: &Scene) -> Result<()> {
        if scene.camera.far == Far::Infinite {
            anyhow::bail!("camera.far: lesson_07 compares a finite far plane with clamping and an infinite one; give a finite far");
        }
        Ok(())
    }

    /// The stencil: light N's z-fail count, N the last light.
    fn buffer_view(&self, gpu: &Gpu, scene: &SceneGpu, v: Variant) -> Result<Option<BufferView>> {
        let ds = match (v, &self.reversed) {
            (Variant::ReversedZ, Ok(r)) => Some(r.depth_stencil()),
            _ => self.depth_stencil.as_ref(),
        };
        let (Some(ds), Some(last)) = (ds, scene.scene.lights.len().checked_sub(1)) else {
            return Ok(None);
        };
        count_view(gpu, ds, last, 0xff, "z-fail count").map(Some)
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let infinite_scene = infinite_scene(gpu, scene)?;
        let clamp = Route::new(gpu, scene, true).map_err(|e| {
            format!("variant \"clamp\": {e}; run --variant neither --variant infinite")
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
        // The model follows what the format stores here (24-bit or float).
        let format = (format, study::storage_of(gpu, format)?);
        let mut counters = Vec::new();
        for &v in Variant::value_variants() {
            // The study reads the GPU back: not in a web page (no counters there).
            if is_exercise(v) || !gpu.can_wait() {
                counters.push(BTreeMap::new());
                continue;
            }
            let row = study::study_one(gpu, format, v.mapping(), near, far)?;
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
            counters.push(c);
        }
        let reversed = ReversedZ::new(gpu, scene).map_err(|e| {
            format!("variant \"reversed_z\": {e}; or run --variant clamp --variant infinite")
        });
        Ok(DepthClamp {
            reversed,
            finite: Route::new(gpu, scene, false)?,
            clamp,
            infinite: Route::new(gpu, &infinite_scene, false)?,
            infinite_scene,
            scene_counters: stencil::scene_counters(scene),
            counters,
            study_written: Cell::new(false),
            pending: vec![false; Variant::value_variants().len()],
            exercises: [None, None],
            depth_stencil: None,
        })
    }

    fn unavailable(&self, variant: Variant) -> Option<String> {
        match variant {
            Variant::Clamp => self.clamp.as_ref().err().cloned(),
            Variant::ReversedZ => self.reversed.as_ref().err().cloned(),
            _ => None,
        }
    }

    /// The variant's camera and volumes drawn by [`zfail_frame`]; around
    /// it, the exercises' cameras and the counts.
    fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        variant: Variant,
    ) -> Result<()> {
        // What the "buffer" view reads: this frame's stencil.
        self.depth_stencil = Some(targets.depth.clone());
        if variant == Variant::ReversedZ {
            let r = self.reversed.as_mut().map_err(|e| anyhow::anyhow!("{e}"))?;
            r.render(frame, scene, targets, &self.infinite.volumes);
            let casters = self.infinite.volumes.casters.len() * r.scene.scene.lights.len();
            self.counters[variant as usize].insert("casters_drawn".into(), casters as u64);
            return Ok(());
        }
        if let Some((k, camera)) = variant.exercise() {
            if self.exercises[k].is_none() {
                let sg = camera(frame.gpu, scene)?;
                let route = Route::new(frame.gpu, &sg, false)?;
                if variant == Variant::ExerciseAdaptiveNear {
                    let near = cameras::adapted_near(scene);
                    let clipped = cameras::vertices_before_near(scene, near);
                    let c = &mut self.counters[variant as usize];
                    c.insert("vertices_before_near".into(), clipped);
                }
                self.exercises[k] = Some((sg, route));
            }
        }
        // The runner's sub-pixel move (`--fragile`) reaches the cameras
        // this lesson makes for itself.
        self.infinite_scene.set_jitter(frame.gpu, scene.jitter);
        for (sg, _) in self.exercises.iter_mut().flatten() {
            sg.set_jitter(frame.gpu, scene.jitter);
        }
        let (sg, route): (&SceneGpu, &mut Route) = match variant {
            Variant::ReversedZ => unreachable!("drawn above"),
            Variant::ExerciseInfiniteProjection | Variant::ExerciseAdaptiveNear => {
                let (sg, route) = self.exercises[variant.exercise().expect("an exercise").0]
                    .as_mut()
                    .expect("made above");
                (sg, route)
            }
            Variant::Neither => (scene, &mut self.finite),
            Variant::Clamp => (
                scene,
                self.clamp.as_mut().map_err(|e| anyhow::anyhow!("{e}"))?,
            ),
            Variant::Infinite => (&self.infinite_scene, &mut self.infinite),
        };
        let draws = zfail_frame(frame, sg, targets, route)?;
        let c = &mut self.counters[variant as usize];
        if !c.contains_key("casters_drawn") {
            c.insert(
                "casters_drawn".into(),
                draws.iter().map(|d| d.len() as u64).sum(),
            );
            let (gpu, ext) = (frame.gpu, Extrusion::Quads);
            if let Some(f) = route.volumes.count_fragments(gpu, sg, ext, &draws) {
                // llvmpipe counts 16 per 4×4 block: not the fragment count.
                c.insert("fragment_shader_invocations".into(), f);
            }
            // The depth is this frame's, not yet drawn: the first frame's
            // costs wait for the second call, untimed in their own submits.
            self.pending[variant as usize] = true;
        } else if self.pending[variant as usize] {
            // In a web page the costs come back a frame or more later.
            let (gpu, ext) = (frame.gpu, Extrusion::Quads);
            let costs = later(|| route.volumes.count_costs(gpu, sg, targets, ext, &draws))?;
            if let Some(costs) = costs {
                self.pending[variant as usize] = false;
                costs.insert_into(c, base_and_lit_draws(sg));
            }
        }
        Ok(())
    }

    /// The costs are counted once, on the frame after `casters_drawn` is
    /// first set: forget that key and they are counted again.
    fn count_again(&mut self, variant: Variant) {
        self.counters[variant as usize].remove("casters_drawn");
        self.pending[variant as usize] = false;
    }

    fn counters(&self, variant: Variant) -> BTreeMap<String, u64> {
        let mut c = self.scene_counters.clone();
        c.extend(self.counters[variant as usize].clone());
        c
    }

    /// The depth-precision study, once per run: both formats, four
    /// mappings, far/near from 1e2 to 1e8 (near = 1e-3).
    fn write_extras(&self, gpu: &Gpu, _: &SceneGpu, _: Variant, out: &Path) -> Result<()> {
        if self.study_written.replace(true) {
            return Ok(());
        }
        let rows = study::study(gpu, 1e-3, &[1e2, 1e4, 1e6, 1e8])?;
        let write = |name: &str, text: String| {
            std::fs::write(out.join(name), text)
                .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", out.join(name).display()))
        };
        write("depth_precision.csv", precision_table::csv(&rows))?;
        write("depth_precision.md", precision_table::markdown(&rows))?;
        write("depth_precision.svg", precision_table::svg_plot(&rows))?;
        save(
            &precision_table::grid_image(&rows, 3),
            &out.join("depth_precision.png"),
        )
    }
}

pub(crate) fn main() -> std::process::ExitCode {
    workbook::lesson_main::<DepthClamp>()
}
