//! Triangle meshes: the mesh type, the built-in unit meshes, welding by
//! position and smooth normals. OBJ files are read and written in
//! [`crate::scene::obj`]; edge adjacency, which shadow volumes need, is lesson
//! 05's (`workbook::lesson_05::adjacency`).

use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

use anyhow::{bail, Result};
use glam::{DVec3, Vec3};

/// An indexed triangle mesh in object space. Front faces wind counter-clockwise.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub name: String,
    pub positions: Vec<Vec3>,
    /// One normal per position (smooth or faceted, as built).
    pub normals: Vec<Vec3>,
    /// Triangle list, three indices per triangle.
    pub indices: Vec<u32>,
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The triangles as index triples.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]])
    }
}

/// The unnormalised normal `(b − a) × (c − a)`: its length is twice the area.
/// Exactly zero for a degenerate triangle. Everything that asks "does this
/// face face the light?" or "is this face degenerate?" uses this one formula.
pub fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    (b - a).cross(c - a)
}

// ---- built-in meshes -----------------------------------------------------

/// The names [`builtin`] knows, in the order its docs list them.
pub const BUILTIN_NAMES: [&str; 5] = ["plane", "cube", "sphere", "torus", "knot"];

/// A built-in unit mesh by name.
///
/// All are centred at the origin, wind front faces counter-clockwise, and
/// have unit normals pointing out of the surface. +Y is up.
///
/// | name | shape | vertices | triangles |
/// |---|---|---|---|
/// | `plane` | 1 × 1 square in XZ at y = 0, facing +Y. Open and single-sided. | 4 | 2 |
/// | `cube` | side 1, flat normals: each face has its own 4 vertices | 24 | 12 |
/// | `sphere` | radius 0.5, UV sphere of 48 segments × 24 stacks, smooth normals, one vertex at each pole (no sliver triangles there) | 1106 | 2208 |
/// | `torus` | a ring lying in XZ around the Y axis: major radius R = 0.35 (origin to the tube's centre line), minor radius r = 0.15 (the tube), so it spans 1 × 0.3 × 1. 64 × 32 segments, smooth normals | 2048 | 4096 |
/// | `knot` | a (2,3) torus knot (trefoil): a tube of radius 0.07 around the curve `((R + a cos 3t) cos 2t, a sin 3t, (R + a cos 3t) sin 2t)` with R = 0.28, a = 0.14. It goes twice around the Y axis while winding three times around the tube of a torus (R, a), so it crosses over itself and shadows itself. Three-fold symmetric about Y with its centroid at the origin; its box is x ∈ [−0.40, 0.49], y ∈ [−0.21, 0.21], z ∈ [−0.46, 0.46]. 192 × 16 segments, smooth normals | 3072 | 6144 |
///
/// Every mesh except `plane` is closed. Seams share their vertices, so the
/// meshes are closed by index as well as by position.
///
/// Two dense ones, for timing and for two-sided casters, are in
/// [`crate::scene::mesh_dense`]: `holed_sphere` (about 50 000 triangles, five
/// holes: open) and `dense_knot` (about 100 000 triangles, closed); a
/// scene names either kind ([`crate::scene::mesh_dense::any_builtin`]).
///
/// Positions and normals are computed in `f64` and rounded once to `f32`.
/// That gives the same bits on every platform, so `assets/*.obj`
/// (written by `gen_assets`) can be checked against this code exactly.
pub fn builtin(name: &str) -> Result<Mesh> {
    let mut mesh = match name {
        "plane" => plane(),
        "cube" => cube(),
        "sphere" => sphere(0.5, 48, 24),
        "torus" => torus(0.35, 0.15, 64, 32),
        "knot" => knot(0.28, 0.14, 0.07, 192, 16),
        _ => bail!(
            "unknown built-in mesh {name:?} (known: {}; or give a path ending in .obj)",
            BUILTIN_NAMES.join(", ")
        ),
    };
    mesh.name = name.to_string();
    Ok(mesh)
}

/// Collects vertices in `f64` and rounds each one once to `f32`.
#[derive(Default)]
struct Builder {
    mesh: Mesh,
}

