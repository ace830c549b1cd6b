//! What chapter 10's two pictures share: the default scene's spot light
//! and plank, measured from `scenes/lesson_10.toml` ([`Setup`]), the one
//! floor point both pictures show and its distances by the text's
//! definition ([`Setup::along_axis`]), their colours, and numbers as they
//! print them.

use anyhow::{bail, Context, Result};
use common::glam::DVec3;
use common::scene::{LightKind, LightSize, Scene};

pub(super) const EMITTER: &str = "#e6a800";
pub(super) const PLANK: &str = "#8e6bb0";
pub(super) const FOOT: &str = "#2a9d3a";
pub(super) const RAY: &str = "#d62728";

/// A number with `d` decimals.
pub(super) fn f(x: f64, d: usize) -> String {
    format!("{:.*}", d, x + 0.0)
}

/// The default scene's spot light and its plank (the highest thin caster,
/// a blocker plane parallel to the floor), origin-relative, and the floor
/// point p both pictures show.
pub(super) struct Setup {
    /// The light's position and unit axis.
    pub(super) light: DVec3,
    pub(super) axis: DVec3,
    /// The emitter's radius R.
    pub(super) radius: f64,
    /// The receiver p: the floor under the middle of the plank's long top
    /// edge away from the light, as the light's centre sees it (no side
    /// face of the plank shows beyond that edge).
    pub(super) p: DVec3,
    /// p's distance from the light along its axis, and that of the
    /// blocker the light's centre sees in front of p (the edge's middle,
    /// on the segment from p to the light): the text's d_r and d_b.
    pub(super) d_r: f64,
    pub(super) d_b: f64,
    /// The middle of the plank's far top edge: the blocker the light's
    /// centre sees in front of p (d_b is its distance).
    pub(super) edge: DVec3,
}

impl Setup {
    pub(super) fn from_scene(scene: &Scene) -> Result<Setup> {
        let light = &scene.lights[0];
        let LightKind::Spot {
            position,
            direction,
            ..
        } = light.kind
        else {
            bail!("scenes/lesson_10.toml: light 0 is not a spot light");
        };
        let LightSize::Radius(radius) = light.size else {
            bail!("scenes/lesson_10.toml: light 0 has no radius");
        };
        let tris = scene.world_triangles();
        let bounds = |o: u32| {
            tris.iter()
                .filter(|(_, k)| *k == o)
                .flat_map(|(t, _)| t)
                .fold((f64::MAX, f64::MIN), |(lo, hi), p| {
                    (lo.min(p.y as f64), hi.max(p.y as f64))
                })
        };
        // The floor: the largest object's lowest point; the plank: the
        // thin (under 10 cm) caster whose underside is highest.
        let floor_y = bounds(0).0;
        let plank = (1..scene.objects.len() as u32)
            .map(|o| (o, bounds(o)))
            .filter(|(_, (lo, hi))| hi - lo < 0.1)
            .max_by(|a, b| a.1 .0.total_cmp(&b.1 .0))
            .map(|(o, _)| o)
            .context("scenes/lesson_10.toml: no thin caster")?;
        let top = bounds(plank).1;
        let mut plank_top: Vec<DVec3> = Vec::new();
        for (t, _) in tris.iter().filter(|(_, k)| *k == plank) {
            for p in t.iter().map(|p| p.as_dvec3()) {
                if (p.y - top).abs() < 1e-4 && !plank_top.iter().any(|q| q.distance(p) < 1e-5) {
                    plank_top.push(p);
                }
            }
        }
        if plank_top.len() != 4 {
            bail!("the plank's top face has {} corners", plank_top.len());
        }
        let c = plank_top.iter().sum::<DVec3>() / 4.0;
        plank_top.sort_by(|a, b| {
            let ang = |p: &DVec3| (p.z - c.z).atan2(p.x - c.x);
            ang(a).total_cmp(&ang(b))
        });
        let (light, axis) = (position - scene.origin(), direction.normalize());
        // The long top edge farther from the light (horizontally), its
        // middle, and the floor point behind it on the ray from the light.
        let c = &plank_top;
        let mid = |i: usize| (c[i] + c[(i + 1) % 4]) / 2.0;
        let len = |i: usize| c[i].distance(c[(i + 1) % 4]);
        let mut long: Vec<usize> = (0..4).collect();
        long.sort_by(|&a, &b| len(b).total_cmp(&len(a)));
        let far = |i: usize| {
            let m = mid(i) - light;
            m.x * m.x + m.z * m.z
        };
        let i = long[..2]
            .iter()
            .copied()
            .max_by(|&a, &b| far(a).total_cmp(&far(b)))
            .context("the plank has no long edge")?;
        let edge = mid(i);
        let to = edge - light;
        let p = light + to * ((floor_y - light.y) / to.y);
        let mut setup = Setup {
            light,
            axis,
            radius,
            p,
            d_r: 0.0,
            d_b: 0.0,
            edge,
        };
        (setup.d_r, setup.d_b) = (setup.along_axis(p), setup.along_axis(edge));
        Ok(setup)
    }

    /// The text's distance: from the light's position to `x`, measured
    /// along the light's axis (what the spot's shadow map stores, linear).
    pub(super) fn along_axis(&self, x: DVec3) -> f64 {
        (x - self.light).dot(self.axis)
    }
}
