//! Depth bounds and scissor for a light of limited range (lesson 08).
//!
//! A point light of range r lights nothing outside its range sphere. So a
//! shadow volume fragment can only matter at a pixel whose *stored* scene
//! depth lies inside the sphere's window-depth interval [zmin, zmax], and
//! inside the sphere's screen rectangle. Both come from the same sphere:
//! [`sphere_depth_bounds`] and [`sphere_scissor`].
//!
//! wgpu has no depth-bounds test (`VK_EXT_depth_bounds_test`,
//! `GL_EXT_depth_bounds_test`). [`DepthBoundsMarker`] emulates it with two
//! quads and the fixed-function depth test: stencil bit 7 is set exactly
//! where zmin ≤ stored depth ≤ zmax, and the volume pass tests that bit.
//! [`FragmentCounter`] counts the fragments that reach the stencil update
//! with an occlusion query (core WebGPU, so it works on GL too).

use anyhow::Result;
use glam::{DMat4, DVec3, DVec4};

use crate::gpu::Gpu;
use crate::render::{pipeline_layout_for, FrameTargets, SceneGpu};
use crate::shadow_volume::{
    lit_stencil, volume_shader_module, volume_stencil, FragmentCounter, Method, ShadowVolumes,
    QUAD_VERTEX_LAYOUT,
};

/// Bit 7 of the stencil: "this pixel's stored depth is inside the bounds".
pub const BOUNDS_BIT: u32 = 0x80;
/// Bits 0–6: the shadow-volume count (wraps modulo 128).
pub const COUNT_BITS: u32 = 0x7f;

/// Widens the range sphere a little, so that a point the lit shader finds
/// at distance ≤ r (in f32) is inside the bounds computed here (in f64).
pub const SPHERE_MARGIN: f64 = 1e-3;
/// Widens the depth interval by a few 24-bit steps for the same reason.
pub const DEPTH_MARGIN: f64 = 4.0 / 16_777_215.0;

/// The window depth of view distance `d` (> 0) under projection `proj`
/// (right-handed, [0, 1] depth; finite, infinite or reversed alike).
pub fn window_depth(proj: DMat4, d: f64) -> f64 {
    let c = proj * DVec4::new(0.0, 0.0, -d, 1.0);
    c.z / c.w
}

// ANCHOR: sphere_depth_bounds
/// [zmin, zmax] in window depth of a sphere (centre in *view* space, radius
/// r), for a camera with this `near` distance and projection (depth growing
/// with distance). `None` when the sphere lies wholly behind the near plane.
/// A sphere crossing the near plane starts at depth 0.
pub fn sphere_depth_bounds(
    proj: DMat4,
    near: f64,
    centre_view: DVec3,
    r: f64,
) -> Option<(f32, f32)> {
    let r = r * (1.0 + SPHERE_MARGIN);
    let d = -centre_view.z; // distance along the view axis
    let (d_near, d_far) = (d - r, d + r);
    if d_far <= near {
        return None;
    }
    let zmin = if d_near <= near {
        0.0
    } else {
        window_depth(proj, d_near) - DEPTH_MARGIN
    };
    // Past a finite far plane the depth exceeds 1: the bound is then 1.
    let zmax = window_depth(proj, d_far) + DEPTH_MARGIN;
    Some((zmin.clamp(0.0, 1.0) as f32, zmax.clamp(0.0, 1.0) as f32))
}
// ANCHOR_END: sphere_depth_bounds

/// A scissor rectangle in pixels (x, y from the top left).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Scissor {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

impl Scissor {
    pub fn full(w: u32, h: u32) -> Scissor {
        Scissor {
            x: 0,
            y: 0,
            width: w,
            height: h,
        }
    }

