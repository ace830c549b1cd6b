//! Triangle meshes: the built-in unit meshes, OBJ loading through tobj,
//! welding by position, and validation. Edge adjacency for shadow volumes
//! is built on top of this in [`crate::adjacency`].

use std::collections::HashMap;
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::io::{BufRead, Read};
use std::path::Path;

use anyhow::{anyhow, bail, Result};
use glam::{DVec3, Vec3};

use crate::adjacency::Adjacency;

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
fn sphere(radius: f64, segments: u32, stacks: u32) -> Mesh {
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
fn knot(big_r: f64, a: f64, tube: f64, segments: u32, sides: u32) -> Mesh {
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

// ---- writing OBJ ---------------------------------------------------------

/// The mesh as OBJ text (`v`, `vn`, `f v//vn`), with the header that marks
/// `assets/*.obj` as generated. `f32` values are written with `{}`, which
/// prints the shortest text that reads back to the same bits.
pub fn to_obj_string(mesh: &Mesh) -> String {
    let mut s = String::new();
    let has_normals = mesh.normals.len() == mesh.positions.len();
    // Writing to a String cannot fail.
    let _ = writeln!(
        s,
        "# generated by `cargo run --release --bin gen_assets`; do not edit"
    );
    let _ = writeln!(
        s,
        "# {}: {} vertices, {} triangles",
        mesh.name,
        mesh.positions.len(),
        mesh.triangle_count()
    );
    let _ = writeln!(s, "o {}", mesh.name);
    for p in &mesh.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    if has_normals {
        for n in &mesh.normals {
            let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
        }
    }
    for [a, b, c] in mesh.triangles() {
        // OBJ indices start at 1.
        let (a, b, c) = (a + 1, b + 1, c + 1);
        if has_normals {
            let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
        } else {
            let _ = writeln!(s, "f {a} {b} {c}");
        }
    }
    s
}

// ---- loading OBJ ---------------------------------------------------------

/// Loads an OBJ file through tobj: polygons are triangulated, every object
/// and group in the file is merged into one mesh, and a vertex is split
/// wherever its position/normal pair differs (one index for the GPU).
///
/// - Normals missing from the file are computed: area-weighted and smooth
///   across vertices that share a position (so UV seams do not show).
/// - Degenerate triangles (a repeated vertex, or zero area) are dropped,
///   with one warning line on stderr giving the count.
/// - Errors are one line that starts with the file (and the line, where it
///   is known): unreadable file, malformed line, index out of range,
///   NaN/infinite coordinates, no triangles, or only degenerate ones.
pub fn load_obj(path: &Path) -> Result<Mesh> {
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| anyhow!("{file}: cannot read OBJ file: {e}"))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = line_of(&bytes, e.valid_up_to());
        anyhow!("{file}:{line}: not UTF-8 text; is this really an OBJ file?")
    })?;
    let mut mesh = parse_obj(text, &file)?;
    if let Some(stem) = path.file_stem() {
        mesh.name = stem.to_string_lossy().into_owned();
    }
    Ok(mesh)
}

