//! The scene format (the book's appendix "Interfaces", "Scene files",
//! `book/src/appendix/interfaces.md`): camera, ambient, lights and objects.
//!
//! Positions and transforms are kept in `f64` so that a scene 10 km from the
//! origin loses nothing before [`Scene::origin`] is subtracted; everything the
//! GPU and the reference see is relative to that origin, in `f32`.
//!
//! Beside the scene itself, its parts and its math:
//! - [`file`]: the scene TOML as written, before validation.
//! - [`limits`]: the magnitudes a scene may have, and numbers in messages.
//! - [`mesh`]: the mesh type, built-in unit meshes, welding, smooth normals.
//! - [`mesh_dense`]: the dense built-ins (`holed_sphere`, `dense_knot`).
//! - [`obj`]: OBJ files, read through tobj and written for `gen_assets`.
//! - [`obj_errors`]: the line of an OBJ file an error is on (tobj names none).
//! - [`camera`]: camera and light matrices.
//! - [`lights`]: the `[[lights]]` tables, their kinds and sizes.
//! - [`camera_path`]: a scene's `[camera_path]` (pan, dolly) and its shimmer.

pub mod camera;
pub mod camera_path;
pub mod file;
pub mod lights;
pub mod limits;
pub mod mesh;
pub mod mesh_dense;
pub mod obj;
pub mod obj_errors;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{anyhow, bail, Context, Result};
use glam::{DMat4, DQuat, DVec2, DVec3, EulerRot, Vec3};

use crate::scene::file::{CameraPath, FarFile, ObjectFile, ScaleFile, SceneFile};
use crate::scene::lights::parse_light;
pub use crate::scene::lights::{Light, LightKind, LightSize};
use crate::scene::limits::{
    check_coord, check_direction, color3, positive, short, short3, Extent, MAX_COORD,
    MAX_DEPTH_RATIO, MAX_FOV_DEG, MAX_REACH_OVER_NEAR, MAX_SCALE, MAX_SHIFT, MIN_FOV_DEG, MIN_NEAR,
    MIN_SCALE,
};
use crate::scene::mesh::Mesh;

/// The camera's far plane: a distance, or `"infinite"`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Far {
    Finite(f64),
    Infinite,
}

/// The camera as the window moves it; serialised (serde) only to hand the
/// view to the web page's reference worker (`run::window::live_worker`).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Camera {
    pub eye: DVec3,
    pub target: DVec3,
    pub up: DVec3,
    pub fov_y_deg: f64,
    pub near: f64,
    pub far: Far,
    /// Lens shift in NDC units (`[camera] shift`, default 0): the image
    /// moves by `shift.x` half-widths and `shift.y` half-heights, so the
    /// frustum is off-centre. Applied in [`camera::camera_matrices`].
    pub shift: DVec2,
}

#[derive(Clone, Debug)]
pub struct Object {
    /// The name as written in the scene (`"cube"` or a path).
    pub mesh_name: String,
    pub mesh: Arc<Mesh>,
    /// `T * Rz * Ry * Rx * S`, in world space, double precision.
    pub model: DMat4,
    pub color: Vec3,
    pub casts_shadow: bool,
}

#[derive(Clone, Debug)]
pub struct Scene {
    /// `"default"` for a lesson's built-in scene, else the file path.
    pub name: String,
    pub camera: Camera,
    pub ambient: Vec3,
    pub lights: Vec<Light>,
    pub objects: Vec<Object>,
    /// `[camera_path]`, for lessons that measure shimmer (chapter 09).
    pub camera_path: Option<CameraPath>,
}

/// 1-based line of a byte offset, for error messages.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

fn finite3(v: [f64; 3], what: &str) -> Result<DVec3> {
    if v.iter().any(|c| !c.is_finite()) {
        bail!("{what}: must be finite, got {}", short3(v));
    }
    Ok(DVec3::from(v))
}

