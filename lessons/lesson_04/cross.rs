//! A picture of the six cube faces, as a horizontal cross (a debug image,
//! readable on GL too): `<variant>_cube_map.png` and the "buffer" view.

use std::path::Path;

use anyhow::Result;
use common::gpu::bindings::{self, sampler_entry, texture_entry, uniform_buffer, uniform_entry};
use common::gpu::fullscreen::{read_floats, Fullscreen, FLOAT_BYTES_FORMAT};
use common::gpu::Gpu;
use common::run::files::save;
use common::run::instruments::BufferView;

use super::cube_map::{cube_group, CubeShadowMap};

const CROSS_WGSL: &str = r#"
// The cube bound as unfilterable float (GL cannot textureLoad a depth cube).
@group(0) @binding(0) var cube: texture_cube<f32>;
@group(0) @binding(1) var nearest: sampler;
@group(0) @binding(2) var<uniform> face_px: vec4<f32>;
// A horizontal cross: +Y above, then -X +Z +X -Z, then -Y below. Each cell is
// turned into the direction the sampler maps to it (the cube-map rules).
@fragment fn fs(in: FullscreenOut) -> @location(0) vec4<f32> {
    let p = in.pos;
    let cell = vec2<i32>(p.xy / face_px.x);
    let st = fract(p.xy / face_px.x) * 2.0 - 1.0;
    var d = vec3<f32>(0.0);
    if cell.y == 0 && cell.x == 1 { d = vec3<f32>(st.x, 1.0, st.y); }
    if cell.y == 2 && cell.x == 1 { d = vec3<f32>(st.x, -1.0, -st.y); }
    if cell.y == 1 && cell.x == 0 { d = vec3<f32>(-1.0, -st.y, st.x); }
    if cell.y == 1 && cell.x == 1 { d = vec3<f32>(st.x, -st.y, 1.0); }
    if cell.y == 1 && cell.x == 2 { d = vec3<f32>(1.0, -st.y, -st.x); }
    if cell.y == 1 && cell.x == 3 { d = vec3<f32>(-st.x, -st.y, -1.0); }
    var depth = -1.0;
    if any(d != vec3<f32>(0.0)) { depth = textureSampleLevel(cube, nearest, d, 0.0).r; }
    return unpack4x8unorm(bitcast<u32>(depth));
}
"#;

// The same cross from a faces map (`CubeShadowMap::new_faces`): its six
// layers +X -X +Y -Y +Z -Z as a 2D array at binding 3. Each cell shows its
// layer's texels as they lie: where the cube's sampler maps a cell's
// directions above, (s, t) runs with the cell's own x and y.
const FACES_CROSS_WGSL: &str = r#"
@group(0) @binding(3) var faces: texture_2d_array<f32>;
@group(0) @binding(1) var nearest: sampler;
@group(0) @binding(2) var<uniform> face_px: vec4<f32>;
@fragment fn fs(in: FullscreenOut) -> @location(0) vec4<f32> {
    let p = in.pos;
    let cell = vec2<i32>(p.xy / face_px.x);
    let uv = fract(p.xy / face_px.x);
    var layer = -1;
    if cell.y == 0 && cell.x == 1 { layer = 2; }
    if cell.y == 2 && cell.x == 1 { layer = 3; }
    if cell.y == 1 && cell.x == 0 { layer = 1; }
    if cell.y == 1 && cell.x == 1 { layer = 4; }
    if cell.y == 1 && cell.x == 2 { layer = 0; }
    if cell.y == 1 && cell.x == 3 { layer = 5; }
    var depth = -1.0;
    if layer >= 0 { depth = textureSampleLevel(faces, nearest, uv, layer, 0.0).r; }
    return unpack4x8unorm(bitcast<u32>(depth));
}
"#;

/// The six faces as a cross (`face_px` pixels per face): near dark, far
/// light, stretched over the depths the map holds; white where no caster
/// wrote; background black.
pub fn cross_image(gpu: &Gpu, map: &CubeShadowMap, face_px: u32) -> Result<image::GrayImage> {
    use wgpu::{SamplerBindingType, ShaderStages, TextureSampleType, TextureViewDimension};
    // The cube bound as unfilterable floats: GL cannot `textureLoad` a depth cube.
    let float = TextureSampleType::Float { filterable: false };
    let (binding, dimension, wgsl) = match map.faces {
        false => (0, TextureViewDimension::Cube, CROSS_WGSL),
        true => (3, TextureViewDimension::D2Array, FACES_CROSS_WGSL),
    };
    let entries = [
        texture_entry(binding, float, dimension),
        sampler_entry(1, SamplerBindingType::NonFiltering),
        uniform_entry(2, ShaderStages::FRAGMENT, false, None),
    ];
    let layout = bindings::layout(gpu, "cube cross", &entries);
    let sampler = gpu
        .device
        .create_sampler(&wgpu::SamplerDescriptor::default());
    let px = [face_px as f32, 0.0, 0.0, 0.0];
    let buf = uniform_buffer(gpu, "cube cross", bytemuck::bytes_of(&px));
    let group = cube_group(gpu, &layout, map, &sampler, &buf);
    let pipeline =
        Fullscreen::image("cube cross", wgsl, "fs", &[&layout], FLOAT_BYTES_FORMAT).pipeline(gpu);
    let (w, h) = (4 * face_px, 3 * face_px);
    let d = read_floats(gpu, &pipeline, &group, (w, h))?;
    let lo = d
        .iter()
        .copied()
        .filter(|&x| x >= 0.0)
        .fold(f32::INFINITY, f32::min);
    let hi = d
        .iter()
        .copied()
        .filter(|x| (0.0..1.0).contains(x))
        .fold(lo, f32::max);
    let span = (hi - lo).max(1e-12);
    Ok(image::GrayImage::from_fn(w, h, |x, y| {
        let v = d[(y * w + x) as usize];
        image::Luma([if v < 0.0 {
            0
        } else if v >= 1.0 {
            255
        } else {
            20 + (((v - lo) / span) * 215.0).round() as u8
        }])
    }))
}

/// Writes [`cross_image`] to `path`.
pub fn write_cross_png(gpu: &Gpu, map: &CubeShadowMap, face_px: u32, path: &Path) -> Result<()> {
    save(&cross_image(gpu, map, face_px)?, path)
}

/// The "buffer" view: [`cross_image`] of `map`, up to 256 pixels a face,
/// which light `light` (the last one drawn into it) left.
pub fn cross_view(gpu: &Gpu, map: &CubeShadowMap, light: usize) -> Result<BufferView> {
    let px = map.size.min(256);
    let cross = cross_image(gpu, map, px)?;
    let title = format!(
        "cube map of light {light} (the last light drawn into it), {0}x{0} a face, as a cross: +Y on top; -X, +Z, +X, -Z across; -Y below; the stored value (distance / range, or hardware depth: the variant's storage), near dark, far light, stretched over the values stored; white: never written; black: outside the cross",
        map.size
    );
    let image = image::DynamicImage::ImageLuma8(cross).to_rgba8();
    Ok(BufferView { title, image })
}
