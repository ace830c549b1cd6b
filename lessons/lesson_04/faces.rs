//! A cube's six faces (lesson 04): the way each looks, its 90°
//! view-projection, and its light uniform (six faces in one submission
//! need six uniform slots per light, written only when the light or the
//! variant's near and far change).

use common::glam::dcamera::rh::proj::directx as webgpu;
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec3, Mat4};
use common::gpu::render::{SceneGpu, SCENE_BUFFER_USAGE};
use common::gpu::Gpu;
use common::scene::camera::{light_uniform, LightUniform};
use common::scene::{Light, LightKind, Scene};

// ANCHOR: cube_faces
/// The six faces in wgpu's layer order +X, −X, +Y, −Y, +Z, −Z: the axis each
/// face looks along, and its `up` (the usual cube-map up vectors).
pub const CUBE_FACES: [(DVec3, DVec3); 6] = [
    (DVec3::X, DVec3::NEG_Y),
    (DVec3::NEG_X, DVec3::NEG_Y),
    (DVec3::Y, DVec3::Z),
    (DVec3::NEG_Y, DVec3::NEG_Z),
    (DVec3::Z, DVec3::NEG_Y),
    (DVec3::NEG_Z, DVec3::NEG_Y),
];

/// Face `face`'s view-projection for a light at `light` (origin-relative):
/// a square 90° frustum, so the six faces tile every direction exactly.
pub fn face_view_proj(light: DVec3, face: usize, near: f64, far: f64) -> Mat4 {
    let (axis, up) = CUBE_FACES[face];
    let view = look_at_mat4(light, light + axis, up);
    let proj = webgpu::perspective(std::f64::consts::FRAC_PI_2, 1.0, near, far);
    // Those up vectors were made for OpenGL, whose framebuffer rows grow
    // upwards; WebGPU's grow downwards. Flip y, or every face is read upside down.
    (DMat4::from_scale(DVec3::new(1.0, -1.0, 1.0)) * proj * view).as_mat4()
}
// ANCHOR_END: cube_faces

/// One face's scissor rectangle, in texels from the face's top left
/// ([`super::face_rects`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexelRect {
    pub x: u32,
    pub y: u32,
    pub w: u32,
    pub h: u32,
}

impl TexelRect {
    /// The whole face.
    pub fn full(size: u32) -> TexelRect {
        TexelRect {
            x: 0,
            y: 0,
            w: size,
            h: size,
        }
    }

    /// Texels inside.
    pub fn area(self) -> u64 {
        u64::from(self.w) * u64::from(self.h)
    }

    /// The smallest rectangle holding both.
    pub fn union(self, o: TexelRect) -> TexelRect {
        let (x, y) = (self.x.min(o.x), self.y.min(o.y));
        let x1 = (self.x + self.w).max(o.x + o.w);
        let y1 = (self.y + self.h).max(o.y + o.h);
        TexelRect {
            x,
            y,
            w: x1 - x,
            h: y1 - y,
        }
    }
}

/// Each face's rectangle; `None`: no visible receiver looks into the face.
pub type FaceRects = [Option<TexelRect>; 6];

/// Uniform slots are spaced by the dynamic-offset alignment.
const SLOT: u64 = 256;

/// The light's position (relative to `origin`, the scene's) and range;
/// `None` for a directional light.
pub fn point_light(scene: &Scene, origin: DVec3, light: usize) -> Option<(DVec3, f64)> {
    match scene.lights[light].kind {
        LightKind::Point { position, range }
        | LightKind::Spot {
            position, range, ..
        } => Some((position - origin, range)),
        LightKind::Directional { .. } => None,
    }
}

/// [`light_uniform`] of each light, made again only when the light
/// changes (the window moves lights): making it finds the scene's origin,
/// and a directional light's map the scene's bounds, passes over every
/// vertex that no frame needs to repeat (objects do not move).
#[derive(Clone, Debug, Default)]
pub struct LightUniforms(Vec<Option<(Light, LightUniform)>>);

impl LightUniforms {
    /// Light `light`'s uniform, as [`light_uniform`] makes it.
    pub fn get(&mut self, scene: &Scene, light: usize) -> LightUniform {
        let l = scene.lights[light];
        if self.0.len() <= light {
            self.0.resize(light + 1, None);
        }
        match self.0[light] {
            Some((made_for, u)) if made_for == l => u,
            _ => {
                let u = light_uniform(scene, light);
                self.0[light] = Some((l, u));
                u
            }
        }
    }
}

/// Six light uniforms per light (one per face), bound as group 0 with the
/// scene's frame layout: `write_light_view_proj` has one slot per light, and
/// queue writes all land before the frame's single submission.
pub struct FaceUniforms {
    buffer: wgpu::Buffer,
    group: wgpu::BindGroup,
    /// The scene's origin, found once (objects do not move), each light's
    /// uniform, made once per light, and the six slots last written for
    /// each light.
    pub origin: DVec3,
    lights: LightUniforms,
    written: Vec<Vec<u8>>,
    /// The runner's sub-texel move of the faces (`--fragile`; the identity
    /// otherwise), pre-multiplied onto each face's matrix. The lit pass
    /// reads the cube by direction, not through these matrices: the faces'
    /// images move under the texel grid, as another rasteriser's snapping
    /// moves them.
    pub jitter: Mat4,
}

impl FaceUniforms {
    pub fn new(gpu: &Gpu, scene: &SceneGpu) -> FaceUniforms {
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cube face lights"),
            size: SLOT * 6 * scene.scene.lights.len().max(1) as u64,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        // Binding 0 (the camera) is unused by the shadow shaders but part of the layout.
        let camera = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cube faces: unused camera"),
            size: 96,
            usage: SCENE_BUFFER_USAGE,
            mapped_at_creation: false,
        });
        let light_size = std::mem::size_of::<LightUniform>() as u64;
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cube faces"),
            layout: &scene.frame_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: camera.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(light_size),
                    }),
                },
            ],
        });
        FaceUniforms {
            buffer,
            group,
            origin: scene.scene.origin(),
            lights: LightUniforms::default(),
            written: vec![Vec::new(); scene.scene.lights.len()],
            jitter: Mat4::IDENTITY,
        }
    }

    /// Binds face `face` of light `light` as group 0.
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>, light: usize, face: usize) {
        let offset = (SLOT * (6 * light + face) as u64) as u32;
        pass.set_bind_group(0, &self.group, &[offset]);
    }

    /// Writes the six faces' view-projections of light `light`, from `near`
    /// to `far` (`None`: the light's range).
    pub fn write(&mut self, gpu: &Gpu, scene: &Scene, light: usize, near: f64, far: Option<f64>) {
        let Some((pos, range)) = point_light(scene, self.origin, light) else {
            return;
        };
        let far = far.unwrap_or(range);
        let base = self.lights.get(scene, light);
        // The six slots in one write, when they change (the light moved,
        // or another variant's near and far).
        let mut slots = vec![0u8; 6 * SLOT as usize];
        for (face, slot) in slots.chunks_exact_mut(SLOT as usize).enumerate() {
            let mut u = base;
            u.view_proj = (self.jitter * face_view_proj(pos, face, near, far)).to_cols_array_2d();
            // The faces' far plane in the range's slot: what the linear
            // storage divides the distance by (`fs_cube_linear`).
            u.color_range[3] = far as f32;
            slot[..std::mem::size_of::<LightUniform>()].copy_from_slice(bytemuck::bytes_of(&u));
        }
        if self.written[light] != slots {
            gpu.queue
                .write_buffer(&self.buffer, SLOT * 6 * light as u64, &slots);
            self.written[light] = slots;
        }
    }
}