impl Builder {
    fn vertex(&mut self, position: DVec3, normal: DVec3) -> u32 {
        self.mesh.positions.push(position.as_vec3());
        self.mesh.normals.push(normal.normalize().as_vec3());
        self.mesh.positions.len() as u32 - 1
    }

    fn triangle(&mut self, a: u32, b: u32, c: u32) {
        self.mesh.indices.extend([a, b, c]);
    }

    /// A flat square centred at `center`, spanning ±u/2 and ±v/2.
    /// Its normal is u × v, and it winds counter-clockwise around it.
    fn square(&mut self, center: DVec3, u: DVec3, v: DVec3) {
        let n = u.cross(v);
        let corners = [-u - v, u - v, u + v, v - u];
        let first = self.mesh.positions.len() as u32;
        for c in corners {
            self.vertex(center + 0.5 * c, n);
        }
        self.triangle(first, first + 1, first + 2);
        self.triangle(first, first + 2, first + 3);
    }

    /// A grid that wraps in both directions (a torus-like surface).
    /// `at(i, j)` gives vertex (i, j) as (position, normal); indices wrap
    /// back to 0, so the seams share vertices and the surface is closed.
    /// The normal must be along (∂p/∂j) × (∂p/∂i).
    fn wrapped_grid(&mut self, n_i: u32, n_j: u32, at: impl Fn(u32, u32) -> (DVec3, DVec3)) {
        let first = self.mesh.positions.len() as u32;
        for i in 0..n_i {
            for j in 0..n_j {
                let (p, n) = at(i, j);
                self.vertex(p, n);
            }
        }
        let id = |i: u32, j: u32| first + (i % n_i) * n_j + (j % n_j);
        for i in 0..n_i {
            for j in 0..n_j {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                self.triangle(a, c, b);
                self.triangle(a, d, c);
            }
        }
    }
}

fn plane() -> Mesh {
    let mut b = Builder::default();
    // Z × X = +Y: the plane faces up.
    b.square(DVec3::ZERO, DVec3::Z, DVec3::X);
    b.mesh
}

fn cube() -> Mesh {
    let mut b = Builder::default();
    let axes = [DVec3::X, DVec3::Y, DVec3::Z];
    for k in 0..3 {
        // For normal e_k use (u, v) = (e_k+1, e_k+2), so that u × v = e_k.
        let (n, u, v) = (axes[k], axes[(k + 1) % 3], axes[(k + 2) % 3]);
        b.square(0.5 * n, u, v);
        b.square(-0.5 * n, v, u);
    }
    b.mesh
}

/// UV sphere: `stacks` bands from pole to pole, `segments` around Y.
/// The poles are single vertices, so their bands are triangle fans.
pub(crate) fn sphere(radius: f64, segments: u32, stacks: u32) -> Mesh {
    let mut b = Builder::default();
    let top = b.vertex(DVec3::new(0.0, radius, 0.0), DVec3::Y);
    for k in 1..stacks {
        let theta = PI * k as f64 / stacks as f64; // from +Y
        for j in 0..segments {
            let phi = TAU * j as f64 / segments as f64;
            let n = DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            b.vertex(radius * n, n);
        }
    }
    let bottom = b.vertex(DVec3::new(0.0, -radius, 0.0), DVec3::NEG_Y);
    // Vertex j of ring k (1..stacks); j wraps, so the seam shares vertices.
    let ring = |k: u32, j: u32| 1 + (k - 1) * segments + j % segments;
    for j in 0..segments {
        b.triangle(top, ring(1, j + 1), ring(1, j));
        for k in 1..stacks - 1 {
            let (a, c) = (ring(k, j), ring(k + 1, j + 1));
            b.triangle(a, ring(k, j + 1), c);
            b.triangle(a, c, ring(k + 1, j));
        }
        b.triangle(ring(stacks - 1, j), ring(stacks - 1, j + 1), bottom);
    }
    b.mesh
}

