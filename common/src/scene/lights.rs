//! The `[[lights]]` tables of a scene file: a light's kind (directional,
//! point, spot), its colour, and its size (lesson 10's area lights).

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum LightKind {
    /// `direction` is the way the light travels (unit length).
    Directional {
        direction: DVec3,
    },
    Point {
        position: DVec3,
        range: f64,
    },
    Spot {
        position: DVec3,
        direction: DVec3,
        range: f64,
        spot_angle_deg: f64,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Light {
    pub kind: LightKind,
    pub color: Vec3,
    /// The emitter's size (lesson 10): a sphere of this radius, scene
    /// units, for point and spot lights (`radius`), or a cone of this
    /// half-angle for directional ones (`angular_radius_deg`). 0: a hard
    /// light, a point or one direction.
    pub size: LightSize,
}

/// How big a light's emitter is; [`LightSize::HARD`] for a point or a
/// single direction.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum LightSize {
    /// Point and spot lights: the radius of the spherical emitter.
    Radius(f64),
    /// Directional lights: the half-angle of the cone of directions, degrees.
    AngularRadiusDeg(f64),
}

impl LightSize {
    pub const HARD: LightSize = LightSize::Radius(0.0);

    /// Whether the emitter has a size (a soft shadow's light).
    pub fn is_area(self) -> bool {
        match self {
            LightSize::Radius(r) | LightSize::AngularRadiusDeg(r) => r > 0.0,
        }
    }
}

use anyhow::{anyhow, bail, Result};
use glam::{DVec3, Vec3};

use crate::scene::file::LightFile;
use crate::scene::limits::{
    check_coord, check_direction, color3, positive, short, MAX_COORD, MIN_FOV_DEG,
};

pub(crate) fn parse_light(l: LightFile, i: usize) -> Result<Light> {
    let p = format!("lights[{i}]");
    let color = color3(l.color, &format!("{p}.color"))?;
    let need = |v: Option<[f64; 3]>, f: &str| -> Result<[f64; 3]> {
        v.ok_or_else(|| anyhow!("{p}.{f}: required for a {} light", l.kind))
    };
    let range = |r: Option<f64>| -> Result<f64> {
        positive(
            r.ok_or_else(|| anyhow!("{p}.range: required for a {} light", l.kind))?,
            2.0 * MAX_COORD,
            &format!("{p}.range"),
        )
    };
    let kind = match l.kind.as_str() {
        "directional" => LightKind::Directional {
            direction: check_direction(need(l.direction, "direction")?, &format!("{p}.direction"))?,
        },
        "point" => LightKind::Point {
            position: check_coord(need(l.position, "position")?, &format!("{p}.position"))?,
            range: range(l.range)?,
        },
        "spot" => {
            let a = l.spot_angle_deg.ok_or_else(|| anyhow!("{p}.spot_angle_deg: required for a spot light"))?;
            // The spot's shadow map is a perspective, like the camera's.
            if !(a.is_finite() && (MIN_FOV_DEG..179.0).contains(&a)) {
                bail!("{p}.spot_angle_deg: must be in [{}, 179), got {}", short(MIN_FOV_DEG), short(a));
            }
            LightKind::Spot {
                position: check_coord(need(l.position, "position")?, &format!("{p}.position"))?,
                direction: check_direction(need(l.direction, "direction")?, &format!("{p}.direction"))?,
                range: range(l.range)?,
                spot_angle_deg: a,
            }
        }
        other => bail!("{p}.type: unknown light type {other:?} (expected \"directional\", \"point\" or \"spot\")"),
    };
    let size = parse_size(&l, &kind, &p)?;
    Ok(Light { kind, color, size })
}

/// The widest cone a directional light may have (`angular_radius_deg`).
pub const MAX_ANGULAR_RADIUS_DEG: f64 = 45.0;

// ANCHOR: light_size
/// `radius` (point, spot) or `angular_radius_deg` (directional): absent or 0
/// is a hard light. A point or spot emitter fits well inside its range.
fn parse_size(l: &LightFile, kind: &LightKind, p: &str) -> Result<LightSize> {
    let check = |x: f64, max: f64, what: &str| -> Result<f64> {
        if !(x.is_finite() && (0.0..=max).contains(&x)) {
            bail!(
                "{p}.{what}: must be in [0, {}], got {}",
                short(max),
                short(x)
            );
        }
        Ok(x)
    };
    match *kind {
        LightKind::Directional { .. } => {
            if l.radius.is_some() {
                bail!(
                    "{p}.radius: a directional light's size is angular_radius_deg (the sun: 0.27)"
                );
            }
            let a = l.angular_radius_deg.unwrap_or(0.0);
            Ok(LightSize::AngularRadiusDeg(check(
                a,
                MAX_ANGULAR_RADIUS_DEG,
                "angular_radius_deg",
            )?))
        }
        LightKind::Point { range, .. } | LightKind::Spot { range, .. } => {
            if l.angular_radius_deg.is_some() {
                bail!("{p}.angular_radius_deg: only directional lights have one; a {} light's size is radius", l.kind);
            }
            let r = l.radius.unwrap_or(0.0);
            Ok(LightSize::Radius(check(
                r,
                0.5 * range,
                "radius (at most half the range)",
            )?))
        }
    }
}
// ANCHOR_END: light_size
