//! Triangle meshes: the built-in unit meshes, OBJ loading through tobj,
//! welding by position, validation, and edge adjacency for shadow volumes.

use glam::Vec3;

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

/// A built-in unit mesh by name (see the module docs for the list).
pub fn builtin(name: &str) -> anyhow::Result<Mesh> {
    anyhow::bail!("unknown mesh {name:?} (built-in meshes are not written yet)")
}

/// Loads an OBJ file through tobj: triangulated, normals computed when missing.
pub fn load_obj(path: &std::path::Path) -> anyhow::Result<Mesh> {
    anyhow::bail!("{}: OBJ loading is not written yet", path.display())
}
