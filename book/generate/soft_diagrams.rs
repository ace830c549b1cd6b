//! Chapter 10's pictures of PCSS, drawn from lesson 10's own scene
//! (`scenes/lesson_10.toml`) and geometry (`LightGeometry`, the light's
//! matrix): the similar triangles of the penumbra's width, and the blocker
//! search's footprint on the shadow map. Every number a picture shows is
//! computed here.
//!
//! The penumbra's formula and the search's taps live in WGSL only
//! (`shaders/lesson_10/soft.wgsl`: `filter_radius`, `vogel`): the first
//! picture constructs the triangles by intersecting rays instead, and the
//! second restates those two small functions ([`filter_radius`],
//! [`vogel`]), checked against the geometric footprint it draws beside them.

use std::f64::consts::PI;
use std::path::Path;

use anyhow::{bail, Context, Result};
use common::glam::{DVec3, Mat4, Vec3};
use common::reference::bvh::Bvh;
use common::scene::camera::light_view_proj;
use common::scene::{LightKind, LightSize, Scene};
use workbook::lesson_10::soft::{LightGeometry, Technique};

use crate::diagrams::{add, fill, stroke, Svg, INK, P};

/// Writes chapter 10's diagrams into `dir` and returns the names written.
pub fn write_all(root: &Path, dir: &Path) -> Result<Vec<String>> {
    crate::diagrams::write_svgs(dir, render(root)?)
}

