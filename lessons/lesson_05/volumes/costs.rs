//! What a frame's shadow volumes cost (lesson 05): fragments rasterised,
//! stencil writes, triangles and draw calls, counted exactly by an untimed
//! copy of the volume pass ([`Tally`](crate::lesson_01::tally::Tally)): exact on one adapter; rasterisers
//! differ by a few edge fragments, and where a depth test ties.

use anyhow::Result;
use common::gpu::read_later::later;
use common::gpu::render::SceneGpu;
use common::gpu::targets::FrameTargets;
use common::gpu::Gpu;
use common::measure::counters::{
    Counts, DRAWS, EDGES_TESTED, FRAGMENT_SHADER_INVOCATIONS, SILHOUETTE_EDGES, STENCIL_UPDATES,
    VOLUME_FRAGMENTS, VOLUME_TRIANGLES,
};
use common::measure::timing::Frame;

use super::super::compute::ComputeVolumes;
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
    /// Edges whose faces were tested for a silhouette: every edge of every
    /// caster drawn, once per light. Over a pass's time: edges per second.
    pub edges_tested: u64,
    /// Silhouette edges extruded into sides (the CPU and compute routes;
    /// the quads route never knows which quads opened).
    pub silhouette_edges: Option<u64>,
}

impl VolumeCosts {
    /// The standard counters ([`VOLUME_FRAGMENTS`], [`STENCIL_UPDATES`],
    /// [`VOLUME_TRIANGLES`], [`EDGES_TESTED`], [`SILHOUETTE_EDGES`]) into
    /// `c`, and [`DRAWS`]: `other_draws` (base and lit passes) plus the
    /// volume passes'.
    pub fn insert_into(&self, c: &mut Counts, other_draws: u64) {
        c.set(VOLUME_FRAGMENTS, self.fragments);
        c.set(STENCIL_UPDATES, self.stencil_updates);
        c.set(VOLUME_TRIANGLES, self.triangles);
        c.set(DRAWS, other_draws + self.draws);
        c.set(EDGES_TESTED, self.edges_tested);
        if let Some(n) = self.silhouette_edges {
            c.set(SILHOUETTE_EDGES, n);
        }
    }
}

/// Draw calls of a frame's base pass and lit passes: every object, once in
/// the base pass and once per light.
pub fn base_and_lit_draws(scene: &SceneGpu) -> u64 {
    scene.scene.objects.len() as u64 * (1 + scene.scene.lights.len() as u64)
}

impl ShadowVolumes {
    /// Fragments rasterised by the volumes of `draws[light]` for every light
    /// (see [`FragmentCounter`](common::measure::fragment_counter::FragmentCounter)); `None` without PIPELINE_STATISTICS_QUERY.
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

    /// [`count_fragments`](Self::count_fragments) and
    /// [`count_costs`](Self::count_costs) of one frame's `draws`.
    pub fn count_all(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        extrusion: Extrusion,
        draws: &[Vec<CasterDraw>],
    ) -> Result<(Option<u64>, VolumeCosts)> {
        let invocations = self.count_fragments(gpu, scene, extrusion, draws);
        Ok((
            invocations,
            self.count_costs(gpu, scene, targets, extrusion, draws)?,
        ))
    }