impl Scene {
    /// Loads and validates a scene file. Relative OBJ paths are relative to it.
    pub fn load(path: &Path) -> Result<Scene> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read scene file", path.display()))?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Scene::parse(&text, &path.display().to_string(), &dir)
    }

    /// Parses scene TOML. `name` is used in messages; `dir` resolves OBJ paths.
    pub fn parse(text: &str, name: &str, dir: &Path) -> Result<Scene> {
        let file: SceneFile = toml::from_str(text).map_err(|e| {
            let line = e.span().map(|s| line_of(text, s.start));
            // One line, even where a quoted key or a value holds a newline.
            let mut msg = e.message().trim().replace(['\n', '\r'], " ");
            if msg == "duplicate key" {
                // toml names neither the key nor the table; the span does.
                let span = e.span().unwrap_or_default();
                let key = text.get(span.clone()).unwrap_or("").trim();
                let line_start = text[..span.start.min(text.len())]
                    .rfind('\n')
                    .map_or(0, |i| i + 1);
                let header = text[line_start..].trim_start().starts_with('[');
                msg = match key.trim_matches(['[', ']', ' ']) {
                    "" => msg,
                    k if header => format!("duplicate table `[{k}]`"),
                    k => format!("duplicate key `{k}`"),
                };
            }
            match line {
                Some(l) => anyhow!("{name}:{l}: {msg}"),
                None => anyhow!("{name}: {msg}"),
            }
        })?;
        let at = |span: std::ops::Range<usize>| format!("{name}:{}", line_of(text, span.start));

        let cam_span = file.camera.span();
        let c = file.camera.into_inner();
        let camera = (|| -> Result<Camera> {
            let eye = check_coord(c.eye, "camera.eye")?;
            let target = check_coord(c.target, "camera.target")?;
            let up = check_direction(c.up, "camera.up")?;
            if (target - eye).length_squared() < 1e-24 {
                bail!("camera.target: equals camera.eye");
            }
            if (target - eye).normalize().cross(up).length() < 1e-6 {
                bail!("camera.up: parallel to the view direction");
            }
            let fov = c.fov_y_deg;
            if !(fov.is_finite() && (MIN_FOV_DEG..MAX_FOV_DEG).contains(&fov)) {
                bail!(
                    "camera.fov_y_deg: must be in [{}, {}), got {}",
                    short(MIN_FOV_DEG),
                    short(MAX_FOV_DEG),
                    short(fov)
                );
            }
            let near = c.near;
            if !(near.is_finite() && (MIN_NEAR..=MAX_COORD).contains(&near)) {
                bail!(
                    "camera.near: must be in [{}, {}], got {}",
                    short(MIN_NEAR),
                    short(MAX_COORD),
                    short(near)
                );
            }
            let far = match c.far {
                FarFile::Number(f) => {
                    let f = positive(f, 2.0 * MAX_COORD, "camera.far")?;
                    if f <= near {
                        bail!(
                            "camera.far: must be greater than near ({}), got {}",
                            short(near),
                            short(f)
                        );
                    }
                    if f / near > MAX_DEPTH_RATIO {
                        bail!(
                            "camera.far: far/near must be at most {}, got {} / {} = {}; raise near",
                            short(MAX_DEPTH_RATIO),
                            short(f),
                            short(near),
                            short(f / near)
                        );
                    }
                    Far::Finite(f)
                }
                FarFile::Word(w) if w == "infinite" => Far::Infinite,
                FarFile::Word(w) => {
                    bail!("camera.far: expected a number or \"infinite\", got {w:?}")
                }
            };
            let [sx, sy] = c.shift;
            if !(sx.is_finite() && sy.is_finite() && sx.abs() <= MAX_SHIFT && sy.abs() <= MAX_SHIFT)
            {
                bail!(
                    "camera.shift: each component must be in [-{0}, {0}], got [{1}, {2}]",
                    short(MAX_SHIFT),
                    short(sx),
                    short(sy)
                );
            }
            Ok(Camera {
                eye,
                target,
                up,
                fov_y_deg: fov,
                near,
                far,
                shift: DVec2::new(sx, sy),
            })
        })()
        .map_err(|e| anyhow!("{}: {e}", at(cam_span)))?;

        let camera_path = match file.camera_path {
            Some(p) => {
                let span = p.span();
                let path = p.into_inner().validate();
                Some(path.map_err(|e| anyhow!("{}: {e}", at(span)))?)
            }
            None => None,
        };

        let ambient = match file.ambient {
            Some(a) => color3(a.color, "ambient.color").map_err(|e| anyhow!("{name}: {e}"))?,
            None => Vec3::splat(0.08),
        };

        let mut lights = Vec::new();
        for (i, l) in file.lights.into_iter().enumerate() {
            let span = l.span();
            let l = l.into_inner();
            let light = parse_light(l, i).map_err(|e| anyhow!("{}: {e}", at(span)))?;
            lights.push(light);
        }
        if lights.is_empty() {
            bail!("{name}: lights: the scene needs at least one [[lights]] entry");
        }

        let mut objects = Vec::new();
        let mut cache: Vec<(String, Arc<Mesh>)> = Vec::new();
        for (i, o) in file.objects.into_iter().enumerate() {
            let span = o.span();
            let o = o.into_inner();
            let obj =
                parse_object(o, i, dir, &mut cache).map_err(|e| anyhow!("{}: {e}", at(span)))?;
            objects.push(obj);
        }
        if objects.is_empty() {
            bail!("{name}: objects: the scene needs at least one [[objects]] entry");
        }
        let scene = Scene {
            name: name.to_string(),
            camera,
            ambient,
            lights,
            objects,
            camera_path,
        };
        scene.check_extent().map_err(|e| anyhow!("{name}: {e}"))?;
        Ok(scene)
    }

    /// The scene fits in [`crate::scene::limits::MAX_EXTENT`] (objects first, then
    /// the camera, then local lights: the message names the first entry that
    /// does not fit), and the farthest point of the scene (or the far plane,
    /// if nearer) over `near` is within [`MAX_REACH_OVER_NEAR`].
    fn check_extent(&self) -> Result<()> {
        let mut extent = Extent::default();
        for (i, o) in self.objects.iter().enumerate() {
            let world = o.mesh.positions.iter();
            extent.add(
                world.map(|p| o.model.transform_point3(p.as_dvec3())),
                &format!("objects[{i}]"),
            )?;
        }
        let c = &self.camera;
        extent.add([c.eye], "camera.eye")?;
        extent.add([c.target], "camera.target")?;
        for (i, l) in self.lights.iter().enumerate() {
            if let LightKind::Point { position, .. } | LightKind::Spot { position, .. } = l.kind {
                extent.add([position], &format!("lights[{i}].position"))?;
            }
        }
        // What the depth buffer must resolve: the scene, up to the far plane.
        let (lo, hi) = (extent.lo, extent.hi);
        let reach = (c.eye - lo).abs().max((c.eye - hi).abs()).length();
        let depth = match c.far {
            Far::Finite(f) => reach.min(f),
            Far::Infinite => reach,
        };
        if depth / c.near > MAX_REACH_OVER_NEAR {
            bail!(
                "camera.near: the scene reaches {} from the eye, and that (or far, if nearer) over near ({}) must be at most {}, got {}; raise near to at least {}",
                short(reach),
                short(c.near),
                short(MAX_REACH_OVER_NEAR),
                short(depth / c.near),
                short(depth / MAX_REACH_OVER_NEAR)
            );
        }
        Ok(())
    }

    /// A lesson's built-in scene: TOML compiled into the binary, meshes built in.
    pub fn builtin(name: &str, text: &str) -> Result<Scene> {
        let mut s = Scene::parse(text, name, Path::new("."))?;
        s.name = "default".into();
        Ok(s)
    }

    /// World-space bounds of every object, in `f64`.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for o in &self.objects {
            for p in &o.mesh.positions {
                let w = o.model.transform_point3(p.as_dvec3());
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
        (lo, hi)
    }

    /// The point everything is made relative to before going to `f32`:
    /// the centre of the scene bounds. Huge coordinates cancel here, in `f64`.
    pub fn origin(&self) -> DVec3 {
        let (lo, hi) = self.bounds();
        (lo + hi) * 0.5
    }

    /// Every object's origin-relative matrix in `f32`, `T(-origin) * model`,
    /// formed in `f64`. All at once: [`Scene::origin`] is a pass over every
    /// vertex, so finding it once per object would be quadratic.
    pub fn relative_models(&self) -> Vec<glam::Mat4> {
        let to_origin = DMat4::from_translation(-self.origin());
        self.objects
            .iter()
            .map(|o| (to_origin * o.model).as_mat4())
            .collect()
    }

    /// Every triangle in origin-relative world space, with its object index.
    pub fn world_triangles(&self) -> Vec<([Vec3; 3], u32)> {
        let origin = self.origin();
        let mut out = Vec::new();
        for (oi, o) in self.objects.iter().enumerate() {
            let rel = DMat4::from_translation(-origin) * o.model;
            let w: Vec<Vec3> = o
                .mesh
                .positions
                .iter()
                .map(|p| rel.transform_point3(p.as_dvec3()).as_vec3())
                .collect();
            for t in o.mesh.indices.chunks_exact(3) {
                out.push((
                    [w[t[0] as usize], w[t[1] as usize], w[t[2] as usize]],
                    oi as u32,
                ));
            }
        }
        out
    }
}

