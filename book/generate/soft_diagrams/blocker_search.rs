//! Picture (b), the blocker search (`soft_blocker_search.svg`): the search's
//! footprint on lesson 10's shadow map, its taps, and what the light sees
//! through each, beside the geometric footprint. `filter_radius` and
//! `vogel` restate the two small WGSL functions (`soft.wgsl`) it checks.

use std::f64::consts::PI;

use anyhow::{Context, Result};
use common::glam::{DVec3, Mat4, Vec3};
use common::reference::bvh::Bvh;
use common::scene::camera::light_view_proj;
use common::scene::Scene;
use workbook::lesson_10::soft::{LightGeometry, Technique};

use super::setup::{f, Setup, FOOT, PLANK, RAY};
use crate::diagrams::svg::{add, fill, stroke, Svg, INK, P};

/// `filter_radius` of `soft.wgsl` (map units, u and v): the emitter's
/// footprint on the plane at `d_b`, as the map sees it.
fn filter_radius(g: &LightGeometry, d_r: f64, d_b: f64) -> [f64; 2] {
    let h = (d_r - d_b).max(0.0);
    let k = if g.perspective {
        g.size as f64 * h / (d_r * d_b.max(1e-6))
    } else {
        h * g.size as f64
    };
    [k * g.uv_per[0] as f64, k * g.uv_per[1] as f64]
}

/// The receiver's mark: a `+` at `c`, its arms `r` long.
fn plus(s: &mut Svg, c: P, r: f64) {
    s.line(add(c, -r, 0.0), add(c, r, 0.0), &stroke("#000", 2.0, ""));
    s.line(add(c, 0.0, -r), add(c, 0.0, r), &stroke("#000", 2.0, ""));
}

/// `vogel` of `soft.wgsl`: point `i` of an `n`-point golden-angle spiral.
fn vogel(i: u32, n: u32, angle: f64) -> P {
    let r = ((i as f64 + 0.5) / n as f64).sqrt();
    let t = i as f64 * 2.39996323 + angle;
    (r * t.cos(), r * t.sin())
}

/// An object's colour as `#rrggbb`.
fn hex(c: Vec3) -> String {
    let b = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", b(c.x), b(c.y), b(c.z))
}

/// A world point's map coordinates (u, v, distance along the axis).
fn map_uv(m: Mat4, p: DVec3) -> (f64, f64, f64) {
    let c = (m * p.as_vec3().extend(1.0)).as_dvec4();
    ((c.x / c.w + 1.0) * 0.5, (1.0 - c.y / c.w) * 0.5, c.w)
}

/// What the light sees through a texel centre: the hit object and its
/// distance along the light's axis, or nothing.
fn texel_ray(m: Mat4, bvh: &Bvh, owner: &[u32], light: DVec3, uv: P) -> Option<(u32, DVec3)> {
    let inv = m.inverse();
    let ndc = Vec3::new((2.0 * uv.0 - 1.0) as f32, (1.0 - 2.0 * uv.1) as f32, 0.5);
    let far = inv.project_point3(ndc).as_dvec3();
    let dir = (far - light).normalize();
    let hit = bvh.closest_hit(light.as_vec3(), dir.as_vec3(), 1.0e4)?;
    Some((owner[hit.tri as usize], light + dir * hit.t as f64))
}

/// The search of the picture, on the map: what it draws of PCSS's first
/// step at the receiver p.
pub(super) struct Search {
    /// The light's matrix and the map's side (texels).
    pub(super) m: Mat4,
    pub(super) size: f64,
    /// p's map coordinates: the disk's centre.
    pub(super) centre: P,
    /// The nearest caster's distance from the light, along its axis.
    pub(super) d_n: f64,
    /// The search disk's radius (map units, u and v): the shader's
    /// `filter_radius(d_r, d_n)`.
    pub(super) radius: [f64; 2],
}

/// The search disk at the setup's receiver p.
pub(super) fn search(scene: &Scene, u: &Setup) -> Result<Search> {
    let g = LightGeometry::new(scene, 0).context("lesson 10's light has no geometry")?;
    let m = light_view_proj(scene, 0).context("no light matrix")?;
    let (su, sv, _) = map_uv(m, u.p);
    let d_n = (g.nearest_caster as f64).min(u.d_r);
    Ok(Search {
        m,
        size: Technique::Pcss(Technique::PCSS).map_size() as f64,
        centre: (su, sv),
        d_n,
        radius: filter_radius(&g, u.d_r, d_n),
    })
}