/// Torus around the Y axis: major radius `big_r`, tube radius `r`.
fn torus(big_r: f64, r: f64, segments: u32, sides: u32) -> Mesh {
    let mut b = Builder::default();
    b.wrapped_grid(segments, sides, |i, j| {
        let u = TAU * i as f64 / segments as f64;
        let v = TAU * j as f64 / sides as f64;
        let out = DVec3::new(u.cos(), 0.0, u.sin());
        let n = v.cos() * out + v.sin() * DVec3::Y;
        (big_r * out + r * n, n)
    });
    b.mesh
}

/// A (2,3) torus knot: a tube of radius `tube` around the curve
/// `((R + a cos 3t) cos 2t, a sin 3t, (R + a cos 3t) sin 2t)`.
pub(crate) fn knot(big_r: f64, a: f64, tube: f64, segments: u32, sides: u32) -> Mesh {
    let mut b = Builder::default();
    b.wrapped_grid(segments, sides, |i, j| {
        let t = TAU * i as f64 / segments as f64;
        let psi = TAU * j as f64 / sides as f64;
        let (phi, theta) = (2.0 * t, 3.0 * t);
        let rho = big_r + a * theta.cos();
        let center = DVec3::new(rho * phi.cos(), a * theta.sin(), rho * phi.sin());
        // The tangent, differentiated by hand (d rho/dt = −3a sin 3t).
        let drho = -3.0 * a * theta.sin();
        let tangent = DVec3::new(
            drho * phi.cos() - 2.0 * rho * phi.sin(),
            3.0 * a * theta.cos(),
            drho * phi.sin() + 2.0 * rho * phi.cos(),
        );
        // A frame from the tangent and the centre: it depends on t only,
        // so it closes up exactly when t wraps (no twist to undo).
        let binormal = tangent.cross(center).normalize();
        let normal = binormal.cross(tangent).normalize();
        let n = psi.cos() * normal + psi.sin() * binormal;
        (center + tube * n, n)
    });
    b.mesh
}

// ---- welding ----------------------------------------------

/// Merges vertices with exactly the same position, as `weld_by_position`
/// does, and returns the welded positions plus, for every input vertex,
/// its welded id.
pub fn weld_remap(positions: &[Vec3]) -> (Vec<Vec3>, Vec<u32>) {
    let mut ids: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    let mut welded = Vec::new();
    let remap = positions
        .iter()
        .map(|p| {
            // + 0.0 turns −0.0 into +0.0, so the two weld together.
            let key = (*p + Vec3::ZERO).to_array().map(f32::to_bits);
            *ids.entry(key).or_insert_with(|| {
                welded.push(*p + Vec3::ZERO);
                welded.len() as u32 - 1
            })
        })
        .collect();
    (welded, remap)
}

/// Welds vertices that have *exactly* the same position (compared bit for
/// bit, with −0.0 equal to +0.0; no tolerance). UV seams and flat-shading
/// splits duplicate positions exactly, so this is enough to recover the
/// surface's connectivity without ever merging two distinct points.
///
/// Returns the distinct positions in order of first appearance and the
/// triangle list re-indexed into them. Panics if an index is out of range.
pub fn weld_by_position(positions: &[Vec3], indices: &[u32]) -> (Vec<Vec3>, Vec<u32>) {
    let (welded, remap) = weld_remap(positions);
    (welded, indices.iter().map(|&i| remap[i as usize]).collect())
}