    pub fn area(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    pub fn contains(&self, px: u32, py: u32) -> bool {
        px >= self.x && py >= self.y && px < self.x + self.width && py < self.y + self.height
    }
}

// ANCHOR: axis_bounds
/// One axis of the sphere's projection (Mara & McGuire 2013, "2D polyhedral
/// bounds of a clipped, perspective-projected 3D sphere"). In the plane of
/// the axis `a` (x or y) and the view axis z, the circle (ca, cz, r) is seen
/// from the eye between its two tangent points; a tangent point in front of
/// the near plane (z > −near) is replaced by where the circle crosses it.
/// Returns the two bounding points as (a, z), z < 0.
fn axis_bounds(ca: f64, cz: f64, r: f64, near: f64) -> [(f64, f64); 2] {
    let near_z = -near;
    let crosses_near = cz + r > near_z;
    let t2 = ca * ca + cz * cz - r * r; // squared tangent length
    let len = (ca * ca + cz * cz).sqrt();
    let mut out = [(0.0, 0.0); 2];
    for (i, s) in [1.0f64, -1.0].into_iter().enumerate() {
        let mut p = (f64::NAN, f64::NAN);
        if t2 > 0.0 {
            // Rotate the centre direction by ±θ (sin θ = r/len), scale by cos θ.
            let (cos, sin) = (t2.sqrt() / len, s * r / len);
            p = (cos * (cos * ca + sin * cz), cos * (-sin * ca + cos * cz));
        }
        if crosses_near && (t2 <= 0.0 || p.1 > near_z) {
            let half_chord = (r * r - (near_z - cz).powi(2)).max(0.0).sqrt();
            p = (ca + s * half_chord, near_z);
        }
        out[i] = p;
    }
    out
}
// ANCHOR_END: axis_bounds

// ANCHOR: sphere_scissor
/// The pixel rectangle that holds the sphere's image (centre in view space),
/// for a `w × h` target. The camera inside the sphere sees it everywhere:
/// the full screen. `None` when the sphere is behind the near plane or off
/// screen.
pub fn sphere_scissor(
    proj: DMat4,
    near: f64,
    centre_view: DVec3,
    r: f64,
    w: u32,
    h: u32,
) -> Option<Scissor> {
    let r = r * (1.0 + SPHERE_MARGIN);
    let c = centre_view;
    if c.length() <= r {
        return Some(Scissor::full(w, h));
    }
    if c.z - r >= -near {
        return None;
    }
    // NDC of a point (a, z) on one axis: proj[a][a] · a / −z.
    let ndc = |scale: f64, (a, z): (f64, f64)| scale * a / -z;
    let xs = axis_bounds(c.x, c.z, r, near).map(|p| ndc(proj.x_axis.x, p));
    let ys = axis_bounds(c.y, c.z, r, near).map(|p| ndc(proj.y_axis.y, p));
    let (x0, x1) = (xs[0].min(xs[1]).max(-1.0), xs[0].max(xs[1]).min(1.0));
    let (y0, y1) = (ys[0].min(ys[1]).max(-1.0), ys[0].max(ys[1]).min(1.0));
    if x0 >= x1 || y0 >= y1 {
        return None;
    }
    // NDC → pixels: x right, y down; round outwards.
    let px0 = ((x0 + 1.0) * 0.5 * w as f64).floor() as u32;
    let px1 = (((x1 + 1.0) * 0.5 * w as f64).ceil() as u32).min(w);
    let py0 = ((1.0 - y1) * 0.5 * h as f64).floor() as u32;
    let py1 = (((1.0 - y0) * 0.5 * h as f64).ceil() as u32).min(h);
    (px1 > px0 && py1 > py0).then(|| Scissor {
        x: px0,
        y: py0,
        width: px1 - px0,
        height: py1 - py0,
    })
}
// ANCHOR_END: sphere_scissor

/// The bounds of one light for one camera: `None` when the light can affect
/// nothing on screen (its volumes need not be drawn at all).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    pub depth: (f32, f32),
    pub scissor: Scissor,
}

/// Depth bounds and scissor of a point or spot light's range sphere
/// (`centre` origin-relative world space).
pub fn light_bounds(
    view: DMat4,
    proj: DMat4,
    near: f64,
    centre: DVec3,
    range: f64,
    w: u32,
    h: u32,
) -> Option<LightBounds> {
    let c = view.transform_point3(centre);
    let depth = sphere_depth_bounds(proj, near, c, range)?;
    let scissor = sphere_scissor(proj, near, c, range, w, h)?;
    Some(LightBounds { depth, scissor })
}

