//! The shadow map (lesson 01, reused by lessons 02 and 03): a depth
//! texture rendered from the light, the pass that fills it, and how the lit
//! pass samples it.

use std::path::Path;

use anyhow::Result;
use common::glam::Mat4;
use common::gpu::bindings::{self, float_texture_entry, sampler_entry, texture_entry};
use common::gpu::fullscreen::{read_floats, Fullscreen, FLOAT_BYTES_FORMAT};
use common::gpu::render::{
    pipeline_layout_for, shader_module as scene_shader_module, vertex_state, SceneGpu,
};
use common::gpu::targets::depth_texture;
use common::gpu::Gpu;
use common::run::files::save;
use common::run::instruments::BufferView;
use common::scene::camera::light_view_proj;
use common::scene::{LightKind, Scene};

use super::tally::Tally;
use super::tally::TallyShader;

// ANCHOR: shadow_map_texture
/// 32-bit float depth: the comparison reads the very value the shadow pass wrote.
pub const SHADOW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A square depth texture seen from the light.
pub struct ShadowMap {
    pub size: u32,
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl ShadowMap {
    pub fn new(gpu: &Gpu, size: u32) -> ShadowMap {
        let texture = depth_texture(gpu, &format!("shadow map {size}"), size, 1, SHADOW_FORMAT);
        let view = texture.create_view(&Default::default());
        ShadowMap {
            size,
            texture,
            view,
        }
    }
}
// ANCHOR_END: shadow_map_texture

/// The map as pictures: the lesson's `<variant>_depth_map.png` and the
/// window's buffer view.
impl ShadowMap {
    /// Reads the stored depths back to the CPU. Drawn through a shader into
    /// an RGBA8 target (the float's four bytes), because GL cannot copy
    /// depth textures to buffers.
    pub fn read_depths(&self, gpu: &Gpu) -> Result<Vec<f32>> {
        // GLSL cannot `textureLoad` a depth binding: bind it as floats.
        let layout = bindings::layout(gpu, "depth as floats", &[float_texture_entry(0)]);
        let view = wgpu::BindingResource::TextureView(&self.view);
        let group = bindings::group(gpu, "depth as floats", &layout, &[view]);
        let pipeline = Fullscreen::image(
            "depth to bytes",
            DEPTH_TO_BYTES_WGSL,
            "fs",
            &[&layout],
            FLOAT_BYTES_FORMAT,
        )
        .pipeline(gpu);
        read_floats(gpu, &pipeline, &group, (self.size, self.size))
    }

    /// Writes the depth map as a picture: near = dark, far = light, the
    /// range stretched over what the map holds so the casters stand out.
    pub fn write_png(&self, gpu: &Gpu, path: &Path) -> Result<()> {
        let (shades, _) = depth_shades(&self.read_depths(gpu)?);
        let img = image::GrayImage::from_fn(self.size, self.size, |x, y| {
            image::Luma([shades[(y * self.size + x) as usize].unwrap_or(255)])
        });
        save(&img, path)
    }

    /// The map as the "buffer" view shows it: [`ShadowMap::write_png`]'s
    /// picture, with the texels no caster wrote in blue. `light`: the light
    /// whose depths it holds (the last one drawn: the lessons draw every
    /// light into the same map, one after the other).
    pub fn buffer_view(&self, gpu: &Gpu, light: usize) -> Result<BufferView> {
        let (shades, range) = depth_shades(&self.read_depths(gpu)?);
        let image = image::RgbaImage::from_fn(self.size, self.size, |x, y| {
            match shades[(y * self.size + x) as usize] {
                Some(v) => image::Rgba([v, v, v, 255]),
                None => image::Rgba(UNWRITTEN),
            }
        });
        let stored = match range {
            Some((lo, hi)) => format!("depths {lo:.4} to {hi:.4}"),
            None => "no depth stored".to_string(),
        };
        let n = self.size;
        let title = format!(
            "shadow map of light {light} (the last light drawn into it), {n}x{n}: depth, near black, far light grey, stretched over the {stored}; blue: never written (cleared to 1)"
        );
        Ok(BufferView { title, image })
    }