    /// The volumes' costs for `draws[light]`, every light ([`VolumeCosts`]),
    /// counted by a [`Tally`](crate::lesson_01::tally::Tally) against the frame's depth in `targets`: call
    /// it after a frame (and after `prepare_cpu` for the CPU path). Exact
    /// on one adapter, on Vulkan and GL alike (rasterisers differ by a few
    /// edge fragments, and where a depth test ties). Untimed: its own submits.
    pub fn count_costs(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        extrusion: Extrusion,
        draws: &[Vec<CasterDraw>],
    ) -> Result<VolumeCosts> {
        let mut costs = VolumeCosts::default();
        // The compute route's counts are on the GPU: read them back.
        let counts = match (extrusion, &self.compute) {
            (Extrusion::Compute, Some(c)) => Some(c.read_counts(gpu)?),
            _ => None,
        };
        for (light, d) in draws.iter().enumerate() {
            let s = self.submitted(scene, light, extrusion, d, counts.as_deref());
            costs.draws += s.calls;
            costs.triangles += s.triangles;
            costs.edges_tested += s.edges_tested;
            if extrusion != Extrusion::Quads {
                *costs.silhouette_edges.get_or_insert(0) += s.silhouette_edges;
            }
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

    /// What one light's volume pass submits. `counts`: the compute
    /// route's vertex counts ([`ComputeVolumes::read_counts`]).
    fn submitted(
        &self,
        scene: &SceneGpu,
        light: usize,
        extrusion: Extrusion,
        draws: &[CasterDraw],
        counts: Option<&[[u32; 3]]>,
    ) -> Submitted {
        let mut s = Submitted::default();
        let per_side = ComputeVolumes::per_side(scene, light) as u64;
        for d in draws {
            let Some((ci, c)) = self.caster(d.object) else {
                continue;
            };
            s.edges_tested += c.adjacency.edges.len() as u64;
            let ranges = match extrusion {
                Extrusion::Cpu => match self.cpu.ranges.get(light).and_then(|r| r.get(ci)) {
                    Some(r) => r,
                    None => continue,
                },
                Extrusion::Quads => &c.quad_ranges,
                Extrusion::Compute => {
                    let (Some(cv), Some(n)) = (&self.compute, counts) else {
                        continue;
                    };
                    for draw in cv.draws(scene, light, ci, (d.front_cap, d.back_cap)) {
                        s.calls += 1;
                        s.triangles += n[draw.slot][draw.part] as u64 / 3;
                    }
                    for slot in cv.slots_of(light, ci) {
                        s.silhouette_edges += n[slot][0] as u64 / per_side;
                    }
                    continue;
                }
            };
            s.silhouette_edges += ranges.sides.len() as u64 / per_side;
            for (r, _) in d.ranges(ranges) {
                s.calls += 1;
                s.triangles += r.len() as u64 / 3;
            }
        }
        s
    }
}

/// One variant's volume counts, taken once, on its second frame: the
/// first frame's depth is then in place, and the counting submits of its
/// own are left out of the frame's times (lessons 05 and 06's harness,
/// one per variant; their `counted_on_frame` is 2).
#[derive(Clone, Debug, Default)]
pub struct SecondFrameCounts {
    /// Frames drawn since the variant was last (re)set.
    frames: u32,
    /// Fragment-shader invocations (pipeline statistics, Vulkan only).
    invocations: Option<u64>,
    /// The exact costs; `None` until counted.
    costs: Option<VolumeCosts>,
}

impl SecondFrameCounts {
    /// After a frame of the variant: on its second, `count` (untimed).
    pub fn after_frame(
        &mut self,
        frame: &mut Frame,
        count: impl FnOnce(&Gpu) -> Result<(Option<u64>, VolumeCosts)>,
    ) -> Result<()> {
        self.frames += 1;
        // From the second frame on, until counted: in a web page the
        // counts come back a frame or more later.
        if self.frames >= 2 && self.costs.is_none() {
            if let Some((invocations, costs)) = frame.untimed(|gpu| later(|| count(gpu)))? {
                self.invocations = invocations;
                self.costs = Some(costs);
            }
        }
        Ok(())
    }

    /// Count again on the variant's second frame from now.
    pub fn again(&mut self) {
        *self = SecondFrameCounts::default();
    }

    /// The counts into `c` ([`VolumeCosts::insert_into`]), with
    /// `other_draws` the base and lit passes' draw calls.
    pub fn insert_into(&self, c: &mut Counts, other_draws: u64) {
        if let Some(f) = self.invocations {
            // llvmpipe counts 16 per 4×4 block: not the fragment count.
            c.set(FRAGMENT_SHADER_INVOCATIONS, f);
        }
        if let Some(costs) = self.costs {
            costs.insert_into(c, other_draws);
        }
    }
}

/// What one light's volume pass submits ([`ShadowVolumes::count_costs`]).
#[derive(Default)]
struct Submitted {
    calls: u64,
    triangles: u64,
    edges_tested: u64,
    silhouette_edges: u64,
}
