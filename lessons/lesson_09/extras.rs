//! Lesson 09's debug pictures: the frame tinted by the cascade each pixel
//! samples (`<variant>_cascades.png`, and the "buffer" view), and each
//! cascade's depth layer.

use std::path::Path;

use anyhow::Result;
use common::gpu::readback::read_texture;
use common::gpu::render::{pipeline_layout_for, vertex_state, SceneGpu};
use common::gpu::targets::render_texture;
use common::gpu::Gpu;
use common::run::files::save;
use common::run::instruments::BufferView;

use super::csm::CascadeMaps;

const TINT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const TINT_DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The pipeline of `fs_cascade_tint` (`csm.wgsl`): the scene from the
/// camera, into its own colour and depth targets, with the variant's
/// `constants` (its cascade count and blend, [`super::pipelines::Shape`]).
pub fn tint_pipeline(
    gpu: &Gpu,
    scene: &SceneGpu,
    module: &wgpu::ShaderModule,
    csm_layout: &wgpu::BindGroupLayout,
    constants: &[(&str, f64)],
) -> wgpu::RenderPipeline {
    let layout = pipeline_layout_for(
        gpu,
        &scene.frame_layout,
        &scene.object_layout,
        &[csm_layout],
    );
    gpu.device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("cascade tint"),
            layout: Some(&layout),
            vertex: vertex_state(module, "vs_scene"),
            primitive: Default::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: TINT_DEPTH,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some("fs_cascade_tint"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants,
                    ..Default::default()
                },
                targets: &[Some(TINT_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        })
}

/// Draws light 0's cascade picture with `group` (the variant's maps and
/// parameters, as its last frame left them) and saves it to `path`.
pub fn write_cascade_png(
    gpu: &Gpu,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
    path: &Path,
) -> Result<()> {
    save(&cascade_image(gpu, scene, pipeline, group)?, path)
}

/// The colours of `CASCADE_TINTS` (`csm.wgsl`), cascade 0 first.
const TINT_NAMES: [&str; 4] = ["red", "green", "blue", "yellow"];

/// The "buffer" view: [`cascade_image`] of `count` cascades, its legend
/// in the title.
pub fn cascade_view(
    gpu: &Gpu,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
    count: usize,
) -> Result<BufferView> {
    let legend: Vec<String> = TINT_NAMES
        .iter()
        .take(count)
        .enumerate()
        .map(|(i, name)| format!("{name} {i}"))
        .collect();
    let title = format!(
        "the cascade each pixel samples for light 0 ({count} cascade{}): {}; shaded by light 0 and its shadow; black: no surface",
        if count == 1 { "" } else { "s" },
        legend.join(", ")
    );
    let image = cascade_image(gpu, scene, pipeline, group)?;
    Ok(BufferView { title, image })
}

/// Light 0's cascade picture: the frame, each pixel tinted by the cascade
/// it samples (`fs_cascade_tint`), drawn with `group` (the variant's maps
/// and parameters, as its last frame left them).
pub fn cascade_image(
    gpu: &Gpu,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
) -> Result<image::RgbaImage> {
    let (w, h) = (scene.width, scene.height);
    let color = render_texture(
        gpu,
        "cascade tint",
        w,
        h,
        TINT_FORMAT,
        wgpu::TextureUsages::empty(),
    );
    let depth = render_texture(
        gpu,
        "cascade tint depth",
        w,
        h,
        TINT_DEPTH,
        wgpu::TextureUsages::empty(),
    );
    let (color_view, depth_view) = (
        color.create_view(&Default::default()),
        depth.create_view(&Default::default()),
    );
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("cascade tint"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        scene.bind_frame(&mut pass, 0);
        pass.set_bind_group(2, group, &[]);
        scene.draw_objects(&mut pass, |_| true);
    }
    gpu.queue.submit([enc.finish()]);
    let bytes = read_texture(gpu, &color, 4)?;
    image::RgbaImage::from_raw(w, h, bytes)
        .ok_or_else(|| anyhow::anyhow!("cascade picture: readback size"))
}

/// Saves each cascade's depth layer as `<stem>_cascade_<i>_depth.png`.
pub fn write_layers(gpu: &Gpu, maps: &CascadeMaps, out: &Path, stem: &str) -> Result<()> {
    for i in 0..maps.count {
        let path = out.join(format!("{stem}_cascade_{i}_depth.png"));
        maps.layer(i).write_png(gpu, &path)?;
    }
    Ok(())
}
