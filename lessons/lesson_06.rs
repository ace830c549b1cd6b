//! # Lesson 06: z-fail with caps (Carmack's reverse)
//!
//! Lesson 05 counted the volume faces *in front of* the visible surface,
//! which misses the "enter" of a volume the eye is already inside. Z-fail
//! counts the faces *behind* it instead (back faces +1, front faces −1),
//! out to infinity, where nothing starts inside a volume. That needs closed
//! volumes: a front cap (the light-facing triangles) and a back cap (the
//! same triangles at infinity, reversed).
//!
//! Variants: `zpass_quads` (lesson 05, for contrast), `zfail_cpu` and
//! `zfail_quads` (the two ways to build the volumes), `zfail_no_front_cap`
//! and `zfail_no_back_cap` (what a missing cap does), and `zfail_selective`
//! (z-fail only for casters whose volume can reach the near plane, z-pass
//! for the rest, nothing for casters whose volume cannot reach the view:
//! the same pixels for less work).
//!
//! Run: `cargo run --release --bin lesson_06 -- --headless`
//! Book: chapter "06 z-fail with caps" (`book/src/lesson_06.md`).

use std::collections::BTreeMap;

use common::app::{self, Lesson};
use common::gpu::Gpu;
use common::render::{FrameTargets, SceneGpu};
use common::shadow_volume::{
    self, CasterDraw, Extrusion, FarPlane, Method, PlanStats, ShadowVolumes,
};
use common::timing::Frame;
use common::Result;

// ANCHOR: variants
const VARIANTS: [&str; 6] = [
    "zpass_quads",
    "zfail_cpu",
    "zfail_quads",
    "zfail_no_front_cap",
    "zfail_no_back_cap",
    "zfail_selective",
];

/// The draws of one light for a variant: which casters, counted how.
fn draws_for(
    variant: &str,
    volumes: &ShadowVolumes,
    scene: &SceneGpu,
    light: usize,
) -> (Vec<CasterDraw>, PlanStats) {
    let mut draws = volumes.all(if variant == "zpass_quads" {
        Method::ZPass
    } else {
        Method::ZFail
    });
    for d in &mut draws {
        d.front_cap &= variant != "zfail_no_front_cap";
        d.back_cap &= variant != "zfail_no_back_cap";
    }
    let n = draws.len() as u32;
    match variant {
        "zfail_selective" => volumes.plan(scene, light),
        "zpass_quads" => (
            draws,
            PlanStats {
                zpass: n,
                ..Default::default()
            },
        ),
        _ => (
            draws,
            PlanStats {
                zfail: n,
                ..Default::default()
            },
        ),
    }
}
// ANCHOR_END: variants

struct ZFail {
    volumes: ShadowVolumes,
    lit_pipeline: wgpu::RenderPipeline,
    scene_counters: BTreeMap<String, u64>,
    /// Per variant: `draws[light]`, and what was left out.
    plans: BTreeMap<String, (Vec<Vec<CasterDraw>>, PlanStats)>,
    fragments: Option<u64>,
}

impl Lesson for ZFail {
    const NAME: &'static str = "lesson_06";
    const DEFAULT_SCENE: &'static str = include_str!("../scenes/lesson_06.toml");

    fn variants() -> Vec<String> {
        VARIANTS.iter().map(|v| v.to_string()).collect()
    }

    fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<Self> {
        let volumes = ShadowVolumes::new(gpu, scene, FarPlane::Clip)?;
        let mut plans = BTreeMap::new();
        for v in VARIANTS {
            let mut total = PlanStats::default();
            let mut per_light = Vec::new();
            for light in 0..scene.scene.lights.len() {
                let (d, s) = draws_for(v, &volumes, scene, light);
                total.zpass += s.zpass;
                total.zfail += s.zfail;
                total.skipped += s.skipped;
                per_light.push(d);
            }
            plans.insert(v.to_string(), (per_light, total));
        }
        Ok(ZFail {
            lit_pipeline: shadow_volume::stencil_lit_pipeline(gpu, scene),
            scene_counters: shadow_volume::scene_counters(scene),
            volumes,
            plans,
            fragments: None,
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
        let (draws, _) = self
            .plans
            .get(variant)
            .ok_or_else(|| anyhow::anyhow!("unknown variant {variant}"))?;
        let ext = if variant == "zfail_cpu" {
            Extrusion::Cpu
        } else {
            Extrusion::Quads
        };
        if ext == Extrusion::Cpu {
            self.volumes.prepare_cpu(frame, scene, draws);
        }
        frame.pass("base", |enc, ts| scene.base_pass(enc, targets, ts.render()));
        for (light, light_draws) in draws.iter().enumerate() {
            // Each caster carries its own method: the stencil ops differ,
            // the count they leave is the same.
            frame.pass("volume", |enc, ts| {
                self.volumes
                    .volume_pass(enc, scene, targets, light, ext, light_draws, ts.render())
            });
            frame.pass("lighting", |enc, ts| {
                scene.lit_pass(enc, targets, light, &self.lit_pipeline, &[], 0, ts.render())
            });
        }
        self.fragments = self.volumes.count_fragments(frame.gpu, scene, ext, draws);
        Ok(())
    }
    // ANCHOR_END: render

    fn counters(&self, variant: &str) -> BTreeMap<String, u64> {
        let mut c = self.scene_counters.clone();
        if let Some((_, s)) = self.plans.get(variant) {
            c.insert("casters_zpass".into(), s.zpass as u64);
            c.insert("casters_zfail".into(), s.zfail as u64);
            c.insert("casters_skipped".into(), s.skipped as u64);
            c.insert("casters_drawn".into(), (s.zpass + s.zfail) as u64);
        }
        if let Some(f) = self.fragments {
            c.insert("volume_fragments".into(), f);
        }
        c
    }
}

fn main() -> std::process::ExitCode {
    app::main::<ZFail>()
}
