//! Extruding silhouettes into shadow volumes (lesson 05).
//!
//! WebGPU has no geometry shader, so the silhouette is found either
//!
//! - [`Extrusion::Cpu`]: on the CPU every frame, as Doom 3 did. The light is
//!   moved into object space (inverse model), [`face_facing`] and
//!   [`silhouette_edges_for`] give the sides, and the light-facing
//!   triangles give the caps ([`cpu_volume`]). Vertices are
//!   `(position, w)`: `w = 1` stays, `w = 0` goes to infinity.
//! - [`Extrusion::Quads`]: degenerate quads built once, in advance, that
//!   the vertex shader opens or collapses ([`quads`](super::quads)).
//! - [`Extrusion::Compute`]: the CPU route's triangles, written by a
//!   compute shader every frame ([`compute`](super::compute)).
//!
//! Both give the same volumes: the boundary of the union of the
//! light-facing faces' own volumes (see [`silhouette_edges`](super::silhouette::silhouette_edges)).

use std::ops::Range;

use super::adjacency::Adjacency;
use common::glam::DVec3;
use common::gpu::render::shader_module;
use common::gpu::Gpu;

use super::silhouette::{
    face_facing, light_facing_triangles_for, silhouette_edges_for, LightDir, SilhouetteEdge,
};
pub use super::silhouette::{light_relative_to, world_light};

/// The volume WGSL (`shaders/lesson_05/volume.wgsl`), after `common.wgsl`.
pub const VOLUME_WGSL: &str = include_str!("../../shaders/lesson_05/volume.wgsl");

/// `common.wgsl` + `volume.wgsl` + a lesson's own WGSL.
pub fn volume_shader_module(gpu: &Gpu, label: &str, extra_wgsl: &str) -> wgpu::ShaderModule {
    shader_module(gpu, label, &format!("{VOLUME_WGSL}\n{extra_wgsl}"))
}

/// How the volume geometry is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extrusion {
    /// Silhouettes on the CPU every frame (Doom 3).
    Cpu,
    /// Degenerate quads built in advance, extruded in the vertex shader.
    Quads,
    /// Silhouettes and caps written by a compute shader every frame, the
    /// CPU route's triangles, drawn indirectly with its pipelines
    /// ([`compute`](super::compute)).
    Compute,
}

/// CPU-path vertex: object-space position and w (1 stays, 0 to infinity).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CpuVertex {
    pub position: [f32; 3],
    pub w: f32,
}

pub const CPU_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<CpuVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32],
};

/// Vertex ranges of one caster's volume: sides, front cap, back cap.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VolumeRanges {
    pub sides: Range<u32>,
    pub front: Range<u32>,
    pub back: Range<u32>,
}

/// The CPU path: one caster's volume for one light (object space), appended
/// to `out`. Sides from the silhouette; caps from the light-facing faces.
pub fn cpu_volume(adj: &Adjacency, light: LightDir, out: &mut Vec<CpuVertex>) -> VolumeRanges {
    cpu_volume_reaching(adj, light, 0.0, out)
}

// ANCHOR: cpu_volume
/// The CPU path: one caster's volume for one light (object space), its far
/// vertices at `w = reach_w` (0 is infinity; lesson 06's finite reach moves
/// them `1 / reach_w` times as far from the light), appended to `out`.
pub fn cpu_volume_reaching(
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
    out: &mut Vec<CpuVertex>,
) -> VolumeRanges {
    // One facing test serves the sides and the caps.
    let facing = face_facing(adj, light);
    let edges = silhouette_edges_for(adj, &facing);
    // The front cap: the light-facing triangles. The back cap: the same
    // triangles at infinity, reversed.
    let front = light_facing_triangles_for(adj, &facing);
    let back: Vec<[u32; 3]> = front.iter().map(|t| [t[0], t[2], t[1]]).collect();
    volume_vertices(adj, light, reach_w, &edges, (&front, &back), out)
}
// ANCHOR_END: cpu_volume