/// [`load_obj`] on text already in memory; `file` names it in messages.
pub fn parse_obj(text: &str, file: &str) -> Result<Mesh> {
    let mut reader = LineCounter {
        bytes: text.as_bytes(),
        pos: 0,
    };
    // Materials are not used by the workbook: every mtllib reads as empty.
    let no_materials = |_: &Path| Ok((Vec::new(), Default::default()));
    let loaded = tobj::load_obj_buf(&mut reader, &tobj::GPU_LOAD_OPTIONS, no_materials);
    let models = match loaded {
        Ok((models, _)) => models,
        Err(e) => return Err(tobj_error(e, text, file, reader.line())),
    };

    // Merge all models. `None`: the file gives no normal for this vertex.
    let mut positions = Vec::new();
    let mut file_normals: Vec<Option<Vec3>> = Vec::new();
    let mut indices = Vec::new();
    for model in &models {
        let m = &model.mesh;
        let base = positions.len() as u32;
        let has_normals = m.normals.len() == m.positions.len();
        for (k, p) in m.positions.chunks_exact(3).enumerate() {
            positions.push(Vec3::new(p[0], p[1], p[2]));
            let n = &m.normals;
            file_normals.push(has_normals.then(|| Vec3::new(n[3 * k], n[3 * k + 1], n[3 * k + 2])));
        }
        indices.extend(m.indices.iter().map(|i| base + i));
    }

    if positions.iter().any(|p| !p.is_finite()) {
        return Err(match find_line(text, is_non_finite_vertex) {
            Some((line, l)) => anyhow!("{file}:{line}: vertex position is not finite: {l:?}"),
            None => anyhow!("{file}: a vertex position is not finite (NaN or infinity)"),
        });
    }
    if indices.is_empty() {
        let count = |tag: &str| {
            text.lines()
                .filter(|l| l.split_whitespace().next() == Some(tag))
                .count()
        };
        bail!(
            "{file}: no triangles (found {} `v` lines and {} `f` lines; is this an OBJ file?)",
            count("v"),
            count("f")
        );
    }

    // Drop degenerate triangles.
    let total = indices.len() / 3;
    let mut kept = Vec::with_capacity(indices.len());
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| positions[i as usize]);
        let repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
        if !repeated && face_normal(a, b, c) != Vec3::ZERO {
            kept.extend_from_slice(t);
        }
    }
    let dropped = total - kept.len() / 3;
    if kept.is_empty() {
        bail!("{file}: every triangle is degenerate ({total} triangles with a repeated vertex or zero area)");
    }
    if dropped > 0 {
        eprintln!("warning: {file}: dropped {dropped} degenerate triangle(s) (repeated vertex or zero area)");
    }

    // Keep only the vertices that a kept triangle uses.
    let mut remap = vec![u32::MAX; positions.len()];
    let mut mesh = Mesh {
        name: file.to_string(),
        ..Default::default()
    };
    let mut normals: Vec<Option<Vec3>> = Vec::new();
    for i in &mut kept {
        let slot = &mut remap[*i as usize];
        if *slot == u32::MAX {
            *slot = mesh.positions.len() as u32;
            mesh.positions.push(positions[*i as usize]);
            normals.push(file_normals[*i as usize]);
        }
        *i = *slot;
    }
    mesh.indices = kept;

    // A normal from the file is used when it can be normalised. One that is
    // already unit length (to f32 rounding) is kept bit for bit.
    let unit = |n: Vec3| match n.length() {
        len if (len - 1.0).abs() < 1e-6 => Some(n),
        _ => n.try_normalize(),
    };
    let bad_normals = normals
        .iter()
        .filter(|n| n.is_some_and(|n| unit(n).is_none()))
        .count();
    if bad_normals > 0 {
        eprintln!(
            "warning: {file}: {bad_normals} normal(s) are zero or not finite; computing those"
        );
    }
    let smooth = smooth_normals(&mesh.positions, &mesh.indices);
    mesh.normals = normals
        .iter()
        .zip(smooth)
        .map(|(n, s)| n.and_then(unit).unwrap_or(s))
        .collect();
    Ok(mesh)
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

/// Reads lines for tobj and remembers how far it got, for error messages.
struct LineCounter<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl LineCounter<'_> {
    /// The 1-based line tobj read last.
    fn line(&self) -> usize {
        line_of(self.bytes, self.pos.saturating_sub(1))
    }
}

impl Read for LineCounter<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = (&self.bytes[self.pos..]).read(buf)?;
        self.pos += n;
        Ok(n)
    }
}

impl BufRead for LineCounter<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        Ok(&self.bytes[self.pos..])
    }
    fn consume(&mut self, amount: usize) {
        self.pos += amount;
    }
}