// ---- the emulation on the GPU ------------------------------------------

/// The marker quads: a full-screen triangle at one window depth, read from
/// `bounds` = (zmin, zmax) of the light (group 2, dynamic offset per light).
const MARKER_WGSL: &str = r#"
@group(2) @binding(0) var<uniform> bounds: vec4<f32>;

fn full_screen(vi: u32, z: f32) -> vec4<f32> {
    let uv = vec2<f32>(f32((vi << 1u) & 2u), f32(vi & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, z, 1.0);
}

@vertex
fn vs_bound_max(@builtin(vertex_index) vi: u32) -> @builtin(position) vec4<f32> {
    return full_screen(vi, bounds.y);
}

@vertex
fn vs_bound_min(@builtin(vertex_index) vi: u32) -> @builtin(position) vec4<f32> {
    return full_screen(vi, bounds.x);
}
"#;

const SLOT: u64 = 256;

/// One caster's pre-built volume (the quads path of `shadow_volume`),
/// uploaded again here so that this module can draw it with its own
/// pipelines.
struct Caster {
    object: usize,
    mirrored: bool,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
}

/// Z-fail shadow volumes whose stencil updates can be limited to one
/// light's depth bounds (emulated) and scissor rectangle.
pub struct BoundedVolumes {
    casters: Vec<Caster>,
    /// `[bounded][mirrored]`: the z-fail pipelines.
    volume: [[wgpu::RenderPipeline; 2]; 2],
    /// `[bounded]`: depth test off, no writes: counts what reaches the stencil.
    count: [wgpu::RenderPipeline; 2],
    /// No depth-stencil, an R8 target: for the pipeline-statistics counter.
    rasterised: wgpu::RenderPipeline,
    mark_max: wgpu::RenderPipeline,
    mark_min: wgpu::RenderPipeline,
    bounds_buf: wgpu::Buffer,
    bounds_group: wgpu::BindGroup,
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    lights: u32,
}

/// Which of the two savings a volume pass uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Limits {
    pub scissor: bool,
    pub depth_bounds: bool,
}

// ANCHOR: bounds_stencil
/// The volume pass's stencil with the emulated depth-bounds test: a
/// fragment updates the count only where bit 7 says "stored depth in
/// bounds" (compare Equal on bit 7 alone); the count lives in bits 0–6.
pub fn bounded_volume_stencil(bounded: bool) -> wgpu::StencilState {
    let mut s = volume_stencil(Method::ZFail);
    for face in [&mut s.front, &mut s.back] {
        face.compare = if bounded {
            wgpu::CompareFunction::Equal
        } else {
            wgpu::CompareFunction::Always
        };
    }
    s.read_mask = BOUNDS_BIT;
    s.write_mask = COUNT_BITS;
    s
}

/// Stencil bit 7 := [stored depth ≤ zmax] (a quad at zmax, test GreaterEqual),
/// then bit 7 := 0 where stored depth < zmin (a quad at zmin, test Greater).
fn marker_stencil(
    pass_op: wgpu::StencilOperation,
    depth_fail_op: wgpu::StencilOperation,
) -> wgpu::StencilState {
    let face = wgpu::StencilFaceState {
        compare: wgpu::CompareFunction::Always,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op,
        pass_op,
    };
    wgpu::StencilState {
        front: face,
        back: face,
        read_mask: 0xff,
        write_mask: BOUNDS_BIT,
    }
}

/// The lit pass: the light where the count (bits 0–6) is 0.
pub fn bounded_lit_stencil() -> wgpu::StencilState {
    let mut s = lit_stencil();
    s.read_mask = COUNT_BITS;
    s
}
// ANCHOR_END: bounds_stencil