    /// [`ShadowMap::buffer_view`] of the scene's last light, the one the map
    /// holds after a frame; `None` when there is no light (no shadow pass).
    pub fn last_light_view(&self, gpu: &Gpu, scene: &SceneGpu) -> Result<Option<BufferView>> {
        let Some(last) = scene.scene.lights.len().checked_sub(1) else {
            return Ok(None);
        };
        self.buffer_view(gpu, last).map(Some)
    }
}

/// The colour of a texel no caster wrote, in [`ShadowMap::buffer_view`].
const UNWRITTEN: [u8; 4] = [40, 70, 170, 255];

/// Stored depths `d` as grey levels: near 0, far 235, stretched over the
/// depths the map holds; `None` where nothing was written (the clear
/// value, 1). Also that stretch's range, when something was written.
fn depth_shades(d: &[f32]) -> (Vec<Option<u8>>, Option<(f32, f32)>) {
    let lo = d.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = d.iter().copied().filter(|&x| x < 1.0).fold(lo, f32::max);
    let span = (hi - lo).max(1e-12);
    let shades = d
        .iter()
        .map(|&v| (v < 1.0).then(|| (((v - lo) / span) * 235.0).round() as u8))
        .collect();
    (shades, (lo < 1.0).then_some((lo, hi)))
}

/// One `T` per shadow-map size. A lesson whose variants run maps of several
/// sizes (a renderer's port runs its renderer's) makes one of each size
/// its variants use, and each variant finds its own by size.
pub struct PerSize<T> {
    items: Vec<(u32, T)>,
}

impl<T> PerSize<T> {
    /// `make(size)` once for each distinct size in `sizes`, smallest first.
    pub fn new(sizes: impl IntoIterator<Item = u32>, mut make: impl FnMut(u32) -> T) -> PerSize<T> {
        let mut sizes: Vec<u32> = sizes.into_iter().collect();
        sizes.sort_unstable();
        sizes.dedup();
        PerSize {
            items: sizes.into_iter().map(|s| (s, make(s))).collect(),
        }
    }

    /// Where the one of `size` is, for [`PerSize::at`].
    pub fn index(&self, size: u32) -> usize {
        (self.items.iter())
            .position(|(s, _)| *s == size)
            .expect("PerSize::new made one of every size the variants use")
    }

    /// The one at `index` ([`PerSize::index`]).
    pub fn at(&self, index: usize) -> &T {
        &self.items[index].1
    }

    /// The one of `size`.
    pub fn get(&self, size: u32) -> &T {
        self.at(self.index(size))
    }
}

/// How the shadow pass rasterises: which faces it culls and what depth bias
/// the hardware adds (lesson 02). Lesson 01 uses the default: none of either.
#[derive(Clone, Copy, Debug, Default)]
pub struct ShadowPassState {
    pub cull: Option<wgpu::Face>,
    pub bias: wgpu::DepthBiasState,
}

// ANCHOR: shadow_pipeline
/// The depth-only pipeline of the shadow pass: the scene's vertex buffers,
/// `vs_light_depth` (object → light clip space), no fragment shader at all.
pub fn shadow_pipeline(
    gpu: &Gpu,
    scene: &SceneGpu,
    module: &wgpu::ShaderModule,
    state: ShadowPassState,
) -> wgpu::RenderPipeline {
    let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
    let descriptor = shadow_pipeline_descriptor(&layout, module, state);
    gpu.device.create_render_pipeline(&descriptor)
}

/// Depth kept where a fragment is nearer (`Less`), no colour at all.
pub fn shadow_pipeline_descriptor<'a>(
    layout: &'a wgpu::PipelineLayout,
    module: &'a wgpu::ShaderModule,
    state: ShadowPassState,
) -> wgpu::RenderPipelineDescriptor<'a> {
    wgpu::RenderPipelineDescriptor {
        label: Some("shadow pass"),
        layout: Some(layout),
        vertex: vertex_state(module, "vs_light_depth"),
        primitive: wgpu::PrimitiveState {
            cull_mode: state.cull,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: SHADOW_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: state.bias,
        }),
        multisample: Default::default(),
        fragment: None,
        multiview_mask: None,
        cache: None,
    }
}
// ANCHOR_END: shadow_pipeline

/// The two counting copies of the shadow pipeline of `state`: `[0]` tests
/// `Less` as the shadow pass does (its depth writes), `[1]` tests nothing
/// (every fragment rasterised). For [`count_shadow_texels`].
pub fn shadow_tally_pipelines(
    gpu: &Gpu,
    scene: &SceneGpu,
    module: &wgpu::ShaderModule,
    state: ShadowPassState,
    tally: &TallyShader,
) -> [wgpu::RenderPipeline; 2] {
    let layout = pipeline_layout_for(gpu, &scene.frame_layout, &scene.object_layout, &[]);
    let with = |compare| {
        let mut copy = shadow_pipeline_descriptor(&layout, module, state);
        copy.fragment = Some(tally.fragment());
        if let Some(depth) = copy.depth_stencil.as_mut() {
            depth.depth_compare = Some(compare);
        }
        gpu.device.create_render_pipeline(&copy)
    };
    [
        with(wgpu::CompareFunction::Less),
        with(wgpu::CompareFunction::Always),
    ]
}