/// 1-based line of a byte offset.
fn line_of(bytes: &[u8], offset: usize) -> usize {
    bytes[..offset.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The first line (1-based) for which `bad` says why it is wrong.
fn find_line(text: &str, mut bad: impl FnMut(&str) -> bool) -> Option<(usize, &str)> {
    text.lines()
        .enumerate()
        .find(|(_, l)| bad(l))
        .map(|(i, l)| (i + 1, l.trim()))
}

fn is_non_finite_vertex(line: &str) -> bool {
    let mut words = line.split_whitespace();
    words.next() == Some("v")
        && words
            .take(4)
            .any(|w| w.parse::<f32>().is_ok_and(|x| !x.is_finite()))
}

/// One line naming the file, and the line where the problem is.
fn tobj_error(e: tobj::LoadError, text: &str, file: &str, line: usize) -> anyhow::Error {
    use tobj::LoadError as E;
    let what = match e {
        E::PositionParseError => "cannot parse a vertex (expected `v x y z`)".to_string(),
        E::ScalingByZeroError => "vertex has w = 0".to_string(),
        E::ColorParseError => "vertex has a wrong number of values (expected `v x y z`, `v x y z w` or `v x y z r g b`)".to_string(),
        E::NormalParseError => "cannot parse a normal (expected `vn x y z`)".to_string(),
        E::TexcoordParseError => "cannot parse a texture coordinate (expected `vt u v`)".to_string(),
        E::FaceParseError => "cannot parse a face (expected `f` and indices like `1`, `1/2`, `1//3` or `1/2/3`)".to_string(),
        // tobj checks face indices only when an object ends: find the face ourselves.
        E::FaceVertexOutOfBounds
        | E::FaceTexCoordOutOfBounds
        | E::FaceNormalOutOfBounds
        | E::FaceColorOutOfBounds
        | E::InvalidPolygon => {
            return match find_bad_face(text) {
                Some((line, why)) => anyhow!("{file}:{line}: {why}"),
                None => anyhow!("{file}: {e}"),
            };
        }
        other => other.to_string(),
    };
    anyhow!("{file}:{line}: {what}")
}

/// The first face with an index out of range, and what is wrong with it.
/// Indices count from 1; negative ones count back from the last element read.
fn find_bad_face(text: &str) -> Option<(usize, String)> {
    let tags = ["v", "vt", "vn"];
    let mut total = [0usize; 3];
    for line in text.lines() {
        if let Some(k) = tags
            .iter()
            .position(|t| line.split_whitespace().next() == Some(t))
        {
            total[k] += 1;
        }
    }
    let mut seen = [0usize; 3];
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let tag = words.next();
        if let Some(k) = tags.iter().position(|t| tag == Some(t)) {
            seen[k] += 1;
            continue;
        }
        if tag != Some("f") {
            continue;
        }
        for word in words {
            for (k, part) in word.split('/').enumerate().take(3) {
                let Ok(x) = part.parse::<i64>() else { continue };
                // tobj ignores vt and vn indices when the file has none.
                if k > 0 && total[k] == 0 {
                    continue;
                }
                let what = ["vertex", "texture coordinate", "normal"][k];
                let why = if x == 0 {
                    Some(format!("face index 0 in {word:?} (OBJ indices start at 1)"))
                } else if x > 0 && x as usize > total[k] {
                    Some(format!(
                        "face refers to {what} {x} but the file has {} ({word:?})",
                        total[k]
                    ))
                } else if x < 0 && x.unsigned_abs() as usize > seen[k] {
                    Some(format!(
                        "face refers to {what} {x} but only {} come before it ({word:?})",
                        seen[k]
                    ))
                } else {
                    None
                };
                if let Some(why) = why {
                    return Some((number + 1, why));
                }
            }
        }
    }
    None
}

// ---- welding and validation ----------------------------------------------

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

/// What [`validate`] found. Edges are counted on the mesh welded by position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshReport {
    pub triangles: usize,
    /// Triangles with a repeated (welded) vertex, or zero area.
    pub degenerate_triangles: usize,
    /// Edges used by exactly one triangle: the rims of holes.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub nonmanifold_edges: usize,
    /// Edges used by two triangles that both run along it the same way:
    /// the two faces disagree about which side is out.
    pub misoriented_edges: usize,
    /// No boundary and no non-manifold edges: the mesh encloses a volume.
    pub closed: bool,
}

impl std::fmt::Display for MeshReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} triangles ({} degenerate), {} boundary edges, {} non-manifold edges, \
             {} misoriented edges: {}",
            self.triangles,
            self.degenerate_triangles,
            self.boundary_edges,
            self.nonmanifold_edges,
            self.misoriented_edges,
            if self.closed { "closed" } else { "open" }
        )
    }
}

