//! The three parsers under test, and what each guarantees of its answer.
//!
//! A refusal is one line that starts with the file (the name passed in,
//! or the path read) and then says where: a line number (`file:12: ...`)
//! or a field (`camera.near`, `lights[0].direction`, an exercise), or it
//! is one of the few refusals of the file as a whole, listed by parser.
//! An acceptance is sane: finite numbers within the format's limits, and
//! meshes whose indices are in range.

use std::path::Path;

use common::glam::{DVec3, Mat4, Vec3};
use common::scene::camera::{camera_matrices, light_view_proj};
use common::scene::camera_path::{check_path, path_cameras, MAX_PAN_DEG, MAX_PATH_FRAMES};
use common::scene::lights::MAX_ANGULAR_RADIUS_DEG;
use common::scene::limits::{
    MAX_COORD, MAX_DEPTH_RATIO, MAX_EXTENT, MAX_FOV_DEG, MAX_SHIFT, MIN_FOV_DEG, MIN_NEAR,
};
use common::scene::mesh::{face_normal, Mesh};
use common::scene::obj::{load_obj, parse_obj};
use common::scene::{Far, LightKind, LightSize, Scene};

use crate::spec::Spec;

/// What one call answered, judged.
pub enum Verdict {
    /// Accepted, and the result is sane.
    Accepted,
    /// Refused in one line that names the file and a place.
    Refused(String),
    /// A broken property: why.
    Broken(String),
}

/// How a parser is reached: its text in memory, or a file it reads.
pub enum Via<'a> {
    /// `parse(text, name, ...)`.
    Text(&'a str, &'a str),
    /// `load(path)`.
    File(&'a Path),
}

// ---- the scene format ----------------------------------------------------

/// The places a scene refusal may name instead of a line: the scene's
/// top-level fields (`camera.eye`, `lights[0].range`, `objects[2]`, ...),
/// and an unreadable file.
const SCENE_PLACES: &[&str] = &[
    "camera.",
    "camera_path",
    "ambient.",
    "lights",
    "objects",
    "cannot read scene file",
];

/// `Scene::parse` (OBJ paths relative to `scenes`) or `Scene::load`.
pub fn scene(via: Via, scenes: &Path) -> Verdict {
    let (result, name) = match via {
        Via::Text(text, name) => (Scene::parse(text, name, scenes), name.to_string()),
        Via::File(path) => (Scene::load(path), path.display().to_string()),
    };
    match result {
        Ok(s) => match scene_is_sane(&s) {
            Ok(()) => Verdict::Accepted,
            Err(why) => Verdict::Broken(format!("accepted, but {why}")),
        },
        Err(e) => refusal(&format!("{e:#}"), &name, SCENE_PLACES),
    }
}

/// Everything a lesson takes from a scene is finite and within the limits
/// of `common::scene::limits`, checked here without the parser's code.
fn scene_is_sane(s: &Scene) -> Result<(), String> {
    let c = &s.camera;
    for (v, what) in [(c.eye, "camera.eye"), (c.target, "camera.target")] {
        within(v, MAX_COORD, what)?;
    }
    unit(c.up, "camera.up")?;
    if c.eye == c.target {
        return Err("camera.eye equals camera.target".into());
    }
    if !(MIN_FOV_DEG..MAX_FOV_DEG).contains(&c.fov_y_deg) {
        return Err(format!("camera.fov_y_deg is {}", c.fov_y_deg));
    }
    if !(MIN_NEAR..=MAX_COORD).contains(&c.near) {
        return Err(format!("camera.near is {}", c.near));
    }
    if let Far::Finite(f) = c.far {
        if !(f.is_finite() && f > c.near && f / c.near <= MAX_DEPTH_RATIO) {
            return Err(format!("camera.far is {f} (near {})", c.near));
        }
    }
    if !(c.shift.is_finite() && c.shift.abs().max_element() <= MAX_SHIFT) {
        return Err(format!("camera.shift is {}", c.shift));
    }
    colour(s.ambient, "ambient.color")?;
    if s.lights.is_empty() || s.objects.is_empty() {
        return Err("no lights or no objects".into());
    }
    for (i, l) in s.lights.iter().enumerate() {
        light_is_sane(l, i)?;
    }
    for (i, o) in s.objects.iter().enumerate() {
        let what = format!("objects[{i}]");
        mesh_is_sane(&o.mesh, &what)?;
        colour(o.color, &what)?;
        if !o.model.is_finite() {
            return Err(format!("{what}: model matrix {}", o.model));
        }
        for p in &o.mesh.positions {
            within(o.model.transform_point3(p.as_dvec3()), MAX_COORD, &what)?;
        }
    }
    let (lo, hi) = s.bounds();
    if !(lo.is_finite() && hi.is_finite() && (hi - lo).max_element() <= MAX_EXTENT) {
        return Err(format!("bounds {lo} to {hi}"));
    }
    // What the GPU is handed: origin-relative f32 matrices.
    let m = camera_matrices(s, 320, 180);
    if ![m.view, m.proj, m.view_proj].iter().all(Mat4::is_finite) || !m.eye.is_finite() {
        return Err(format!("camera matrices not finite: {m:?}"));
    }
    for i in 0..s.lights.len() {
        if let Some(vp) = light_view_proj(s, i) {
            if !vp.is_finite() {
                return Err(format!("lights[{i}]: view-projection not finite: {vp}"));
            }
        }
    }
    if !s.relative_models().iter().all(Mat4::is_finite) {
        return Err("origin-relative model matrices not finite".into());
    }
    if let Some(p) = &s.camera_path {
        let frames = i64::from(p.frames);
        let pan = p.pan_deg.is_finite() && p.pan_deg.abs() <= MAX_PAN_DEG;
        let dolly = p.dolly.is_finite() && p.dolly.abs() <= MAX_EXTENT;
        if !((2..=MAX_PATH_FRAMES).contains(&frames) && pan && dolly) {
            return Err(format!("camera_path {p:?}"));
        }
        // The runner refuses a path that leaves the world (prefixing the
        // scene's name); a path it runs is finite all along.
        match check_path(s) {
            Err(e) => {
                let e = format!("{e:#}");
                if e.contains('\n') || !e.starts_with("camera_path.") {
                    return Err(format!("camera path refused with {e:?}"));
                }
            }
            Ok(()) => {
                let cams = path_cameras(c, p);
                if !cams
                    .iter()
                    .all(|k| k.eye.is_finite() && k.target.is_finite())
                {
                    return Err("camera path not finite".into());
                }
            }
        }
    }
    Ok(())
}