// ANCHOR: shadow_pass
/// Renders every shadow caster's depth from light `light` into `map`.
pub fn shadow_pass(
    encoder: &mut wgpu::CommandEncoder,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    map: &ShadowMap,
    light: usize,
    ts: Option<wgpu::RenderPassTimestampWrites>,
) -> u32 {
    let mut pass = begin_shadow_pass(encoder, "shadow pass", &map.view, ts);
    pass.set_pipeline(pipeline);
    scene.bind_frame(&mut pass, light);
    scene.draw_objects(&mut pass, |i| scene.casts_shadow(i))
}

/// A depth-only pass into `view`: no colour target, the depth cleared to
/// 1.0 (the far plane) and stored for the lighting pass to read.
pub fn begin_shadow_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    view: &wgpu::TextureView,
    ts: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: ts,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
// ANCHOR_END: shadow_pass

/// [`shadow_pass`] drawing only the casters `keep` keeps (lesson 10's map
/// without the objects that hide nothing); the count drawn.
pub fn shadow_pass_keeping(
    encoder: &mut wgpu::CommandEncoder,
    scene: &SceneGpu,
    pipeline: &wgpu::RenderPipeline,
    map: &ShadowMap,
    light: usize,
    ts: Option<wgpu::RenderPassTimestampWrites>,
    keep: impl Fn(usize) -> bool,
) -> u32 {
    let mut pass = begin_shadow_pass(encoder, "shadow pass", &map.view, ts);
    pass.set_pipeline(pipeline);
    scene.bind_frame(&mut pass, light);
    scene.draw_objects(&mut pass, |i| scene.casts_shadow(i) && keep(i))
}

/// The shadow pass's costs over every light, for a `size`² map, counted by
/// a [`Tally`] through `pipelines(light)` ([`shadow_tally_pipelines`]) into
/// a fresh map: `.0` its depth writes (the fragments that pass its `Less`
/// test, in draw order), `.1` the fragments it rasterises. Untimed: its
/// own submits.
///
/// The rasterised count differs between rasterisers by a few edge
/// fragments; the depth writes can differ more (near-equal depths of a
/// caster's overlapping faces can compare the other way: GL's depth
/// arrives through another range conversion, and GPUs round differently).
pub fn count_shadow_texels<'p>(
    gpu: &Gpu,
    scene: &SceneGpu,
    size: u32,
    pipelines: impl Fn(usize) -> &'p [wgpu::RenderPipeline; 2],
) -> Result<(u64, u64)> {
    let map = ShadowMap::new(gpu, size);
    let tally = Tally::new(gpu, size, size);
    let mut total = [0, 0];
    for (which, total) in total.iter_mut().enumerate() {
        *total = count_lights(gpu, scene, &map, &tally, |k| &pipelines(k)[which])?;
    }
    Ok((total[0], total[1]))
}

fn count_lights<'p>(
    gpu: &Gpu,
    scene: &SceneGpu,
    map: &ShadowMap,
    tally: &Tally,
    tally_pipeline: impl Fn(usize) -> &'p wgpu::RenderPipeline,
) -> Result<u64> {
    let mut total = 0;
    for light in 0..scene.scene.lights.len() {
        let depth = wgpu::RenderPassDepthStencilAttachment {
            view: &map.view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        };
        total += tally.count(gpu, Some(depth), |pass| {
            pass.set_pipeline(tally_pipeline(light));
            scene.bind_frame(pass, light);
            scene.draw_objects(pass, |i| scene.casts_shadow(i));
        })?;
    }
    Ok(total)
}

/// The runner's sub-texel move of the maps (`--fragile`,
/// `SceneGpu::light_jitter`), for lessons whose shadow pass and lit pass
/// both read the light buffer's matrix (01, 02, 03, 10): each light's own
/// matrix, moved for a `size`² map. Writes nothing unless the runner moves
/// the maps; it uploads the lights' own matrices again when it stops.
pub fn jitter_light_maps(gpu: &Gpu, scene: &SceneGpu, size: u32) {
    let jitter = scene.light_jitter.matrix(size);
    if jitter == Mat4::IDENTITY {
        return;
    }
    for k in 0..scene.scene.lights.len() {
        if let Some(m) = light_view_proj(&scene.scene, k) {
            scene.write_light_view_proj(gpu, k, jitter * m);
        }
    }
}