/// Area-weighted vertex normals, smooth across vertices that share a
/// position. A vertex whose faces cancel out (a two-sided sheet) gets +Y.
pub fn smooth_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let (welded, remap) = weld_remap(positions);
    let mut sum = vec![Vec3::ZERO; welded.len()];
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| remap[i as usize] as usize);
        // The cross product's length is twice the area: that is the weight.
        let n = face_normal(welded[a], welded[b], welded[c]);
        for v in [a, b, c] {
            sum[v] += n;
        }
    }
    remap
        .iter()
        .map(|&w| sum[w as usize].try_normalize().unwrap_or(Vec3::Y))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;
    fn signed_volume(m: &Mesh) -> f64 {
        m.triangles()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn builtin_counts() {
        let expect = [
            ("plane", 4, 2),
            ("cube", 24, 12),
            ("sphere", 1106, 2208),
            ("torus", 2048, 4096),
            ("knot", 3072, 6144),
        ];
        for (name, vertices, triangles) in expect {
            let m = builtin(name).unwrap();
            assert_eq!(
                (m.positions.len(), m.triangle_count()),
                (vertices, triangles),
                "{name}"
            );
            assert_eq!(m.normals.len(), m.positions.len(), "{name}");
            assert_eq!(m.name, name);
        }
    }

    #[test]
    fn builtins_are_unit_sized_and_centred() {
        for name in BUILTIN_NAMES {
            let m = builtin(name).unwrap();
            let lo = m.positions.iter().fold(Vec3::INFINITY, |a, p| a.min(*p));
            let hi = m
                .positions
                .iter()
                .fold(Vec3::NEG_INFINITY, |a, p| a.max(*p));
            assert!(
                lo.cmpge(Vec3::splat(-0.5)).all() && hi.cmple(Vec3::splat(0.5)).all(),
                "{name}: {lo} {hi}"
            );
            // The largest extent is (close to) 1, except the knot's, which fits inside.
            let size = (hi - lo).max_element();
            assert!(size > 0.85, "{name}: size {size}");
            let mean =
                m.positions.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / m.positions.len() as f64;
            assert!(mean.length() < 1e-6, "{name}: centroid {mean}");
        }
    }

    #[test]
    fn builtins_wind_outward_with_unit_normals() {
        for name in BUILTIN_NAMES {
            let m = builtin(name).unwrap();
            for n in &m.normals {
                assert!((n.length() - 1.0).abs() < 1e-6, "{name}: normal {n}");
            }
            for t in m.triangles() {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                let face = face_normal(a, b, c).normalize();
                let smooth: Vec3 = t.iter().map(|&i| m.normals[i as usize]).sum();
                assert!(
                    face.dot(smooth.normalize()) > 0.9,
                    "{name}: triangle {t:?} winds inward"
                );
            }
        }
        for (name, exact) in [
            ("cube", 1.0),
            ("sphere", PI / 6.0),
            ("torus", 2.0 * PI * PI * 0.35 * 0.15 * 0.15),
        ] {
            let v = signed_volume(&builtin(name).unwrap());
            assert!(
                v > 0.0 && (v - exact).abs() < 0.01 * exact,
                "{name}: volume {v}, expected {exact}"
            );
        }
        assert!(signed_volume(&builtin("knot").unwrap()) > 0.0);
    }

    #[test]
    fn knot_tube_does_not_cut_itself() {
        // Sample the core curve; strands that are far apart along the curve
        // must stay more than two tube radii apart.
        let (big_r, a, tube) = (0.28, 0.14, 0.07);
        let n = 1200;
        let core: Vec<DVec3> = (0..n)
            .map(|i| {
                let t = TAU * i as f64 / n as f64;
                let rho = big_r + a * (3.0 * t).cos();
                DVec3::new(
                    rho * (2.0 * t).cos(),
                    a * (3.0 * t).sin(),
                    rho * (2.0 * t).sin(),
                )
            })
            .collect();
        let mut closest = f64::MAX;
        for i in 0..n {
            for j in i + n / 6..i + n - n / 6 {
                closest = closest.min(core[i].distance(core[j % n]));
            }
        }
        assert!(closest > 2.0 * tube + 0.05, "strands {closest} apart");
    }

    #[test]
    fn unknown_builtin_lists_the_known_names() {
        let e = builtin("teapot").unwrap_err().to_string();
        for name in BUILTIN_NAMES {
            assert!(e.contains(name), "{e}");
        }
    }

    #[test]
    fn weld_merges_exact_duplicates_and_signed_zero() {
        let p = [
            Vec3::new(0.0, 1.0, 2.0),
            Vec3::new(-0.0, 1.0, 2.0),
            Vec3::new(0.0, 1.0, 2.000001),
            Vec3::new(0.0, 1.0, 2.0),
        ];
        let (w, i) = weld_by_position(&p, &[0, 1, 2, 3, 2, 1]);
        assert_eq!(w.len(), 2);
        assert_eq!(i, [0, 0, 1, 0, 1, 0]);
    }
}