fn light_is_sane(l: &common::scene::Light, i: usize) -> Result<(), String> {
    let what = format!("lights[{i}]");
    colour(l.color, &what)?;
    let range_ok = |r: f64| r.is_finite() && r > 0.0 && r <= 2.0 * MAX_COORD;
    let limit = match l.kind {
        LightKind::Directional { direction } => {
            unit(direction, &what)?;
            MAX_ANGULAR_RADIUS_DEG
        }
        LightKind::Point { position, range } => {
            within(position, MAX_COORD, &what)?;
            range_ok(range)
                .then_some(0.5 * range)
                .ok_or(format!("{what}: range {range}"))?
        }
        LightKind::Spot {
            position,
            direction,
            range,
            spot_angle_deg: a,
        } => {
            within(position, MAX_COORD, &what)?;
            unit(direction, &what)?;
            if !(MIN_FOV_DEG..179.0).contains(&a) {
                return Err(format!("{what}: spot_angle_deg {a:?}"));
            }
            range_ok(range)
                .then_some(0.5 * range)
                .ok_or(format!("{what}: range {range}"))?
        }
    };
    let size = match (l.kind, l.size) {
        (LightKind::Directional { .. }, LightSize::AngularRadiusDeg(a)) => a,
        (LightKind::Point { .. } | LightKind::Spot { .. }, LightSize::Radius(r)) => r,
        _ => return Err(format!("{what}: size {:?} of the wrong kind", l.size)),
    };
    if !(0.0..=limit).contains(&size) {
        return Err(format!("{what}: size {size}, limit {limit}"));
    }
    Ok(())
}

fn within(v: DVec3, bound: f64, what: &str) -> Result<(), String> {
    match v.is_finite() && v.abs().max_element() <= bound {
        true => Ok(()),
        false => Err(format!("{what}: {v} is not within ±{bound}")),
    }
}

fn unit(v: DVec3, what: &str) -> Result<(), String> {
    match v.is_finite() && (v.length() - 1.0).abs() < 1e-9 {
        true => Ok(()),
        false => Err(format!("{what}: direction {v} is not unit length")),
    }
}

fn colour(c: Vec3, what: &str) -> Result<(), String> {
    match c.is_finite() && c.min_element() >= 0.0 {
        true => Ok(()),
        false => Err(format!("{what}: colour {c}")),
    }
}

/// What every mesh guarantees: triangles whose indices are in range,
/// finite positions, one finite unit normal per position.
fn mesh_is_sane(m: &Mesh, what: &str) -> Result<(), String> {
    let n = m.positions.len();
    if m.indices.is_empty() || !m.indices.len().is_multiple_of(3) {
        return Err(format!("{what}: {} indices", m.indices.len()));
    }
    if let Some(i) = m.indices.iter().find(|&&i| i as usize >= n) {
        return Err(format!("{what}: index {i} of {n} positions"));
    }
    if let Some(p) = m.positions.iter().find(|p| !p.is_finite()) {
        return Err(format!("{what}: position {p}"));
    }
    if m.normals.len() != n {
        return Err(format!(
            "{what}: {} normals, {n} positions",
            m.normals.len()
        ));
    }
    if let Some(v) = m
        .normals
        .iter()
        .find(|v| !(v.is_finite() && (v.length() - 1.0).abs() < 1e-3))
    {
        return Err(format!("{what}: normal {v}"));
    }
    Ok(())
}