// ANCHOR: volume_vertices
/// One volume's `(position, w)` vertices, appended to `out`: the sides
/// over `edges`, then the front cap, then the back cap (w = 0 goes to
/// `reach_w`).
pub fn volume_vertices(
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
    edges: &[SilhouetteEdge],
    (front, back): (&[[u32; 3]], &[[u32; 3]]),
    out: &mut Vec<CpuVertex>,
) -> VolumeRanges {
    let v = |i: u32, w: f32| CpuVertex {
        position: adj.positions[i as usize].to_array(),
        w: if w == 0.0 { reach_w } else { w },
    };
    let directional = matches!(light, LightDir::Directional(_));
    let start = out.len() as u32;
    for e in edges {
        // The lit face runs a → b; its side of the volume, seen from
        // outside, runs b → a → a∞ → b∞ (counter-clockwise, like the caps).
        out.extend([v(e.a, 1.0), v(e.b, 0.0), v(e.b, 1.0)]);
        if !directional {
            // Directional: a∞ = b∞, the second triangle would have no area.
            out.extend([v(e.a, 1.0), v(e.a, 0.0), v(e.b, 0.0)]);
        }
    }
    let sides_end = out.len() as u32;
    out.extend(front.iter().flat_map(|t| t.map(|i| v(i, 1.0))));
    let front_end = out.len() as u32;
    if !directional {
        // Directional: the back cap shrinks to a point at infinity.
        out.extend(back.iter().flat_map(|t| t.map(|i| v(i, 0.0))));
    }
    VolumeRanges {
        sides: start..sides_end,
        front: sides_end..front_end,
        back: front_end..out.len() as u32,
    }
}
// ANCHOR_END: volume_vertices

/// [`cpu_volume_reaching`], with the sides or the caps found by `parts`
/// where it says so (an exercise's code), else by the lesson's own.
/// `view`: the view frustum's planes in object space, for `parts.sides`
/// and `parts.caps`.
pub fn cpu_volume_parts(
    adj: &Adjacency,
    light: LightDir,
    reach_w: f32,
    parts: CpuParts,
    view: &[(DVec3, f64)],
    out: &mut Vec<CpuVertex>,
) -> VolumeRanges {
    if parts.sides.is_none() && parts.caps.is_none() {
        return cpu_volume_reaching(adj, light, reach_w, out);
    }
    let facing = face_facing(adj, light);
    let edges = match parts.sides {
        Some(sides) => sides(adj, light, view),
        None => silhouette_edges_for(adj, &facing),
    };
    let (front, back) = match parts.caps {
        Some(caps) => caps(adj, light, view),
        None => {
            let lit = light_facing_triangles_for(adj, &facing);
            let back = lit.iter().map(|t| [t[0], t[2], t[1]]).collect();
            (lit, back)
        }
    };
    volume_vertices(adj, light, reach_w, &edges, (&front, &back), out)
}

/// A silhouette finder: the edges to extrude, as
/// [`silhouette_edges`](super::silhouette::silhouette_edges) gives them,
/// given also the view frustum's planes `(n, d)` in object space (`n` not
/// of unit length, `n · x + d ≥ 0` inside).
pub type SidesFn = fn(&Adjacency, LightDir, &[(DVec3, f64)]) -> Vec<SilhouetteEdge>;

/// A cap builder: (front cap, back cap) triangles, welded ids, each wound
/// as drawn (the back cap's vertices go to infinity), given also the view
/// frustum's planes as for [`SidesFn`].
pub type CapsFn = fn(&Adjacency, LightDir, &[(DVec3, f64)]) -> (Vec<[u32; 3]>, Vec<[u32; 3]>);

/// Which parts of the CPU path's volume an exercise's code builds
/// ([`cpu_volume_parts`]); `None`: the lesson's own. The default is the
/// lesson's own everywhere.
#[derive(Clone, Copy, Debug, Default)]
pub struct CpuParts {
    pub sides: Option<SidesFn>,
    pub caps: Option<CapsFn>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson_05::silhouette::{light_facing_triangles, silhouette_edges};
    use common::glam::Vec3;
    use common::scene::mesh::builtin;

    /// The lesson's sides, as a [`SidesFn`] would give them.
    fn lesson_sides(adj: &Adjacency, light: LightDir, _: &[(DVec3, f64)]) -> Vec<SilhouetteEdge> {
        silhouette_edges(adj, light)
    }

    /// The lesson's caps, as a [`CapsFn`] would give them.
    fn lesson_caps(
        adj: &Adjacency,
        light: LightDir,
        _: &[(DVec3, f64)],
    ) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
        let front = light_facing_triangles(adj, light);
        let back = front.iter().map(|t| [t[0], t[2], t[1]]).collect();
        (front, back)
    }

    #[test]
    fn parts_given_as_functions_build_the_same_volume() {
        let adj = Adjacency::new(&builtin("knot").unwrap());
        let parts = CpuParts {
            sides: Some(lesson_sides),
            caps: Some(lesson_caps),
        };
        for light in [
            LightDir::Point(Vec3::new(1.0, 3.0, 0.5)),
            LightDir::Directional(Vec3::new(-0.4, -1.0, 0.3)),
        ] {
            for reach in [0.0, 0.25] {
                let (mut own, mut given) = (Vec::new(), Vec::new());
                let r = cpu_volume_reaching(&adj, light, reach, &mut own);
                let s = cpu_volume_parts(&adj, light, reach, parts, &[], &mut given);
                assert_eq!((r, &own), (s, &given), "{light:?}, reach {reach}");
                assert!(!own.is_empty());
            }
        }
    }
}