/// Checks a mesh the way shadow volumes need it: welded by position, is it
/// closed, manifold and consistently oriented? Triangles with a repeated
/// welded vertex add no edges; zero-area triangles with three distinct
/// vertices still do (they are degenerate but still connect their edges).
/// Panics if an index is out of range.
pub fn validate(mesh: &Mesh) -> MeshReport {
    let adjacency = Adjacency::new(mesh);
    let mut report = MeshReport {
        triangles: mesh.triangle_count(),
        degenerate_triangles: adjacency
            .face_normals
            .iter()
            .filter(|n| **n == Vec3::ZERO)
            .count(),
        boundary_edges: 0,
        nonmanifold_edges: 0,
        misoriented_edges: 0,
        closed: false,
    };
    for edge in &adjacency.edges {
        match adjacency.faces_of(edge) {
            [_] => report.boundary_edges += 1,
            [f, g] if f.forward == g.forward => report.misoriented_edges += 1,
            [_, _] => {}
            _ => report.nonmanifold_edges += 1,
        }
    }
    report.closed = report.triangles > report.degenerate_triangles
        && report.boundary_edges == 0
        && report.nonmanifold_edges == 0;
    report
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn builtins_validate() {
        for name in BUILTIN_NAMES {
            let r = validate(&builtin(name).unwrap());
            assert_eq!(r.degenerate_triangles, 0, "{name}: {r}");
            assert_eq!(r.misoriented_edges, 0, "{name}: {r}");
            assert_eq!(r.nonmanifold_edges, 0, "{name}: {r}");
            assert_eq!(r.closed, name != "plane", "{name}: {r}");
        }
        let plane = validate(&builtin("plane").unwrap());
        assert_eq!(plane.boundary_edges, 4);
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

    #[test]
    fn split_seams_weld_closed() {
        // Give every triangle its own three vertices: closed only after welding.
        let cube = builtin("cube").unwrap();
        let positions: Vec<Vec3> = cube
            .indices
            .iter()
            .map(|&i| cube.positions[i as usize])
            .collect();
        let split = Mesh {
            name: "split".into(),
            normals: vec![Vec3::Y; positions.len()],
            indices: (0..positions.len() as u32).collect(),
            positions,
        };
        let r = validate(&split);
        assert!(r.closed && r.boundary_edges == 0, "{r}");
    }

    #[test]
    fn validate_counts_open_nonmanifold_and_misoriented_edges() {
        let p = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::NEG_Z,
            Vec3::ONE,
        ];
        let mesh = |indices: Vec<u32>| Mesh {
            positions: p.clone(),
            normals: vec![Vec3::Y; 6],
            indices,
            ..Default::default()
        };
        // Three triangles on edge 0–1: non-manifold; the other edges open.
        let r = validate(&mesh(vec![0, 1, 2, 1, 0, 3, 0, 1, 4]));
        assert_eq!(
            (r.nonmanifold_edges, r.boundary_edges, r.closed),
            (1, 6, false),
            "{r}"
        );
        // Two triangles that both run 0→1: misoriented.
        let r = validate(&mesh(vec![0, 1, 2, 0, 1, 3]));
        assert_eq!(r.misoriented_edges, 1, "{r}");
        // A repeated vertex and a zero-area triangle.
        let r = validate(&mesh(vec![0, 0, 1, 0, 1, 5, 0, 5, 5]));
        let collinear = validate(&Mesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            indices: vec![0, 1, 2],
            ..Default::default()
        });
        assert_eq!(r.degenerate_triangles, 2, "{r}");
        assert_eq!(collinear.degenerate_triangles, 1, "{collinear}");
        assert!(!collinear.closed);
    }

    #[test]
    fn obj_round_trip_is_exact() {
        for name in BUILTIN_NAMES {
            let m = builtin(name).unwrap();
            let back = parse_obj(&to_obj_string(&m), name).unwrap();
            assert_eq!(back.triangle_count(), m.triangle_count());
            for (t, u) in m.triangles().zip(back.triangles()) {
                for k in 0..3 {
                    let (i, j) = (t[k] as usize, u[k] as usize);
                    assert_eq!(m.positions[i], back.positions[j], "{name}");
                    assert_eq!(m.normals[i], back.normals[j], "{name}");
                }
            }
        }
    }

    #[test]
    fn obj_quads_objects_and_missing_normals() {
        let text = "o a\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3 4\no b\nv 0 1 0\nv 1 1 0\nv 0 1 -1\nf -3 -2 -1\n";
        let m = parse_obj(text, "quads.obj").unwrap();
        assert_eq!(m.triangle_count(), 3);
        assert_eq!(m.positions.len(), 7);
        for n in &m.normals {
            assert!((*n - Vec3::Y).length() < 1e-6, "{n}");
        }
    }

    #[test]
    fn obj_drops_degenerate_triangles() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 9 9 9\nf 1 2 3\nf 1 1 2\nf 1 2 4\n";
        let m = parse_obj(text, "degenerate.obj").unwrap();
        assert_eq!(m.triangle_count(), 1);
        // Only the vertices of the kept triangle remain.
        assert_eq!(m.positions.len(), 3);
    }

    #[test]
    fn obj_errors_name_file_and_line() {
        let cases = [
            ("v 0 0 0\nv 1 0\n", "bad.obj:2:"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 x\n", "bad.obj:5:"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 7\no next\n",
                "bad.obj:5: face refers to vertex 7 but the file has 3",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                "bad.obj:4: face index 0",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n",
                "bad.obj:4: face refers to vertex -4",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n",
                "bad.obj:3: vertex position is not finite",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n",
                "bad.obj:3: vertex position is not finite",
            ),
            ("hello world\n", "bad.obj: no triangles"),
            (
                "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
                "bad.obj: every triangle is degenerate",
            ),
        ];
        for (text, expect) in cases {
            let e = format!("{:#}", parse_obj(text, "bad.obj").unwrap_err());
            assert!(
                e.starts_with(expect),
                "{text:?}: got {e:?}, expected {expect:?}"
            );
            assert!(!e.contains('\n'), "{e:?}");
        }
    }
}