/// Draw calls of a frame of a shadow-map lesson: the base pass (every
/// object), then per light the shadow pass (every caster) and the lit
/// pass (every object).
pub fn shadow_map_draws(scene: &SceneGpu) -> u64 {
    let objects = scene.scene.objects.len() as u64;
    let casters = scene
        .scene
        .objects
        .iter()
        .filter(|o| o.casts_shadow)
        .count() as u64;
    objects + scene.scene.lights.len() as u64 * (casters + objects)
}

/// Refuses point lights: lessons 01–03 render one 2D map per light, which a
/// point light (lesson 04's cube map) cannot use.
pub fn refuse_point_lights(scene: &Scene, lesson: &str) -> Result<()> {
    match scene
        .lights
        .iter()
        .position(|l| matches!(l.kind, LightKind::Point { .. }))
    {
        Some(k) => anyhow::bail!(
            "lights[{k}]: {lesson} shadows directional and spot lights; point lights are lesson_04"
        ),
        None => Ok(()),
    }
}

// ANCHOR: shadow_map_layout
/// The lit pass samples the map at group 2: binding 0 the depth texture,
/// binding 1 a comparison sampler (`shaders/lesson_01/shadow_map.wgsl`).
pub fn shadow_map_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    use wgpu::{SamplerBindingType, TextureSampleType, TextureViewDimension};
    vec![
        texture_entry(0, TextureSampleType::Depth, TextureViewDimension::D2),
        sampler_entry(1, SamplerBindingType::Comparison),
    ]
}

/// The layout of [`shadow_map_entries`].
pub fn shadow_map_layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
    bindings::layout(gpu, "shadow map", &shadow_map_entries())
}
// ANCHOR_END: shadow_map_layout

// ANCHOR: shadow_map_group
/// The comparison sampler: the hardware answers `receiver <= stored` per
/// texel. `filter` Linear blends the 4 nearest answers (lesson 03's 2×2).
pub fn comparison_sampler(gpu: &Gpu, filter: wgpu::FilterMode) -> wgpu::Sampler {
    gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("shadow comparison"),
        address_mode_u: wgpu::AddressMode::ClampToEdge,
        address_mode_v: wgpu::AddressMode::ClampToEdge,
        mag_filter: filter,
        min_filter: filter,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    })
}

/// The bind group of [`shadow_map_layout`] for `map`.
pub fn shadow_map_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    map: &ShadowMap,
    filter: wgpu::FilterMode,
) -> wgpu::BindGroup {
    let sampler = comparison_sampler(gpu, filter);
    let resources = [
        wgpu::BindingResource::TextureView(&map.view),
        wgpu::BindingResource::Sampler(&sampler),
    ];
    bindings::group(gpu, "shadow map", layout, &resources)
}
// ANCHOR_END: shadow_map_group

const DEPTH_TO_BYTES_WGSL: &str = r#"
// The depth texture bound as unfilterable float: GLSL has no textureLoad on
// shadow samplers.
@group(0) @binding(0) var depth: texture_2d<f32>;
@fragment fn fs(in: FullscreenOut) -> @location(0) vec4<f32> {
    let d = textureLoad(depth, vec2<i32>(in.pos.xy), 0).r;
    // The float's bits, one byte per channel: exact on the way back.
    return unpack4x8unorm(bitcast<u32>(d));
}
"#;

// ---- the shader side, shared by lessons 01, 02 and 03 ---------------------

/// The WGSL that lessons 01, 02 and 03 share (`shaders/lesson_01/shadow_map.wgsl`):
/// the shadow map's bindings (group 2), the light-space transform and the
/// texel size.
pub const SHADOW_MAP_WGSL: &str = include_str!("../../shaders/lesson_01/shadow_map.wgsl");

/// Compiles `common.wgsl`, then `shadow_map.wgsl`, then a lesson's own WGSL.
pub fn shader_module(gpu: &Gpu, label: &str, lesson_wgsl: &str) -> wgpu::ShaderModule {
    scene_shader_module(
        gpu,
        label,
        &format!("{SHADOW_MAP_WGSL}\n// ---- {label} ----\n{lesson_wgsl}"),
    )
}

/// Compiles `common.wgsl`, then `shadow_map.wgsl`, then a lesson's WGSL
/// files given as (path, text), so that an error names its own file.
pub fn shader_module_from_files(
    gpu: &Gpu,
    label: &str,
    files: &[(&str, &str)],
) -> Result<wgpu::ShaderModule> {
    let mut all = vec![("shaders/lesson_01/shadow_map.wgsl", SHADOW_MAP_WGSL)];
    all.extend_from_slice(files);
    common::gpu::render::shader_module_from_files(gpu, label, &all)
}
