//! What a frame's shadow volumes cost (lesson 05): fragments rasterised,
//! stencil writes, triangles and draw calls, counted exactly by an untimed
//! copy of the volume pass ([`Tally`](crate::lesson_01::tally::Tally)), the same on Vulkan and GL.

use anyhow::Result;
use common::gpu::Gpu;
use common::render::SceneGpu;
use common::targets::FrameTargets;

use super::super::extrusion::Extrusion;
use super::super::stencil::Method;
use super::{CasterDraw, DrawRole, LightVolumes, ShadowVolumes};

/// A frame's volume costs ([`ShadowVolumes::count_costs`]), over every light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VolumeCosts {
    /// Fragments the volumes rasterise (no depth test): exact.
    pub fragments: u64,
    /// Stencil writes: z-pass faces where the depth test passes, z-fail
    /// faces where it fails.
    pub stencil_updates: u64,
    /// Triangles submitted for the volumes (sides and caps).
    pub triangles: u64,
    /// Draw calls of the volume passes.
    pub draws: u64,
}

impl VolumeCosts {
    /// The standard report keys (`volume_fragments`, `stencil_updates`,
    /// `volume_triangles`) into `c`, and `draws`: `other_draws` (base and
    /// lit passes) plus the volume passes'.
    pub fn insert_into(&self, c: &mut std::collections::BTreeMap<String, u64>, other_draws: u64) {
        c.insert("volume_fragments".into(), self.fragments);
        c.insert("stencil_updates".into(), self.stencil_updates);
        c.insert("volume_triangles".into(), self.triangles);
        c.insert("draws".into(), other_draws + self.draws);
    }
}

/// Draw calls of a frame's base pass and lit passes: every object, once in
/// the base pass and once per light.
pub fn base_and_lit_draws(scene: &SceneGpu) -> u64 {
    scene.scene.objects.len() as u64 * (1 + scene.scene.lights.len() as u64)
}

impl ShadowVolumes {
    /// Fragments rasterised by the volumes of `draws[light]` for every light
    /// (see [`FragmentCounter`](common::counters::FragmentCounter)); `None` without PIPELINE_STATISTICS_QUERY.
    /// Call after `prepare_cpu` for the CPU path. Untimed: its own submit.
    pub fn count_fragments(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        extrusion: Extrusion,
        draws: &[Vec<CasterDraw>],
    ) -> Option<u64> {
        let counter = self.counter.as_ref()?;
        counter
            .count(gpu, |pass| {
                for (light, draws) in draws.iter().enumerate() {
                    let v = LightVolumes {
                        light,
                        extrusion,
                        draws,
                    };
                    self.draw_casters(pass, scene, v, DrawRole::Statistics);
                }
            })
            .ok()
    }

    // ANCHOR: count_costs
    /// The volumes' costs for `draws[light]`, every light ([`VolumeCosts`]),
    /// counted by a [`Tally`](crate::lesson_01::tally::Tally) against the frame's depth in `targets`: call
    /// it after a frame (and after `prepare_cpu` for the CPU path). Exact
    /// and the same on Vulkan and GL. Untimed: its own submits.
    pub fn count_costs(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        extrusion: Extrusion,
        draws: &[Vec<CasterDraw>],
    ) -> Result<VolumeCosts> {
        let mut costs = VolumeCosts::default();
        for (light, d) in draws.iter().enumerate() {
            let (calls, tris) = self.submitted(light, extrusion, d);
            costs.draws += calls;
            costs.triangles += tris;
        }
        // Tally `draws` filtered by `keep`, with or without the depth test.
        let tally = |keep: fn(&CasterDraw) -> bool, depth_test: bool| -> Result<u64> {
            let depth = targets.depth_attachment_loaded();
            self.tally.count(gpu, Some(depth), |pass| {
                for (light, d) in draws.iter().enumerate() {
                    let kept: Vec<CasterDraw> = d.iter().copied().filter(keep).collect();
                    let v = LightVolumes {
                        light,
                        extrusion,
                        draws: &kept,
                    };
                    self.draw_casters(pass, scene, v, DrawRole::Tally { depth_test });
                }
            })
        };
        let zpass = |d: &CasterDraw| d.method == Method::ZPass;
        let zfail = |d: &CasterDraw| d.method == Method::ZFail;
        costs.fragments = tally(|_| true, false)?;
        let zfail_all = if draws.iter().flatten().any(zfail) {
            tally(zfail, false)? - tally(zfail, true)?
        } else {
            0
        };
        costs.stencil_updates = tally(zpass, true)? + zfail_all;
        Ok(costs)
    }
    // ANCHOR_END: count_costs

    /// Draw calls and triangles of one light's volume pass.
    fn submitted(&self, light: usize, extrusion: Extrusion, draws: &[CasterDraw]) -> (u64, u64) {
        let (mut calls, mut tris) = (0, 0);
        for d in draws {
            let Some((ci, c)) = self.caster(d.object) else {
                continue;
            };
            let ranges = match extrusion {
                Extrusion::Cpu => match self.cpu.ranges.get(light).and_then(|r| r.get(ci)) {
                    Some(r) => r,
                    None => continue,
                },
                Extrusion::Quads => &c.quad_ranges,
            };
            for (r, _) in d.ranges(ranges) {
                calls += 1;
                tris += r.len() as u64 / 3;
            }
        }
        (calls, tris)
    }
}
