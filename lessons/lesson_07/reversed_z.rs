//! Reversed-Z with a float depth buffer (lesson 07): near → 1, infinity → 0,
//! in `Depth32FloatStencil8`. Window depth n/d puts far distances near 0,
//! where float32 is dense, so a centimetre stays resolvable hundreds of
//! units away. The far plane stays at infinity: the back cap (w = 0) lands
//! on depth 0 exactly, with no ε.
//!
//! Every depth test flips: the base pass clears to 0 and keeps `Greater`,
//! the volumes count with `Greater` (z-fail's "depth fail" is still
//! "behind the surface", now the *smaller* depth), the caps are pushed back
//! by a *negative* bias, and the lit pass tests `GreaterEqual`.

use anyhow::{bail, Result};
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec3, DVec4};
use common::gpu::lit::LitPass;
use common::gpu::render::{base_pipeline, pipeline_layout_for, SceneGpu};
use common::gpu::targets::{render_texture, FrameTargets};
use common::gpu::Gpu;
use common::measure::timing::Frame;
use common::scene::camera::lens_shift;

use crate::lesson_05::extrusion::volume_shader_module;
use crate::lesson_05::quads::QUAD_VERTEX_LAYOUT;
use crate::lesson_05::stencil::lit_stencil;
use crate::lesson_05::volumes::ShadowVolumes;
use crate::lesson_06::caps::{zfail_stencil, CAP_DEPTH_BIAS};

/// The depth-stencil format of reversed-Z: float depth, 8-bit stencil.
pub const REVERSED_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32FloatStencil8;

// ANCHOR: reversed_infinite_perspective
/// Right-handed perspective, WebGPU depth, near → 1 and infinity → 0: the
/// third row is (0, 0, 0, n), so clip z = n·w and window depth = n/d. A
/// point at infinity (w = 0) gets z = 0 exactly: on the far boundary, and
/// no rounding can push it outside, since 0·anything is 0.
pub fn reversed_infinite_perspective(fov_y_rad: f64, aspect: f64, near: f64) -> DMat4 {
    let h = 1.0 / (0.5 * fov_y_rad).tan();
    DMat4::from_cols(
        DVec4::new(h / aspect, 0.0, 0.0, 0.0),
        DVec4::new(0.0, h, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 0.0, -1.0),
        DVec4::new(0.0, 0.0, near, 0.0),
    )
}
// ANCHOR_END: reversed_infinite_perspective

// ANCHOR: reversed_states
/// Caps pushed *back*: in reversed-Z, back is towards 0, so the bias of
/// lesson 06 changes sign.
pub const REVERSED_CAP_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: -CAP_DEPTH_BIAS.constant,
    slope_scale: -CAP_DEPTH_BIAS.slope_scale,
    clamp: 0.0,
};

/// The depth state of every reversed-Z pass: the test flips to `Greater`.
fn reversed_depth(
    compare: wgpu::CompareFunction,
    write: bool,
    stencil: wgpu::StencilState,
    bias: wgpu::DepthBiasState,
) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: REVERSED_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil,
        bias,
    }
}
// ANCHOR_END: reversed_states

/// The reversed-Z frame: its own camera, depth buffer and pipelines; the
/// colour, id and visibility images are the runner's.
pub struct ReversedZ {
    pub scene: SceneGpu,
    depth: wgpu::Texture,
    depth_view: wgpu::TextureView,
    /// The scene's origin (`Scene::origin`), found once.
    origin: DVec3,
    base: wgpu::RenderPipeline,
    /// `[mirrored][cap]`, z-fail with `Greater`.
    volumes: [[wgpu::RenderPipeline; 2]; 2],
    lit: wgpu::RenderPipeline,
}

impl ReversedZ {
    /// Its depth-stencil texture, as the last frame left it.
    pub fn depth_stencil(&self) -> &wgpu::Texture {
        &self.depth
    }