impl BoundedVolumes {
    pub fn new(gpu: &Gpu, scene: &SceneGpu, volumes: &ShadowVolumes) -> Result<BoundedVolumes> {
        let device = &gpu.device;
        // The same pre-built quads as lessons 05-07 draw: shared buffers.
        let casters = volumes
            .casters
            .iter()
            .map(|c| {
                let (vertices, indices, count) = c.quad_buffers();
                Caster {
                    object: c.object,
                    mirrored: c.mirrored,
                    vertices,
                    indices,
                    count,
                }
            })
            .collect();
        let module = volume_shader_module(gpu, "bounded volumes", MARKER_WGSL);
        let bounds_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("depth bounds"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: wgpu::BufferSize::new(16),
                },
                count: None,
            }],
        });
        let lights = scene.scene.lights.len().max(1) as u32;
        let bounds_buf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("depth bounds"),
            size: SLOT * lights as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bounds_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("depth bounds"),
            layout: &bounds_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &bounds_buf,
                    offset: 0,
                    size: wgpu::BufferSize::new(16),
                }),
            }],
        });
        let layout = pipeline_layout_for(
            gpu,
            &scene.frame_layout,
            &scene.object_layout,
            &[&bounds_layout],
        );
        let quads = [Some(QUAD_VERTEX_LAYOUT)];
        let targets = [Some(wgpu::TextureFormat::R8Unorm.into())];
        let make = |label: &str,
                    vs: &str,
                    buffers: &[Option<wgpu::VertexBufferLayout<'static>>],
                    cull: bool,
                    ds: Option<wgpu::DepthStencilState>,
                    mirrored: bool| {
            let fragment = ds.is_none().then(|| wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_volume_count"),
                compilation_options: Default::default(),
                targets: &targets,
            });
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState {
                    front_face: if mirrored {
                        wgpu::FrontFace::Cw
                    } else {
                        wgpu::FrontFace::Ccw
                    },
                    cull_mode: cull.then_some(wgpu::Face::Back),
                    ..Default::default()
                },
                depth_stencil: ds,
                multisample: Default::default(),
                fragment,
                multiview_mask: None,
                cache: None,
            })
        };
        let ds = |compare, stencil| {
            Some(wgpu::DepthStencilState {
                format: scene.depth_format,
                depth_write_enabled: Some(false),
                depth_compare: Some(compare),
                stencil,
                bias: Default::default(),
            })
        };
        use wgpu::CompareFunction::{Always, Greater, GreaterEqual, Less};
        use wgpu::StencilOperation::{Keep, Replace, Zero};
        let volume = |bounded: bool, m: bool| {
            make(
                "bounded volume",
                "vs_volume_quads",
                &quads,
                false,
                ds(Less, bounded_volume_stencil(bounded)),
                m,
            )
        };
        let counting = |bounded: bool| {
            let mut st = bounded_volume_stencil(bounded);
            st.write_mask = 0;
            make(
                "bounded volume count",
                "vs_volume_quads",
                &quads,
                false,
                ds(Always, st),
                false,
            )
        };
        let queries = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("bounded fragments"),
            ty: wgpu::QueryType::Occlusion,
            count: lights,
        });
        let buffer = |usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bounded fragments"),
                size: 8 * lights as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        Ok(BoundedVolumes {
            casters,
            volume: [
                [volume(false, false), volume(false, true)],
                [volume(true, false), volume(true, true)],
            ],
            count: [counting(false), counting(true)],
            rasterised: make(
                "volume fragments",
                "vs_volume_quads",
                &quads,
                false,
                None,
                false,
            ),
            mark_max: make(
                "depth bounds max",
                "vs_bound_max",
                &[],
                true,
                ds(GreaterEqual, marker_stencil(Replace, Zero)),
                false,
            ),
            mark_min: make(
                "depth bounds min",
                "vs_bound_min",
                &[],
                true,
                ds(Greater, marker_stencil(Zero, Keep)),
                false,
            ),
            bounds_buf,
            bounds_group,
            queries,
            resolve: buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read: buffer(wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
            lights,
        })
    }

    /// Uploads light `k`'s depth bounds (before the frame is submitted).
    pub fn write_bounds(&self, gpu: &Gpu, k: usize, b: &LightBounds) {
        let v = [b.depth.0, b.depth.1, 0.0, 0.0];
        gpu.queue
            .write_buffer(&self.bounds_buf, SLOT * k as u64, bytemuck::cast_slice(&v));
    }

    fn draw_volumes(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        scene: &SceneGpu,
        light: usize,
        pipes: [&wgpu::RenderPipeline; 2],
    ) -> u32 {
        scene.bind_frame(pass, light);
        pass.set_bind_group(2, &self.bounds_group, &[(SLOT * light as u64) as u32]);
        for c in &self.casters {
            pass.set_pipeline(pipes[c.mirrored as usize]);
            scene.bind_object(pass, c.object);
            pass.set_vertex_buffer(0, c.vertices.slice(..));
            pass.set_index_buffer(c.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..c.count, 0, 0..1);
        }
        self.casters.len() as u32
    }

    /// Scissor and the bit-7 marker for one light, inside an open pass.
    fn limit(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        scene: &SceneGpu,
        light: usize,
        bounds: Option<&LightBounds>,
        limits: Limits,
    ) {
        let Some(b) = bounds else { return };
        if limits.scissor {
            pass.set_scissor_rect(b.scissor.x, b.scissor.y, b.scissor.width, b.scissor.height);
        }
        if limits.depth_bounds {
            // Every group of the layout must be bound, used or not.
            scene.bind_frame(pass, light);
            scene.bind_object(pass, 0);
            pass.set_bind_group(2, &self.bounds_group, &[(SLOT * light as u64) as u32]);
            pass.set_stencil_reference(BOUNDS_BIT);
            pass.set_pipeline(&self.mark_max);
            pass.draw(0..3, 0..1);
            pass.set_pipeline(&self.mark_min);
            pass.draw(0..3, 0..1);
        }
    }

    // ANCHOR: bounded_volume_pass
    /// One light's z-fail volume pass, limited as `limits` says. `bounds`
    /// is `None` for a light without a range (directional): no limits.
    /// Returns the number of casters drawn (0 when the light's sphere is
    /// off screen: its volumes cannot change a lit pixel).
    #[allow(clippy::too_many_arguments)]
    pub fn volume_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &SceneGpu,
        targets: &FrameTargets,
        light: usize,
        bounds: Option<Option<LightBounds>>,
        limits: Limits,
        ts: Option<wgpu::RenderPassTimestampWrites>,
    ) -> u32 {
        let mut pass = targets.stencil_pass(encoder, "bounded volume pass", ts, None);
        let limited = limits != Limits::default();
        if limited && bounds == Some(None) {
            return 0; // the range sphere is behind the camera or off screen
        }
        let b = bounds.flatten();
        self.limit(&mut pass, scene, light, b.as_ref(), limits);
        let bounded = limits.depth_bounds && b.is_some();
        pass.set_stencil_reference(BOUNDS_BIT);
        self.draw_volumes(
            &mut pass,
            scene,
            light,
            [
                &self.volume[bounded as usize][0],
                &self.volume[bounded as usize][1],
            ],
        )
    }
    // ANCHOR_END: bounded_volume_pass

    /// Counts, for every light, the volume fragments that reach the stencil
    /// update (after scissor and bounds), with one occlusion query per light
    /// (depth test off). Uses the frame's depth: call it after a frame.
    /// Its own submit; it overwrites the stencil. `None` on GL: wgpu's GL
    /// backend implements occlusion queries as ANY_SAMPLES_PASSED (0 or 1).
    pub fn count_stencil_fragments(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        targets: &FrameTargets,
        bounds: &[Option<Option<LightBounds>>],
        limits: Limits,
    ) -> Result<Option<Vec<u64>>> {
        if gpu.info.backend == wgpu::Backend::Gl {
            return Ok(None);
        }
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        for (k, b) in bounds.iter().enumerate().take(self.lights as usize) {
            let mut pass = targets.stencil_pass(
                &mut enc,
                "count bounded fragments",
                None,
                Some(&self.queries),
            );
            let limited = limits != Limits::default();
            if limited && *b == Some(None) {
                // Nothing drawn: an empty query reads 0.
                pass.begin_occlusion_query(k as u32);
                pass.end_occlusion_query();
                continue;
            }
            let lb = b.flatten();
            // The marker quads first, outside the query: only volumes count.
            self.limit(&mut pass, scene, k, lb.as_ref(), limits);
            let bounded = limits.depth_bounds && lb.is_some();
            pass.set_stencil_reference(BOUNDS_BIT);
            pass.begin_occlusion_query(k as u32);
            self.draw_volumes(&mut pass, scene, k, [&self.count[bounded as usize]; 2]);
            pass.end_occlusion_query();
        }
        let n = bounds.len().min(self.lights as usize) as u32;
        enc.resolve_query_set(&self.queries, 0..n, &self.resolve, 0);
        enc.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 8 * n as u64);
        gpu.queue.submit([enc.finish()]);
        let slice = self.read.slice(..8 * n as u64);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        gpu.wait()?;
        let out = {
            let view = slice
                .get_mapped_range()
                .map_err(|e| anyhow::anyhow!("occlusion query readback: {e}"))?;
            bytemuck::cast_slice::<u8, u64>(&view).to_vec()
        };
        self.read.unmap();
        Ok(Some(out))
    }

    /// Fragments the volumes rasterise (after the scissor, before any depth
    /// or stencil test), from pipeline statistics; `None` without them (GL).
    pub fn count_rasterised(
        &self,
        gpu: &Gpu,
        scene: &SceneGpu,
        counter: Option<&FragmentCounter>,
        bounds: &[Option<Option<LightBounds>>],
        scissor: bool,
    ) -> Option<u64> {
        let counter = counter?;
        counter
            .count(gpu, |pass| {
                for (k, b) in bounds.iter().enumerate() {
                    if scissor && *b == Some(None) {
                        continue;
                    }
                    match b.flatten() {
                        Some(lb) if scissor => pass.set_scissor_rect(
                            lb.scissor.x,
                            lb.scissor.y,
                            lb.scissor.width,
                            lb.scissor.height,
                        ),
                        _ => pass.set_scissor_rect(0, 0, scene.width, scene.height),
                    }
                    self.draw_volumes(pass, scene, k, [&self.rasterised; 2]);
                }
            })
            .ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::dcamera::rh::proj::directx::{perspective, perspective_infinite};

    const W: u32 = 640;
    const H: u32 = 360;

    fn proj() -> DMat4 {
        perspective(50f64.to_radians(), W as f64 / H as f64, 0.1, 100.0)
    }

    /// Points on the sphere and on its cut by the near plane that the
    /// camera sees (in front of the near plane).
    fn visible_samples(c: DVec3, r: f64, near: f64) -> Vec<DVec3> {
        let mut v = Vec::new();
        for i in 0..200 {
            for j in 0..400 {
                let th = std::f64::consts::PI * (i as f64 + 0.5) / 200.0;
                let ph = std::f64::consts::TAU * j as f64 / 400.0;
                v.push(c + r * DVec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()));
            }
        }
        let dz = -near - c.z;
        if dz.abs() < r {
            let rr = (r * r - dz * dz).sqrt();
            for k in 0..2000 {
                let a = std::f64::consts::TAU * k as f64 / 2000.0;
                v.push(DVec3::new(c.x + rr * a.cos(), c.y + rr * a.sin(), -near));
            }
        }
        v.retain(|p| p.z <= -near);
        v
    }

    fn pixel_of(p: DMat4, q: DVec3) -> (f64, f64) {
        let c = p * q.extend(1.0);
        (
            (c.x / c.w + 1.0) * 0.5 * W as f64,
            (1.0 - c.y / c.w) * 0.5 * H as f64,
        )
    }

    /// The rectangle contains every sample and is tight to within 2 pixels.
    fn check_scissor(c: DVec3, r: f64) {
        let p = proj();
        let s = sphere_scissor(p, 0.1, c, r, W, H).expect("visible sphere");
        let (mut lo, mut hi) = ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN));
        for q in visible_samples(c, r, 0.1) {
            let (x, y) = pixel_of(p, q);
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        }
        let (lo, hi) = (
            (lo.0.max(0.0), lo.1.max(0.0)),
            (hi.0.min(W as f64), hi.1.min(H as f64)),
        );
        let (x0, y0, x1, y1) = (
            s.x as f64,
            s.y as f64,
            (s.x + s.width) as f64,
            (s.y + s.height) as f64,
        );
        assert!(
            x0 <= lo.0 && y0 <= lo.1 && x1 >= hi.0 && y1 >= hi.1,
            "{s:?} misses samples {lo:?}..{hi:?}"
        );
        let slack = (lo.0 - x0).max(lo.1 - y0).max(x1 - hi.0).max(y1 - hi.1);
        assert!(
            slack <= 2.0 + r * 0.01 * W as f64 / c.z.abs(),
            "{s:?} is loose around {lo:?}..{hi:?} (slack {slack})"
        );
    }

    #[test]
    fn scissor_bounds_a_sphere_in_front_of_the_camera() {
        check_scissor(DVec3::new(0.0, 0.0, -10.0), 2.0);
        check_scissor(DVec3::new(3.0, -1.5, -8.0), 1.0);
        check_scissor(DVec3::new(-6.0, 2.0, -7.0), 3.0);
    }

    #[test]
    fn scissor_handles_a_sphere_crossing_the_near_plane() {
        // The centre is behind the camera's near plane, off axis.
        check_scissor(DVec3::new(0.9, 0.0, -0.3), 0.8);
        check_scissor(DVec3::new(1.0, -0.4, -0.2), 0.9);
        check_scissor(DVec3::new(-0.5, 0.6, 0.2), 0.7);
    }

    #[test]
    fn camera_inside_the_sphere_gives_the_full_screen() {
        let s = sphere_scissor(proj(), 0.1, DVec3::new(0.3, 0.1, -0.5), 2.0, W, H);
        assert_eq!(s, Some(Scissor::full(W, H)));
        let b = sphere_depth_bounds(proj(), 0.1, DVec3::new(0.3, 0.1, -0.5), 2.0).unwrap();
        assert_eq!(b.0, 0.0, "a sphere around the camera starts at depth 0");
    }

    #[test]
    fn a_sphere_behind_the_camera_is_culled() {
        assert_eq!(
            sphere_scissor(proj(), 0.1, DVec3::new(0.0, 0.0, 5.0), 2.0, W, H),
            None
        );
        assert_eq!(
            sphere_depth_bounds(proj(), 0.1, DVec3::new(0.0, 0.0, 5.0), 2.0),
            None
        );
    }

    #[test]
    fn depth_bounds_hold_every_point_of_the_sphere() {
        for p in [
            proj(),
            perspective_infinite(50f64.to_radians(), W as f64 / H as f64, 0.1),
        ] {
            for (c, r) in [
                (DVec3::new(1.0, 0.0, -10.0), 3.0),
                (DVec3::new(0.0, 1.0, -0.5), 1.0),
                (DVec3::new(0.0, 0.0, -90.0), 20.0),
            ] {
                let (zmin, zmax) = sphere_depth_bounds(p, 0.1, c, r).unwrap();
                let (mut lo, mut hi) = (f64::MAX, f64::MIN);
                for q in visible_samples(c, r, 0.1) {
                    let z = window_depth(p, -q.z).min(1.0);
                    lo = lo.min(z);
                    hi = hi.max(z);
                }
                assert!(
                    zmin as f64 <= lo && zmax as f64 >= hi,
                    "[{zmin}, {zmax}] misses [{lo}, {hi}] for {c:?} r {r}"
                );
                // Tight: the interval is no wider than the margins allow.
                assert!(
                    hi - lo > 0.0 && (zmax as f64 - hi) < 1e-3 && (lo - zmin as f64) < 1e-3,
                    "[{zmin}, {zmax}] vs [{lo}, {hi}]"
                );
                if c.z + r * (1.0 + SPHERE_MARGIN) > -0.1 {
                    assert_eq!(zmin, 0.0, "crossing the near plane starts at 0");
                }
            }
        }
    }
}