fn parse_object(
    o: ObjectFile,
    i: usize,
    dir: &Path,
    cache: &mut Vec<(String, Arc<Mesh>)>,
) -> Result<Object> {
    let p = format!("objects[{i}]");
    let t = check_coord(o.translate, &format!("{p}.translate"))?;
    let r = finite3(o.rotate_deg, &format!("{p}.rotate_deg"))?;
    let s = match o.scale {
        ScaleFile::Uniform(s) => DVec3::splat(s),
        ScaleFile::PerAxis(v) => DVec3::from(v),
    };
    if s.to_array()
        .iter()
        .any(|c| !(c.is_finite() && (MIN_SCALE..=MAX_SCALE).contains(&c.abs())))
    {
        bail!(
            "{p}.scale: every component must be non-zero, with a magnitude in [{}, {}]; got {}",
            short(MIN_SCALE),
            short(MAX_SCALE),
            short3(s)
        );
    }
    let color = color3(o.color, &format!("{p}.color"))?;
    let mesh = match cache.iter().find(|(n, _)| *n == o.mesh) {
        Some((_, m)) => m.clone(),
        None => {
            let m = Arc::new(load_mesh(&o.mesh, dir).map_err(|e| anyhow!("{p}.mesh: {e:#}"))?);
            cache.push((o.mesh.clone(), m.clone()));
            m
        }
    };
    // T * Rz * Ry * Rx * S: rotate about X first, then Y, then Z.
    let rot = DQuat::from_euler(
        EulerRot::ZYX,
        r.z.to_radians(),
        r.y.to_radians(),
        r.x.to_radians(),
    );
    let model = DMat4::from_scale_rotation_translation(s, rot, t);
    Ok(Object {
        mesh_name: o.mesh,
        mesh,
        model,
        color,
        casts_shadow: o.casts_shadow,
    })
}

/// A built-in name, or an `.obj` path relative to the scene's folder.
fn load_mesh(name: &str, dir: &Path) -> Result<Mesh> {
    if name.to_ascii_lowercase().ends_with(".obj") {
        let path: PathBuf = dir.join(name);
        crate::scene::obj::load_obj(&path)
    } else {
        crate::scene::mesh_dense::any_builtin(name)
    }
}

#[cfg(test)]
#[path = "unit_tests/scene.rs"]
mod tests;
