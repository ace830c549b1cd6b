//! The scene file as written (TOML), before [`crate::scene`] validates it.
//!
//! `scale` and `far` take a number or something else; they are read by hand,
//! not as serde `untagged` enums, whose message names a Rust type ("did not
//! match any variant of untagged enum ScaleFile") instead of the field.

use anyhow::{bail, Result};
use serde::Deserialize;
use toml::Spanned;

use crate::scene::limits::{short, MAX_EXTENT};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SceneFile {
    pub(crate) camera: Spanned<CameraFile>,
    #[serde(default)]
    pub(crate) ambient: Option<AmbientFile>,
    #[serde(default)]
    pub(crate) lights: Vec<Spanned<LightFile>>,
    #[serde(default)]
    pub(crate) objects: Vec<Spanned<ObjectFile>>,
    #[serde(default)]
    pub(crate) camera_path: Option<Spanned<CameraPathFile>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CameraFile {
    pub(crate) eye: [f64; 3],
    pub(crate) target: [f64; 3],
    #[serde(default = "default_up")]
    pub(crate) up: [f64; 3],
    #[serde(default = "default_fov")]
    pub(crate) fov_y_deg: f64,
    #[serde(default = "default_near")]
    pub(crate) near: f64,
    #[serde(default = "default_far", deserialize_with = "far_file")]
    pub(crate) far: FarFile,
    /// Lens shift in NDC units: the image moves by `[sx, sy]` half-widths
    /// and half-heights (an off-centre frustum).
    #[serde(default, deserialize_with = "shift_file")]
    pub(crate) shift: [f64; 2],
}

/// Written by hand, not `untagged`: serde's message for that names a Rust
/// type ("did not match any variant of untagged enum FarFile").
pub(crate) enum FarFile {
    Number(f64),
    Word(String),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct AmbientFile {
    pub(crate) color: [f32; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LightFile {
    #[serde(rename = "type")]
    pub(crate) kind: String,
    pub(crate) direction: Option<[f64; 3]>,
    pub(crate) position: Option<[f64; 3]>,
    pub(crate) range: Option<f64>,
    pub(crate) spot_angle_deg: Option<f64>,
    /// Point and spot: the emitter's radius (lesson 10).
    pub(crate) radius: Option<f64>,
    /// Directional: the cone's half-angle in degrees (lesson 10).
    pub(crate) angular_radius_deg: Option<f64>,
    #[serde(default = "default_white")]
    pub(crate) color: [f32; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ObjectFile {
    pub(crate) mesh: String,
    #[serde(default)]
    pub(crate) translate: [f64; 3],
    #[serde(default)]
    pub(crate) rotate_deg: [f64; 3],
    #[serde(default = "default_scale", deserialize_with = "scale_file")]
    pub(crate) scale: ScaleFile,
    #[serde(default = "default_grey")]
    pub(crate) color: [f32; 3],
    #[serde(default = "default_true")]
    pub(crate) casts_shadow: bool,
}

/// `[camera_path]`: see [`crate::scene::camera_path`].
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CameraPathFile {
    #[serde(default = "default_path_frames", deserialize_with = "whole_number")]
    pub(crate) frames: i64,
    #[serde(default, deserialize_with = "pan_deg")]
    pub(crate) pan_deg: f64,
    #[serde(default, deserialize_with = "dolly")]
    pub(crate) dolly: f64,
}

/// The most frames a camera path may have (each costs a reference ray cast).
pub const MAX_PATH_FRAMES: i64 = 1000;

/// The most a camera path may pan, either way (degrees).
pub const MAX_PAN_DEG: f64 = 360.0;

/// `[camera_path]`, validated; the path's maths is in [`crate::scene::camera_path`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraPath {
    /// At least 2.
    pub frames: u32,
    /// Frames 0 ..= n/2: the view direction yaws about `up` (right-handed:
    /// positive turns left) from 0 to this.
    pub pan_deg: f64,
    /// Frames n/2 ..= n-1: eye and target move this far forward, along the
    /// view direction at the pan's end (negative: backward).
    pub dolly: f64,
}

impl CameraPathFile {
    /// The path, if every field is in range (one line naming the field).
    pub(crate) fn validate(self) -> Result<CameraPath> {
        if !(2..=MAX_PATH_FRAMES).contains(&self.frames) {
            bail!(
                "camera_path.frames: must be in [2, {MAX_PATH_FRAMES}], got {}",
                self.frames
            );
        }
        let (pan, dolly) = (self.pan_deg, self.dolly);
        if !(pan.is_finite() && pan.abs() <= MAX_PAN_DEG) {
            bail!(
                "camera_path.pan_deg: must be in [-{0}, {0}], got {1}",
                short(MAX_PAN_DEG),
                short(pan)
            );
        }
        if !(dolly.is_finite() && dolly.abs() <= MAX_EXTENT) {
            bail!(
                "camera_path.dolly: must be in [-{0}, {0}], got {1}",
                short(MAX_EXTENT),
                short(dolly)
            );
        }
        if pan == 0.0 && dolly == 0.0 {
            bail!("camera_path: pan_deg and dolly are both 0, so the camera never moves; set one");
        }
        Ok(CameraPath {
            frames: self.frames as u32,
            pan_deg: pan,
            dolly,
        })
    }
}

pub(crate) enum ScaleFile {
    Uniform(f64),
    PerAxis([f64; 3]),
}

/// A TOML number as `f64` (integers too).
pub(crate) fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) => Some(*f),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// A value as written, cut short for a one-line message.
pub(crate) fn written(v: &toml::Value) -> String {
    let s = v.to_string();
    if s.chars().count() > 40 {
        format!("{}...", s.chars().take(40).collect::<String>())
    } else {
        s
    }
}

pub(crate) fn scale_file<'de, D: serde::Deserializer<'de>>(d: D) -> Result<ScaleFile, D::Error> {
    let v = toml::Value::deserialize(d)?;
    if let Some(s) = number(&v) {
        return Ok(ScaleFile::Uniform(s));
    }
    if let toml::Value::Array(a) = &v {
        if let [Some(x), Some(y), Some(z)] = a.iter().map(number).collect::<Vec<_>>()[..] {
            return Ok(ScaleFile::PerAxis([x, y, z]));
        }
    }
    Err(serde::de::Error::custom(format!(
        "scale: expected a number or [x, y, z], got {}",
        written(&v)
    )))
}

pub(crate) fn far_file<'de, D: serde::Deserializer<'de>>(d: D) -> Result<FarFile, D::Error> {
    let v = toml::Value::deserialize(d)?;
    match (&v, number(&v)) {
        (_, Some(f)) => Ok(FarFile::Number(f)),
        (toml::Value::String(w), _) => Ok(FarFile::Word(w.clone())),
        _ => Err(serde::de::Error::custom(format!(
            "far: expected a number or \"infinite\", got {}",
            written(&v)
        ))),
    }
}

/// `camera.shift`: two numbers; the range is checked later.
pub(crate) fn shift_file<'de, D: serde::Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
    let v = toml::Value::deserialize(d)?;
    if let toml::Value::Array(a) = &v {
        if let [Some(x), Some(y)] = a.iter().map(number).collect::<Vec<_>>()[..] {
            return Ok([x, y]);
        }
    }
    Err(serde::de::Error::custom(format!(
        "camera.shift: expected [sx, sy] (two numbers), got {}",
        written(&v)
    )))
}

/// A whole number (`camera_path.frames`); the range is checked later.
pub(crate) fn whole_number<'de, D: serde::Deserializer<'de>>(d: D) -> Result<i64, D::Error> {
    match toml::Value::deserialize(d)? {
        toml::Value::Integer(i) => Ok(i),
        v => Err(serde::de::Error::custom(format!(
            "camera_path.frames: expected a whole number, got {}",
            written(&v)
        ))),
    }
}

/// A number (integers too), or a message that names `camera_path.{field}`.
fn path_number<E: serde::de::Error>(v: toml::Value, field: &str) -> Result<f64, E> {
    number(&v).ok_or_else(|| {
        E::custom(format!(
            "camera_path.{field}: expected a number, got {}",
            written(&v)
        ))
    })
}
pub(crate) fn pan_deg<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    path_number(toml::Value::deserialize(d)?, "pan_deg")
}
pub(crate) fn dolly<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    path_number(toml::Value::deserialize(d)?, "dolly")
}

pub(crate) fn default_path_frames() -> i64 {
    16
}
pub(crate) fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}
pub(crate) fn default_fov() -> f64 {
    50.0
}
pub(crate) fn default_near() -> f64 {
    0.1
}
pub(crate) fn default_far() -> FarFile {
    FarFile::Number(100.0)
}
pub(crate) fn default_white() -> [f32; 3] {
    [1.0; 3]
}
pub(crate) fn default_grey() -> [f32; 3] {
    [0.8; 3]
}
pub(crate) fn default_scale() -> ScaleFile {
    ScaleFile::Uniform(1.0)
}
pub(crate) fn default_true() -> bool {
    true
}