fn render(root: &Path) -> Result<[(&'static str, String); 2]> {
    let scene = Scene::load(&root.join("scenes/lesson_10.toml"))?;
    let setup = Setup::from_scene(&scene)?;
    Ok([
        ("soft_similar_triangles.svg", similar_triangles(&setup)),
        ("soft_blocker_search.svg", blocker_search(&scene, &setup)?),
    ])
}

const EMITTER: &str = "#e6a800";
const PLANK: &str = "#8e6bb0";
const FOOT: &str = "#2a9d3a";
const RAY: &str = "#d62728";

/// A number with `d` decimals.
fn f(x: f64, d: usize) -> String {
    format!("{:.*}", d, x + 0.0)
}

// ---------------------------------------------------------------- the scene

/// The default scene's spot light and its plank (the highest thin caster,
/// a blocker plane parallel to the floor), origin-relative.
struct Setup {
    /// The light's position and unit axis.
    light: DVec3,
    axis: DVec3,
    /// The emitter's radius R.
    radius: f64,
    /// The plank's top face corners, and the floor's height.
    plank_top: Vec<DVec3>,
    floor_y: f64,
}

impl Setup {
    fn from_scene(scene: &Scene) -> Result<Setup> {
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
        Ok(Setup {
            light: position - scene.origin(),
            axis: direction.normalize(),
            radius,
            plank_top,
            floor_y,
        })
    }
}

// ---------------------------------------------------------------- (a) similar triangles

/// Where the line through `a` and `b` (x, height) meets height `y`.
fn at_height(a: P, b: P, y: f64) -> f64 {
    a.0 + (b.0 - a.0) * (y - a.1) / (b.1 - a.1)
}

/// A two-headed dimension line from `a` to `b`.
fn dimension(s: &mut Svg, a: P, b: P) {
    let m = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    s.arrow(m, a, "#222");
    s.arrow(m, b, "#222");
}

/// The penumbra's similar triangles on the default scene's plank, in a
/// vertical section: (a) the emitter's two ends through the plank's edge
/// onto the floor, w_penumbra; (b) the emitter seen from a floor point p,
/// its footprint 2 r_b on the plank's plane.
fn similar_triangles(u: &Setup) -> String {
    let (w, title) = (
        800.0,
        "The penumbra's similar triangles on lesson 10's default scene",
    );
    let mut s = Svg::new(w, 0.0, title);
    // Heights measured down from the light: the emitter's plane at 0, the
    // plank's top at d_b, the floor at d_r (the scene's vertical
    // distances; the emitter drawn parallel to the floor).
    let d_r = u.light.y - u.floor_y;
    let d_b = u.light.y - u.plank_top[0].y;
    let r = u.radius;
    // Across, the scale is stretched: similar triangles survive it.
    let (ky, top) = (100.0, 92.0);
    let kx = 4.0 * ky;
    let ends = [(-r, 0.0), (r, 0.0)];
    let mut bottom: f64 = 0.0;
    for (panel, left) in [(0, 0.0), (1, w / 2.0)] {
        let cx = left + 235.0;
        let px = |p: P| (cx + p.0 * kx, top + p.1 * ky);
        let heading = [
            "(a) the penumbra on the receiver",
            "(b) the emitter seen from p: its footprint",
        ][panel];
        s.text((left + 20.0, 54.0), 14.0, "start", heading);
        // The emitter, the plank (its edge at x = 0, reaching left), the floor.
        s.line(px(ends[0]), px(ends[1]), &stroke(EMITTER, 6.0, ""));
        s.text(
            add(px((0.0, 0.0)), 0.0, -12.0),
            12.0,
            "middle",
            &format!("emitter: radius R = w_light = {} m", f(r, 2)),
        );
        let plank_left = -0.42;
        let (a, b) = (px((plank_left, d_b)), px((0.0, d_b + 0.04)));
        s.rect(a, (b.0 - a.0, b.1 - a.1), &fill(PLANK, "#5a3f75"));
        s.text(add(a, 0.0, -6.0), 12.0, "start", "blocker (the plank)");
        s.line(px((-0.52, d_r)), px((0.36, d_r)), INK);
        // Depths, on the left.
        let x0 = left + 14.0;
        dimension(&mut s, (x0, px((0.0, 0.0)).1), (x0, px((0.0, d_b)).1));
        dimension(
            &mut s,
            (x0 - 8.0, px((0.0, 0.0)).1),
            (x0 - 8.0, px((0.0, d_r)).1),
        );
        s.text(
            (x0 + 6.0, px((0.0, d_b / 2.0)).1),
            13.0,
            "start",
            &format!("d_b = {} m", f(d_b, 2)),
        );
        s.text(
            (x0 + 6.0, px((0.0, d_b + 0.35)).1),
            13.0,
            "start",
            &format!("d_r = {} m", f(d_r, 2)),
        );
        let floor = px((0.0, d_r)).1;
        if panel == 0 {
            // Each end of the emitter through the edge, down to the floor.
            let edge = (0.0, d_b);
            let hits: Vec<f64> = ends.iter().map(|&q| at_height(q, edge, d_r)).collect();
            for (&q, &x) in ends.iter().zip(&hits) {
                s.line(px(q), px((x, d_r)), &stroke(RAY, 1.5, ""));
            }
            let (lo, hi) = (hits[0].min(hits[1]), hits[0].max(hits[1]));
            // The floor: umbra, penumbra, lit.
            let band = |s: &mut Svg, x0: f64, x1: f64, c: &str| {
                let (a, b) = (px((x0, d_r)), px((x1, d_r)));
                s.rect(add(a, 0.0, 1.0), (b.0 - a.0, 7.0), &fill(c, c));
            };
            band(&mut s, -0.52, lo, "#555");
            band(&mut s, lo, hi, "#aaa");
            dimension(
                &mut s,
                (px((lo, 0.0)).0, floor + 22.0),
                (px((hi, 0.0)).0, floor + 22.0),
            );
            s.text(
                (px((0.0, 0.0)).0, floor + 44.0),
                13.0,
                "middle",
                &format!("2 w_penumbra = {} m", f(hi - lo, 3)),
            );
            s.text((px((-0.40, 0.0)).0, floor + 22.0), 12.0, "start", "umbra");
            s.text((px((0.33, 0.0)).0, floor + 22.0), 12.0, "end", "lit");
            bottom = bottom.max(floor + 44.0);
        } else {
            // From p, under the edge, to the emitter's two ends.
            let p = (0.0, d_r);
            let cross: Vec<f64> = ends.iter().map(|&q| at_height(p, q, d_b)).collect();
            for &q in &ends {
                s.line(px(p), px(q), &stroke(RAY, 1.5, ""));
            }
            let (lo, hi) = (cross[0].min(cross[1]), cross[0].max(cross[1]));
            let y = px((0.0, d_b)).1 - 9.0;
            s.line(
                (px((lo, 0.0)).0, y),
                (px((hi, 0.0)).0, y),
                &stroke(FOOT, 4.0, ""),
            );
            s.text(
                (px((hi, 0.0)).0 + 8.0, y + 4.0),
                13.0,
                "start",
                &format!("2 r_b = {} m", f(hi - lo, 3)),
            );
            s.circle(px(p), 4.0, &fill("#222", "#222"));
            s.text(add(px(p), 0.0, 22.0), 13.0, "middle", "p");
            bottom = bottom.max(floor + 22.0);
        }
    }
    let note = format!(
        "A vertical section through the plank's edge (scenes/lesson_10.toml): the light {} m \
         above the floor, its disk of radius R = {} m drawn parallel to the floor, the plank's \
         top {} m below it; the distances are measured vertically. Across, the scale is 4 \
         times the vertical one; lines stay lines and the ratios hold. The widths are where the \
         drawn rays cross the planes, not a formula: (a) the edges of the emitter through the \
         plank's edge bound the penumbra on the floor, 2 w_penumbra wide, with Fernando's \
         w_penumbra = (d_r − d_b) w_light / d_b and w_light = R; (b) the rays from p to the \
         emitter's edges cross the blocker's plane on the footprint of radius \
         r_b = R (d_r − d_b) / d_r, of which the plank covers half: p, under the edge, sees \
         half the emitter.",
        f(d_r, 2),
        f(r, 2),
        f(d_b, 2),
    );
    s.h = s.para((20.0, bottom + 30.0), 12.0, "start", w - 40.0, &note);
    s.finish()
}

// ---------------------------------------------------------------- (b) the blocker search

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

fn blocker_search(scene: &Scene, u: &Setup) -> Result<String> {
    let g = LightGeometry::new(scene, 0).context("lesson 10's light has no geometry")?;
    let m = light_view_proj(scene, 0).context("no light matrix")?;
    let size = Technique::Pcss(Technique::PCSS).map_size() as f64;
    let taps = Technique::PCSS.search_taps;
    let tris = scene.world_triangles();
    let owner: Vec<u32> = tris.iter().map(|(_, o)| *o).collect();
    let bvh = Bvh::build(tris.iter().map(|(t, _)| *t).collect());
    // The receiver: the floor under the middle of the plank's long top
    // edge away from the light, as the light sees it (no side face of the
    // plank shows beyond that edge).
    let c = &u.plank_top;
    let edge = |i: usize| (c[i] + c[(i + 1) % 4]) / 2.0;
    let mut long: Vec<usize> = (0..4).collect();
    long.sort_by(|&a, &b| {
        let len = |i: usize| c[i].distance(c[(i + 1) % 4]);
        len(b).total_cmp(&len(a))
    });
    let far = |i: usize| {
        let m = edge(i) - u.light;
        m.x * m.x + m.z * m.z
    };
    let i = long[..2]
        .iter()
        .copied()
        .max_by(|&a, &b| far(a).total_cmp(&far(b)))
        .unwrap();
    let mid = edge(i);
    let to = mid - u.light;
    let p = u.light + to * ((u.floor_y - u.light.y) / to.y);
    let (su, sv, d_r) = map_uv(m, p);
    // 1. The search disk: the shader's radius, and (dashed) the emitter's
    // disk carried through p onto the nearest caster's plane.
    let d_n = (g.nearest_caster as f64).min(d_r);
    let search = filter_radius(&g, d_r, d_n);
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
    s.line(
        add(sp, -7.0, 0.0),
        add(sp, 7.0, 0.0),
        &stroke("#000", 2.0, ""),
    );
    s.line(
        add(sp, 0.0, -7.0),
        add(sp, 0.0, 7.0),
        &stroke("#000", 2.0, ""),
    );
    // 2. The mean blocker distance, and the filter disk it gives.
    let mean = found.iter().sum::<f64>() / found.len().max(1) as f64;
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
        ("+", "the receiver p: a floor point under the plank's edge".into()),
        ("o", format!("the {taps} search taps (Vogel's spiral, angle 0), at their texels; filled red: a blocker found")),
        ("—", format!("the search disk: filter_radius(d_r, d_n), {} texels", f(search[0] * size, 1))),
        ("- -", "the emitter's disk seen from p, on the nearest caster's plane".into()),
        (":", format!("the filter disk from the blockers' mean: {} texels", f(filter[0] * size, 1))),
    ];
    for (i, (_, t)) in marks.iter().enumerate() {
        let c = (lx + 8.0, y - 4.0);
        match i {
            0 => {
                s.line(
                    add(c, -6.0, 0.0),
                    add(c, 6.0, 0.0),
                    &stroke("#000", 2.0, ""),
                );
                s.line(
                    add(c, 0.0, -6.0),
                    add(c, 0.0, 6.0),
                    &stroke("#000", 2.0, ""),
                );
            }
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
        format!("d_r = {} m (p, along the axis)", f(d_r, 2)),
        format!("d_n = {} m (nearest caster)", f(d_n, 2)),
        format!("blockers found: {} of {taps}", found.len()),
        format!("their mean d_b = {} m", f(mean, 2)),
    ];
    y = s.texts((lx, y + 10.0), 12.0, "start", &numbers);
    let note = "The map's texels around p's, coloured by what the light sees through each. \
        The search reads one texel per tap and keeps those in front of the receiver's plane; \
        the mean of their distances sizes the filter. The blue disk is the shader's search \
        radius; the dashed green ring, the emitter's disk carried through p onto the nearest \
        caster's plane and projected by the light's matrix: where they differ, the derivation's \
        disk square to the axis is not the map's.";
    let bottom = (top + grid).max(y) + 24.0;
    s.h = s.para((left, bottom), 12.0, "start", 800.0 - 2.0 * left, note);
    Ok(s.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagrams::tests::assert_texts_fit;

    #[test]
    fn texts_inside_the_canvas_and_apart() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for (name, svg) in render(root).unwrap() {
            assert_texts_fit(name, &svg);
        }
    }
}