pub(super) fn blocker_search(scene: &Scene, u: &Setup) -> Result<String> {
    let g = LightGeometry::new(scene, 0).context("lesson 10's light has no geometry")?;
    let Search {
        m,
        size,
        centre: (su, sv),
        d_n,
        radius: search,
    } = search(scene, u)?;
    let taps = Technique::PCSS.search_taps;
    let tris = scene.world_triangles();
    let owner: Vec<u32> = tris.iter().map(|(_, o)| *o).collect();
    let bvh = Bvh::build(tris.iter().map(|(t, _)| *t).collect());
    let (p, d_r) = (u.p, u.d_r);
    // 1. The search disk (the shader's radius) and, dashed, the emitter's
    // disk carried through p onto the nearest caster's plane.
    let (a1, a2) = {
        let a = u.axis;
        let t = if a.y.abs() < 0.9 { DVec3::Y } else { DVec3::X };
        let a1 = a.cross(t).normalize();
        (a1, a.cross(a1))
    };
    let footprint: Vec<(f64, f64)> = (0..72)
        .map(|k| {
            let t = k as f64 / 72.0 * 2.0 * PI;
            let q = u.light + u.radius * (t.cos() * a1 + t.sin() * a2);
            let x = p + (q - p) * ((d_r - d_n) / d_r);
            let (x_u, x_v, _) = map_uv(m, x);
            (x_u, x_v)
        })
        .collect();
    // The window of texels drawn, around the receiver's texel.
    let half = ((search[0].max(search[1]) * size * 1.2).ceil() as i64 + 2).min(60);
    let (ti, tj) = ((su * size).floor() as i64, (sv * size).floor() as i64);
    let n = 2 * half + 1;
    let (left, top, cell) = (20.0, 50.0, (460.0 / n as f64).floor());
    let grid = cell * n as f64;
    let to_px = |uv: P| {
        (
            left + (uv.0 * size - (ti - half) as f64) * cell,
            top + (uv.1 * size - (tj - half) as f64) * cell,
        )
    };
    // Each texel: is what the light sees there in front of the receiver's
    // plane (the floor)? Keep its distance along the axis if so.
    let blocker_at = |i: i64, j: i64| -> Option<(u32, f64)> {
        let uv = ((i as f64 + 0.5) / size, (j as f64 + 0.5) / size);
        let (o, x) = texel_ray(m, &bvh, &owner, u.light, uv)?;
        (x.y > p.y + 1e-3).then(|| (o, map_uv(m, x).2))
    };
    let title = "The blocker search of one floor point (lesson 10's PCSS)";
    let mut s = Svg::new(800.0, 0.0, title);
    let mut kinds = Vec::new();
    for j in tj - half..=tj + half {
        for i in ti - half..=ti + half {
            let b = blocker_at(i, j);
            let colour = match b {
                Some((o, _)) => {
                    kinds.push(o);
                    hex(scene.objects[o as usize].color)
                }
                None => "#ececec".into(),
            };
            let at = (
                left + (i - ti + half) as f64 * cell,
                top + (j - tj + half) as f64 * cell,
            );
            s.rect(
                at,
                (cell, cell),
                &format!(r##"fill="{colour}" stroke="#fff" stroke-width="0.4""##),
            );
        }
    }
    s.rect((left, top), (grid, grid), INK);
    // The search disk (the shader's radius) and the geometric footprint.
    let ring = |r: [f64; 2]| -> Vec<P> {
        (0..72)
            .map(|k| {
                let t = k as f64 / 72.0 * 2.0 * PI;
                to_px((su + r[0] * t.cos(), sv + r[1] * t.sin()))
            })
            .collect()
    };
    s.poly(&ring(search), true, &stroke("#1f5fbf", 2.0, ""));
    let foot: Vec<P> = footprint.iter().map(|&q| to_px(q)).collect();
    s.poly(&foot, true, &stroke(FOOT, 2.0, "6 4"));
    // The taps (angle 0: the shader turns them per pixel).
    let mut found = Vec::new();
    for k in 0..taps {
        let o = vogel(k, taps, 0.0);
        let uv = (su + o.0 * search[0], sv + o.1 * search[1]);
        let (i, j) = ((uv.0 * size).floor() as i64, (uv.1 * size).floor() as i64);
        let hit = blocker_at(i, j);
        let centre = to_px(((i as f64 + 0.5) / size, (j as f64 + 0.5) / size));
        match hit {
            Some((_, d)) => {
                found.push(d);
                s.circle(centre, 4.5, &fill(RAY, "#fff"));
            }
            None => s.circle(centre, 4.5, &fill("#fff", "#222")),
        }
    }
    let sp = to_px((su, sv));
    plus(&mut s, sp, 7.0);
    // 2. The mean blocker distance, and the filter disk it gives.
    let mean = found.iter().sum::<f64>() / found.len().max(1) as f64;
    let (lo, hi) = found
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &d| (a.min(d), b.max(d)));
    let filter = filter_radius(&g, d_r, mean);
    if !found.is_empty() {
        s.poly(&ring(filter), true, &stroke("#222", 1.5, "3 3"));
    }
    // The legend and the numbers, on the right.
    let (lx, mut y) = (left + grid + 24.0, top + 14.0);
    let lw = 800.0 - lx - 16.0;
    let rows: Vec<(String, String)> = [
        (
            r##"fill="#ececec" stroke="#999""##.to_string(),
            "a texel that sees the floor (no blocker)".to_string(),
        ),
        (
            fill(
                &kinds
                    .first()
                    .map_or(PLANK.into(), |&o| hex(scene.objects[o as usize].color)),
                "#555",
            ),
            format!(
                "a texel that sees a caster in front of the floor (its colour; {} of {} drawn)",
                kinds.len(),
                n * n
            ),
        ),
    ]
    .into();
    for (style, t) in rows {
        s.rect((lx, y - 10.0), (16.0, 11.0), &style);
        y = s.para((lx + 24.0, y), 12.0, "start", lw - 24.0, &t) + 4.0;
    }
    let marks: [(&str, String); 5] = [
        ("+", "the receiver p: the floor point under the plank's far edge".into()),
        ("o", format!("the {taps} search taps (Vogel's spiral, angle 0), at their texels; filled red: a blocker found")),
        ("—", format!("the search disk: filter_radius(d_r, d_n), {} texels", f(search[0] * size, 1))),
        ("- -", "the emitter's disk seen from p, on the nearest caster's plane".into()),
        (":", format!("the filter disk from the blockers' mean: {} texels", f(filter[0] * size, 1))),
    ];
    for (i, (_, t)) in marks.iter().enumerate() {
        let c = (lx + 8.0, y - 4.0);
        match i {
            0 => plus(&mut s, c, 6.0),
            1 => s.circle(c, 4.5, &fill(RAY, "#fff")),
            2 => s.line(
                add(c, -8.0, 0.0),
                add(c, 8.0, 0.0),
                &stroke("#1f5fbf", 2.0, ""),
            ),
            3 => s.line(
                add(c, -8.0, 0.0),
                add(c, 8.0, 0.0),
                &stroke(FOOT, 2.0, "6 4"),
            ),
            _ => s.line(
                add(c, -8.0, 0.0),
                add(c, 8.0, 0.0),
                &stroke("#222", 1.5, "3 3"),
            ),
        }
        y = s.para((lx + 24.0, y), 12.0, "start", lw - 24.0, t) + 4.0;
    }
    let numbers = [
        format!("map: {0}×{0} texels, one cell each", size as u32),
        "distances from the light, along its axis:".to_string(),
        format!("d_r = {} m (p)", f(d_r, 2)),
        format!("d_b = {} m (the plank's edge above p)", f(u.d_b, 2)),
        format!("d_n = {} m (the nearest caster)", f(d_n, 2)),
        format!("blockers found: {} of {taps},", found.len()),
        format!("at {} to {} m; their mean", f(lo, 2), f(hi, 2)),
        format!("d̄ = {} m, PCSS's estimate of d_b", f(mean, 2)),
    ];
    y = s.texts((lx, y + 10.0), 12.0, "start", &numbers);
    let note = "The map's texels around p's, coloured by what the light sees through each. \
        The search reads one texel per tap and keeps those in front of the receiver's plane; \
        the mean of their distances sizes the filter. The plank is not square to the light's \
        axis, so the points of it the taps find lie at different distances, and their mean is \
        not the distance of its edge above p. The blue disk is the shader's search radius; the \
        dashed green ring, the emitter's disk carried through p onto the nearest caster's plane \
        (square to the axis, at d_n) and projected by the light's matrix: the two coincide.";
    let bottom = (top + grid).max(y) + 24.0;
    s.h = s.para((left, bottom), 12.0, "start", 800.0 - 2.0 * left, note);
    Ok(s.finish())
}