    /// Fails with one line where the adapter lacks `Depth32FloatStencil8`.
    pub fn new(gpu: &Gpu, scene: &SceneGpu) -> Result<ReversedZ> {
        if !gpu.has(wgpu::Features::DEPTH32FLOAT_STENCIL8) {
            bail!(
                "reversed-Z needs Depth32FloatStencil8 (DEPTH32FLOAT_STENCIL8), which {} does not have",
                gpu.adapter_name()
            );
        }
        // wgpu's GL backend appends `z = 2z − w` to every vertex shader (GL's
        // [−1, 1] depth): in f32, 2n − d loses exactly the small n/d we keep.
        if gpu.info.backend == wgpu::Backend::Gl {
            bail!("wgpu's GL backend rewrites clip z to 2z − w in f32, which discards reversed-Z's precision; run it with --backend vulkan (or metal, dx12)");
        }
        let mut s = SceneGpu::new(gpu, scene.scene.clone(), scene.width, scene.height)?;
        // The objects never move (a frame takes only the camera and the
        // lights), so their origin is found once: a pass over every vertex.
        let origin = s.scene.origin();
        set_reversed_camera(gpu, &mut s, origin);
        let none = wgpu::TextureUsages::empty();
        let depth = render_texture(
            gpu,
            "reversed depth",
            s.width,
            s.height,
            REVERSED_FORMAT,
            none,
        );
        let device = &gpu.device;
        let layout = pipeline_layout_for(gpu, &s.frame_layout, &s.object_layout, &[]);
        use wgpu::CompareFunction::{Greater, GreaterEqual};
        let base = base_pipeline(
            gpu,
            &s.frame_layout,
            &s.object_layout,
            reversed_depth(Greater, true, Default::default(), Default::default()),
        );
        let vmod = volume_shader_module(gpu, "reversed shadow volume", "");
        let volume = |front_face, cap: bool| {
            let bias = if cap {
                REVERSED_CAP_BIAS
            } else {
                Default::default()
            };
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("reversed shadow volume"),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &vmod,
                    entry_point: Some("vs_volume_quads"),
                    compilation_options: Default::default(),
                    buffers: &[Some(QUAD_VERTEX_LAYOUT)],
                },
                primitive: wgpu::PrimitiveState {
                    front_face,
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(reversed_depth(Greater, false, zfail_stencil(), bias)),
                multisample: Default::default(),
                fragment: None,
                multiview_mask: None,
                cache: None,
            })
        };
        let (ccw, cw) = (wgpu::FrontFace::Ccw, wgpu::FrontFace::Cw);
        let volumes = [
            [volume(ccw, false), volume(ccw, true)],
            [volume(cw, false), volume(cw, true)],
        ];
        // Lesson 05's lit pass (`fs_stencil_lit`) with the reversed depth test.
        let lit = s.lit_pipeline_with_depth(
            gpu,
            &volume_shader_module(gpu, "reversed lit pass", ""),
            "fs_stencil_lit",
            &[],
            reversed_depth(GreaterEqual, false, lit_stencil(), Default::default()),
            &[],
        );
        Ok(ReversedZ {
            scene: s,
            depth_view: depth.create_view(&Default::default()),
            origin,
            depth,
            base,
            volumes,
            lit,
        })
    }

    // ANCHOR: reversed_render
    /// One frame: base pass (clear depth to 0), then per light the z-fail
    /// volumes and the lit pass, all against the float depth buffer.
    pub fn render(
        &mut self,
        frame: &mut Frame,
        scene: &SceneGpu,
        targets: &FrameTargets,
        shadow: &ShadowVolumes,
    ) {
        // The window orbits the camera and moves lights: follow them.
        self.scene.scene.camera = scene.scene.camera.clone();
        self.scene.scene.lights = scene.scene.lights.clone();
        self.scene.jitter = scene.jitter;
        let gpu = frame.gpu;
        let origin = self.origin;
        frame.cpu("camera", || {
            set_reversed_camera(gpu, &mut self.scene, origin)
        });
        let t = with_depth(targets, &self.depth, &self.depth_view);
        let s = &self.scene;
        // Reversed: 0 is the farthest depth.
        frame.pass("base", |enc, ts| {
            s.base_pass_with(enc, &t, &self.base, 0.0, ts.render())
        });
        for light in 0..s.scene.lights.len() {
            frame.pass("volume", |enc, ts| {
                let mut pass = t.stencil_pass(enc, "reversed volume pass", ts.render(), None);
                self.draw_volumes(&mut pass, light, shadow);
            });
            frame.pass("lighting", |enc, ts| {
                s.lit_pass(enc, &t, LitPass::new(light, &self.lit, &[]), ts.render())
            });
        }
    }
    // ANCHOR_END: reversed_render

    // ANCHOR: reversed_volumes
    /// Light `light`'s z-fail volumes: every caster's pre-built quads,
    /// sides and both caps, through this variant's reversed pipelines.
    fn draw_volumes(&self, pass: &mut wgpu::RenderPass<'_>, light: usize, shadow: &ShadowVolumes) {
        let s = &self.scene;
        s.bind_frame(pass, light);
        for c in &shadow.casters {
            let (vb, ib, _) = c.quad_buffers();
            s.bind_object(pass, c.object);
            pass.set_vertex_buffer(0, vb.slice(..));
            pass.set_index_buffer(ib.slice(..), wgpu::IndexFormat::Uint32);
            let r = &c.quad_ranges;
            for (range, cap) in [(&r.sides, false), (&r.front, true), (&r.back, true)] {
                if !range.is_empty() {
                    pass.set_pipeline(&self.volumes[c.mirrored as usize][cap as usize]);
                    pass.draw_indexed(range.clone(), 0, 0..1);
                }
            }
        }
    }
    // ANCHOR_END: reversed_volumes
}

/// Puts the reversed infinite projection into `s`'s camera, relative to
/// the scene's origin `o`, and uploads it.
fn set_reversed_camera(gpu: &Gpu, s: &mut SceneGpu, o: DVec3) {
    let c = &s.scene.camera;
    let view = look_at_mat4(c.eye - o, c.target - o, c.up);
    let aspect = s.width as f64 / s.height as f64;
    let proj = reversed_infinite_perspective(c.fov_y_deg.to_radians(), aspect, c.near);
    // The scene's lens shift, after the projection as the runner applies it.
    let proj = lens_shift(c.shift) * proj;
    s.camera.proj = proj.as_mat4();
    // The runner's sub-pixel move, if any (`SceneGpu::jitter`).
    s.camera.view_proj = s.jitter * (proj * view).as_mat4();
    s.upload_uniforms(gpu);
}

/// The runner's colour, id and visibility images with another depth buffer
/// (handles: nothing is copied).
fn with_depth(t: &FrameTargets, depth: &wgpu::Texture, view: &wgpu::TextureView) -> FrameTargets {
    FrameTargets {
        width: t.width,
        height: t.height,
        color: t.color.clone(),
        color_view: t.color_view.clone(),
        depth: depth.clone(),
        depth_view: view.clone(),
        id: t.id.clone(),
        id_view: t.id_view.clone(),
        visibility: t.visibility.clone(),
        visibility_views: t.visibility_views.clone(),
    }
}