// ---- OBJ -----------------------------------------------------------------

/// The refusals of an OBJ file as a whole (no line to name).
const OBJ_PLACES: &[&str] = &[
    "cannot read OBJ file",
    "no triangles",
    "every triangle is degenerate",
];

/// `parse_obj` or `load_obj`.
pub fn obj(via: Via) -> Verdict {
    let (result, name) = match via {
        Via::Text(text, name) => (parse_obj(text, name), name.to_string()),
        Via::File(path) => (load_obj(path), path.display().to_string()),
    };
    match result {
        Ok(m) => match obj_is_sane(&m) {
            Ok(()) => Verdict::Accepted,
            Err(why) => Verdict::Broken(format!("accepted, but {why}")),
        },
        Err(e) => refusal(&format!("{e:#}"), &name, OBJ_PLACES),
    }
}

/// [`mesh_is_sane`], and what `load_obj` promises beyond it: coordinates
/// within the world bound, no degenerate triangle, no unused vertex.
fn obj_is_sane(m: &Mesh) -> Result<(), String> {
    mesh_is_sane(m, "mesh")?;
    let too_far = |p: &&Vec3| p.abs().max_element() as f64 > MAX_COORD;
    if let Some(p) = m.positions.iter().find(too_far) {
        return Err(format!("position {p} beyond ±{MAX_COORD}"));
    }
    let mut used = vec![false; m.positions.len()];
    for t in m.triangles() {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || face_normal(a, b, c) == Vec3::ZERO {
            return Err(format!("degenerate triangle {t:?}"));
        }
        for i in t {
            used[i as usize] = true;
        }
    }
    match used.iter().position(|u| !u) {
        Some(i) => Err(format!("vertex {i} is in no triangle")),
        None => Ok(()),
    }
}

// ---- exercise specs ------------------------------------------------------

/// The places a spec refusal names: its entries, or the file as a whole.
const SPEC_PLACES: &[&str] = &[
    "exercise \"",
    "[[fix]] of",
    "no [[exercise]]",
    "cannot read the exercise spec",
];

/// `Spec::load` of a file (scene names relative to `scenes`).
pub fn spec(path: &Path, scenes: &Path) -> Verdict {
    match Spec::load(path, scenes) {
        Ok(s) => match spec_is_sane(&s) {
            Ok(()) => Verdict::Accepted,
            Err(why) => Verdict::Broken(format!("accepted, but {why}")),
        },
        Err(e) => refusal(&format!("{e:#}"), &path.display().to_string(), SPEC_PLACES),
    }
}

/// Every exercise is graded by its variant on at least one hidden check,
/// and every target (checks and hints alike) is one finite number or one
/// variant, scaled by finite numbers: a grader that compares with NaN or
/// infinity passes or fails whatever is measured.
fn spec_is_sane(s: &Spec) -> Result<(), String> {
    if s.exercises.is_empty() {
        return Err("no exercises".into());
    }
    for ex in &s.exercises {
        let what = &ex.variant;
        if !ex.variant.starts_with("exercise_") || ex.checks.is_empty() {
            return Err(format!("{what}: variant name or no checks"));
        }
        if !ex.checks.iter().any(|c| c.hidden) {
            return Err(format!("{what}: no hidden check"));
        }
        let checks = ex.checks.iter().map(|c| c.bound.target());
        for t in checks.chain(ex.hints.iter().map(|h| h.target())) {
            let one = t.value.is_some() != t.variant.is_some();
            let finite =
                t.value.is_none_or(f64::is_finite) && t.factor.is_finite() && t.slack.is_finite();
            if !(one && finite) {
                return Err(format!(
                    "{what}: target {:?} / {:?} x {} + {}",
                    t.value, t.variant, t.factor, t.slack
                ));
            }
        }
    }
    Ok(())
}

// ---- refusals ------------------------------------------------------------

/// One line, that starts with `name:`, then a line number or one of `places`.
fn refusal(msg: &str, name: &str, places: &[&str]) -> Verdict {
    if msg.contains(['\n', '\r']) {
        return Verdict::Broken(format!("refused in more than one line: {msg:?}"));
    }
    let Some(rest) = msg.strip_prefix(name).and_then(|r| r.strip_prefix(':')) else {
        return Verdict::Broken(format!("the refusal does not start with {name:?}: {msg:?}"));
    };
    let line = rest
        .split_once(':')
        .is_some_and(|(n, _)| n.parse::<usize>().is_ok_and(|n| n > 0));
    let place = places.iter().any(|p| rest.trim_start().starts_with(p));
    if line || place {
        Verdict::Refused(msg.to_string())
    } else {
        Verdict::Broken(format!("the refusal names no line and no field: {msg:?}"))
    }
}
