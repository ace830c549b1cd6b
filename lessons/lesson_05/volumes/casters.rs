//! One shadow caster of lesson 05's volumes: its welded adjacency, its
//! bounding sphere, and its pre-built quads (when they fit the adapter).

use common::glam::DVec3;
use common::gpu::render::SceneGpu;
use common::gpu::Gpu;

use crate::lesson_05::adjacency::Adjacency;
use crate::lesson_05::extrusion::VolumeRanges;
use crate::lesson_05::quads::{degenerate_quads, quad_sizes, QuadVertex, QUAD_VERTEX_BYTES};
use crate::lesson_05::silhouette::caster_adjacency;

/// One shadow caster: its welded adjacency and its pre-built quads.
pub struct VolumeCaster {
    /// Index into `scene.objects`.
    pub object: usize,
    pub adjacency: Adjacency,
    /// det(model) < 0: windings flip in world space.
    pub mirrored: bool,
    /// Origin-relative bounding sphere.
    pub center: DVec3,
    pub radius: f64,
    pub(super) quad_vertices: wgpu::Buffer,
    pub(super) quad_indices: wgpu::Buffer,
    pub quad_ranges: VolumeRanges,
    /// (vertices, indices) of its quads ([`quad_sizes`]), counted once:
    /// what `fit::quads_unfit` checks.
    pub quad_sizes: (u64, u64),
}

impl VolumeCaster {
    /// The pre-built quads' vertex and index buffers (cheap handles), and
    /// the index count of the whole volume: sides, front cap and back cap.
    pub fn quad_buffers(&self) -> (wgpu::Buffer, wgpu::Buffer, u32) {
        let r = &self.quad_ranges;
        let count = r.sides.end.max(r.front.end).max(r.back.end);
        (self.quad_vertices.clone(), self.quad_indices.clone(), count)
    }
}

/// Every casting object's [`VolumeCaster`], in scene order. A caster's
/// quads are built only if they fit the adapter's `max_buffer_size`
/// (`fit::quads_unfit` then leaves the quads route out); otherwise its
/// quad buffers hold a placeholder.
pub(super) fn build_casters(gpu: &Gpu, scene: &SceneGpu) -> Vec<VolumeCaster> {
    use wgpu::util::DeviceExt;
    let mut casters = Vec::new();
    let models = scene.scene.relative_models();
    let max_buffer = gpu.device.limits().max_buffer_size;
    for (i, o) in scene.scene.objects.iter().enumerate() {
        if !o.casts_shadow {
            continue;
        }
        let adjacency = caster_adjacency(&o.mesh);
        let model = models[i];
        let world: Vec<DVec3> = adjacency
            .positions
            .iter()
            .map(|p| model.as_dmat4().transform_point3(p.as_dvec3()))
            .collect();
        let (lo, hi) = world
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), p| {
                (a.min(*p), b.max(*p))
            });
        let center = (lo + hi) * 0.5;
        let radius =
            world.iter().map(|p| p.distance(center)).fold(0.0, f64::max) * (1.0 + 1e-6) + 1e-6;
        // Built only if every caster's quads fit (`quads_unfit` below).
        let quad_sizes = quad_sizes(&adjacency);
        let (verts, idx, quad_ranges) = match quad_sizes {
            (v, i) if v * QUAD_VERTEX_BYTES > max_buffer || i * 4 > max_buffer => {
                Default::default()
            }
            _ => degenerate_quads(&adjacency),
        };
        let buf = |label: &str, contents: &[u8], usage| {
            gpu.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage,
                })
        };
        // wgpu rejects empty buffers: a caster with no edges gets one dummy.
        let verts = if verts.is_empty() {
            vec![QuadVertex::zeroed_vertex()]
        } else {
            verts
        };
        let idx_bytes: Vec<u32> = if idx.is_empty() { vec![0] } else { idx };
        casters.push(VolumeCaster {
            object: i,
            mirrored: model.determinant() < 0.0,
            center,
            radius,
            quad_vertices: buf(
                "volume quads",
                bytemuck::cast_slice(&verts),
                wgpu::BufferUsages::VERTEX,
            ),
            quad_indices: buf(
                "volume quad indices",
                bytemuck::cast_slice(&idx_bytes),
                wgpu::BufferUsages::INDEX,
            ),
            quad_ranges,
            quad_sizes,
            adjacency,
        });
    }
    casters
}
