//! Lesson 04's cost counters: what the cube faces' shadow passes write and
//! rasterise, counted exactly on every backend with lesson 01's
//! [`Tally`] (a copy of the face pass, with its own depth test, adds 1.0
//! per fragment), and the frame's draw calls.
//!
//! Untimed: the counts are submits of their own, made once per variant.

use anyhow::Result;
use common::gpu::render::SceneGpu;
use common::gpu::targets::depth_texture;
use common::gpu::Gpu;

use super::cube_map::{cube_pipeline_with, DepthStorage, CUBE_FORMAT};
use super::faces::{FaceRects, FaceUniforms};
use crate::lesson_01::tally::{Tally, TallyShader, TALLY_TARGETS};

/// Texture lookups per lit pixel of the 3D PCF variants: the 20 directions
/// of `pcf_offset` in `shaders/lesson_04/cube_map.wgsl`.
pub const PCF3D_TAPS: u64 = 20;

/// The two counting copies of the face pipeline of `storage`: `[0]` tests
/// `Less` as the face pass does (its depth writes), `[1]` tests nothing
/// (every fragment rasterised). The linear storage keeps its fragment
/// shader's depth (`fs_cube_linear_tally`), so the test sees the same values.
pub fn cube_tally_pipelines(
    gpu: &Gpu,
    scene: &SceneGpu,
    module: &wgpu::ShaderModule,
    storage: DepthStorage,
    unclipped: bool,
    tally: &TallyShader,
) -> [wgpu::RenderPipeline; 2] {
    let with = |compare| {
        let (vs, fragment) = match storage {
            DepthStorage::Linear { vs_entry, .. } => (
                vs_entry,
                wgpu::FragmentState {
                    module,
                    entry_point: Some("fs_cube_linear_tally"),
                    compilation_options: Default::default(),
                    targets: &TALLY_TARGETS,
                },
            ),
            DepthStorage::Hardware => ("vs_light_depth", tally.fragment()),
        };
        cube_pipeline_with(gpu, scene, module, vs, Some(fragment), compare, unclipped)
    };
    [
        with(wgpu::CompareFunction::Less),
        with(wgpu::CompareFunction::Always),
    ]
}

/// Light `light`'s face passes, counted: `.0` the depth writes (fragments
/// that pass the faces' `Less` test, in draw order), `.1` the fragments
/// rasterised, over the faces with casters (`casters(face)`) and a
/// rectangle, inside it (`rects`), as the frame draws them (a face without
/// is not rendered). `faces` must hold the light's uniforms
/// ([`FaceUniforms::write`]); each face is counted into a fresh `size`²
/// depth target, not the frame's cube.
pub fn count_light_texels(
    gpu: &Gpu,
    scene: &SceneGpu,
    pipelines: &[wgpu::RenderPipeline; 2],
    faces: &FaceUniforms,
    size: u32,
    (light, rects): (usize, &FaceRects),
    casters: impl Fn(usize) -> Vec<usize>,
) -> Result<(u64, u64)> {
    let texture = depth_texture(gpu, "cube face count", size, 1, CUBE_FORMAT);
    let view = texture.create_view(&Default::default());
    let tally = Tally::new(gpu, size, size);
    let mut total = [0, 0];
    for (face, rect) in rects.iter().enumerate() {
        let Some(rect) = rect else {
            continue;
        };
        let list = casters(face);
        if list.is_empty() {
            continue;
        }
        for (pipeline, total) in pipelines.iter().zip(total.iter_mut()) {
            let depth = wgpu::RenderPassDepthStencilAttachment {
                view: &view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            };
            *total += tally.count(gpu, Some(depth), |pass| {
                pass.set_pipeline(pipeline);
                faces.bind(pass, light, face);
                pass.set_scissor_rect(rect.x, rect.y, rect.w, rect.h);
                scene.draw_objects(pass, |i| list.contains(&i));
            })?;
        }
    }
    Ok((total[0], total[1]))
}

/// Draw calls of a frame: the base pass (every object), the face passes'
/// `caster_draws`, and per light the lit pass (every object).
pub fn frame_draws(scene: &SceneGpu, caster_draws: u64) -> u64 {
    let objects = scene.scene.objects.len() as u64;
    objects + caster_draws + scene.scene.lights.len() as u64 * objects
}