#[cfg(test)]
mod tests {

    use common::glam::{DVec3, Vec4};
    use common::scene::{LightKind, Scene};

    use super::super::setup::Setup;
    use super::*;

    /// The search disk drawn is the emitter seen from p on the nearest
    /// caster's plane, computed another way: the nearest caster found
    /// again from the scene's triangles (distance along the scene's axis),
    /// each ray from p to the emitter's rim cut by that plane, and the cut
    /// projected by the light's matrix. Every cut lies on the drawn disk,
    /// and its centre is p's texel. The printed distances are the text's,
    /// as in the similar triangles.
    #[test]
    fn the_search_disk_is_the_emitter_seen_from_p_on_the_nearest_casters_plane() {
        let root = &crate::repo_root();
        let scene = Scene::load(&root.join("scenes/lesson_10.toml")).unwrap();
        let u = Setup::from_scene(&scene).unwrap();
        let drawn = search(&scene, &u).unwrap();
        let m = light_view_proj(&scene, 0).unwrap();
        let LightKind::Spot {
            position,
            direction,
            ..
        } = scene.lights[0].kind
        else {
            panic!("lesson 10's light is a spot");
        };
        let (light, axis) = (position - scene.origin(), direction.normalize());
        let along = |x: DVec3| (x - light).dot(axis);
        // The nearest casting vertex the light's frustum holds.
        let seen = |c: Vec4| c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w && c.z >= 0.0;
        let d_n = (scene.world_triangles().iter())
            .filter(|(_, o)| scene.objects[*o as usize].casts_shadow)
            .flat_map(|(t, _)| t.iter())
            .filter(|v| seen(m * v.extend(1.0)))
            .map(|v| along(v.as_dvec3()))
            .fold(f64::MAX, f64::min);
        assert!(
            (drawn.d_n - d_n).abs() < 1e-3,
            "d_n {} against {d_n}",
            drawn.d_n
        );
        let uv = |x: DVec3| {
            let n = m.project_point3(x.as_vec3()).as_dvec3();
            ((n.x + 1.0) / 2.0, (1.0 - n.y) / 2.0)
        };
        let c = uv(u.p);
        assert!((c.0 - drawn.centre.0).hypot(c.1 - drawn.centre.1) < 1e-6);
        // The emitter's rim, square to the axis, from a basis of its own.
        let e1 = (DVec3::X - axis * axis.x).normalize();
        let e2 = axis.cross(e1);
        let d_r = along(u.p);
        for k in 0..24 {
            let t = k as f64 / 24.0 * std::f64::consts::TAU;
            let q = light + u.radius * (t.cos() * e1 + t.sin() * e2);
            // The ray from p to q, cut by the plane at d_n along the axis.
            let s = (d_n - d_r) / (along(q) - d_r);
            let x = uv(u.p + (q - u.p) * s);
            let e = ((x.0 - c.0) / drawn.radius[0]).hypot((x.1 - c.1) / drawn.radius[1]);
            assert!(
                (e - 1.0).abs() < 2e-3,
                "rim point {k}: {e} radii from p's texel"
            );
        }
        // The printed distances: d_r and d_b by the text's definition.
        let svg = blocker_search(&scene, &u).unwrap();
        // The plank (object 4): the top of its triangles.
        let top = (scene.world_triangles().iter())
            .filter(|(_, o)| *o == 4)
            .flat_map(|(t, _)| t.iter().map(|v| v.y as f64))
            .fold(f64::MIN, f64::max);
        let b = light + (u.p - light) * ((light.y - top) / (light.y - u.p.y));
        for (label, want) in [("d_r", d_r), ("d_b", along(b)), ("d_n", d_n)] {
            let at = svg.find(&format!("{label} = ")).expect(label) + label.len() + 3;
            let got: f64 = svg[at..].split(" m").next().unwrap().parse().unwrap();
            assert!(
                (got - want).abs() <= 0.0051,
                "printed {label} = {got}, want {want}"
            );
        }
    }
}
