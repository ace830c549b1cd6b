//! The shadow map's min/max mip chain (lesson 10, `pcss_min_max`): for
//! every 2^l × 2^l block of the map, its nearest and farthest depth, made
//! after the shadow pass by one compute pass per level
//! (`shaders/lesson_10/min_max.wgsl`). The lit pass reads four blocks of
//! one level to learn what a whole disk of the map holds, before it reads
//! a single texel (`soft.wgsl`'s `region_min_max`).

use common::gpu::bindings;
use common::gpu::Gpu;

use crate::lesson_01::shadow_map::ShadowMap;

/// `Level` in `min_max.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct LevelUniform {
    below: u32,
    start: u32,
    side: u32,
    _pad: u32,
}

/// Where level `l` (1 to log2 of the map's side) starts in the chain, in
/// (min, max) pairs: the levels below it, `(side >> k)²` pairs each, a
/// geometric sum, `(side² − (side >> (l − 1))²) / 3`. `soft.wgsl`'s
/// `region_min_max` computes the same sum (its `start`).
pub fn level_start(side: u32, l: u32) -> u32 {
    (side * side - (side >> (l - 1)) * (side >> (l - 1))) / 3
}

/// A map's min/max chain and the passes that make it.
pub struct MinMaxChain {
    /// Every level's (min, max) pairs, row by row, level 1 first: bound at
    /// group 2 binding 4 of the lit pass.
    pub buffer: wgpu::Buffer,
    /// Per level: its group and whether it reads the map.
    levels: Vec<(wgpu::BindGroup, u32)>,
    from_depth: wgpu::ComputePipeline,
    from_chain: wgpu::ComputePipeline,
}

impl MinMaxChain {
    /// The chain of `map`, whose side must be a power of two (every map of
    /// this lesson's is).
    pub fn new(gpu: &Gpu, map: &ShadowMap) -> MinMaxChain {
        let side = map.size;
        assert!(
            side.is_power_of_two(),
            "a min/max chain needs a power-of-two map, not {side}"
        );
        let count = side.trailing_zeros();
        let pairs = level_start(side, count + 1).max(1);
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("min/max chain"),
            size: pairs as u64 * 8,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let (layout, module, pipeline_layout) = bindings::compute_over_map(
            gpu,
            "min/max chain",
            1,
            "shaders/lesson_10/min_max.wgsl",
            include_str!("../../shaders/lesson_10/min_max.wgsl"),
        );
        let pipeline = |from_depth: bool| {
            gpu.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("min/max chain"),
                    layout: Some(&pipeline_layout),
                    module: &module,
                    entry_point: Some("cs_reduce"),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants: &[("FROM_DEPTH", from_depth as u32 as f64)],
                        ..Default::default()
                    },
                    cache: None,
                })
        };
        let levels = (1..=count)
            .map(|l| {
                let u = LevelUniform {
                    below: if l == 1 { 0 } else { level_start(side, l - 1) },
                    start: level_start(side, l),
                    side: side >> l,
                    _pad: 0,
                };
                let params = bindings::params_buffer(gpu, "min/max level", bytemuck::bytes_of(&u));
                let resources = [
                    wgpu::BindingResource::TextureView(&map.view),
                    params.as_entire_binding(),
                    buffer.as_entire_binding(),
                ];
                let group = bindings::group(gpu, "min/max level", &layout, &resources);
                (group, u.side)
            })
            .collect();
        MinMaxChain {
            buffer,
            levels,
            from_depth: pipeline(true),
            from_chain: pipeline(false),
        }
    }

    // ANCHOR: record
    /// Records the chain's passes, level 1 to the last: one compute pass
    /// each, so that each reads what the one before it wrote. The
    /// timestamps, if any, open the first and close the last.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites>,
    ) {
        let last = self.levels.len() - 1;
        for (i, (group, side)) in self.levels.iter().enumerate() {
            let timestamp_writes = (timestamps.as_ref())
                .map(|t| wgpu::ComputePassTimestampWrites {
                    query_set: t.query_set,
                    beginning_of_pass_write_index: t
                        .beginning_of_pass_write_index
                        .filter(|_| i == 0),
                    end_of_pass_write_index: t.end_of_pass_write_index.filter(|_| i == last),
                })
                .filter(|t| {
                    t.beginning_of_pass_write_index
                        .or(t.end_of_pass_write_index)
                        .is_some()
                });
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("min/max chain"),
                timestamp_writes,
            });
            pass.set_pipeline(if i == 0 {
                &self.from_depth
            } else {
                &self.from_chain
            });
            pass.set_bind_group(0, group, &[]);
            let groups = side.div_ceil(8);
            pass.dispatch_workgroups(groups, groups, 1);
        }
    }
    // ANCHOR_END: record
}

#[cfg(test)]
mod tests {
    use super::level_start;

    /// Each level starts where the one below it ends.
    #[test]
    fn levels_follow_each_other() {
        for side in [2u32, 512, 1024, 2048] {
            let mut start = 0;
            for l in 1..=side.trailing_zeros() {
                assert_eq!(level_start(side, l), start, "side {side}, level {l}");
                start += (side >> l) * (side >> l);
            }
        }
    }
}
