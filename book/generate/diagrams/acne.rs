//! Chapter 02's acne staircase (`acne_staircase.svg`): lesson 02's floor
//! edge-on, the map's stored depths, and where each bias leaves acne,
//! computed from lesson 02's own bias functions on its scene.

use std::path::Path;

use anyhow::{bail, Context, Result};
use common::glam::{DMat4, DVec3};
use common::scene::camera::light_view_proj;
use common::scene::{LightKind, Scene};
use workbook::lesson_02::bias::{depth_per_texel, SlopeScaledBias};

use super::svg::{add, fill, stroke, Svg, INK};

/// Lesson 02's shadow-map size, read from its source (`MAP_SIZE` in
/// `lessons/lesson_02/main.rs`, private to the lesson's binary).
fn lesson_02_map_size(root: &Path) -> Result<u32> {
    let path = root.join("lessons/lesson_02/main.rs");
    let src = std::fs::read_to_string(&path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    let line = src
        .lines()
        .find_map(|l| l.strip_prefix("const MAP_SIZE: u32 = "));
    let size = line.and_then(|l| l.strip_suffix(';')?.parse().ok());
    size.with_context(|| format!("{}: no `const MAP_SIZE: u32 = …;`", path.display()))
}

/// The floor (object 0 of lesson 02's scene, a plane) and its light
/// (light 0, directional), origin-relative: a point of the floor, its unit
/// normal on the light's side, and the unit vector towards the light.
struct Floor {
    point: DVec3,
    n: DVec3,
    l: DVec3,
}

fn floor(scene: &Scene) -> Result<Floor> {
    let LightKind::Directional { direction } = scene.lights[0].kind else {
        bail!("lesson_02.toml: light 0 is not directional");
    };
    if scene.objects[0].mesh_name != "plane" {
        bail!("lesson_02.toml: object 0 is not the floor plane");
    }
    let tris = scene.world_triangles();
    let (t, _) = tris.iter().find(|(_, o)| *o == 0).context("no floor")?;
    let t = t.map(|v| v.as_dvec3());
    let l = -direction.normalize();
    let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
    let n = if n.dot(l) < 0.0 { -n } else { n };
    Ok(Floor {
        point: (t[0] + t[1] + t[2]) / 3.0,
        n,
        l,
    })
}

/// The unit the receiver biases are given in, on the floor: one texel as
/// lesson 01's `shadow_texel_size` measures it for a receiver (the texel's
/// side along the direction the receiver's depth changes fastest across
/// the map), and that length along the light's ray in depth units, the
/// texel-step. Returns (texel in metres, texel-step in depth).
fn texel_step(m: DMat4, size: u32, f: &Floor) -> (f64, f64) {
    let row = |i: usize| DVec3::new(m.x_axis[i], m.y_axis[i], m.z_axis[i]);
    let w = (m * f.point.extend(1.0)).w;
    let extent = |i: usize| 2.0 * w / (size as f64 * row(i).length());
    let g = f.n - f.n.dot(f.l) * f.l;
    let texel = if g.length() < 1e-4 {
        extent(0).max(extent(1))
    } else {
        let g = g.normalize();
        let along = |i: usize| extent(i) * g.dot(row(i).normalize()).abs();
        along(0) + along(1)
    };
    let z = |p: DVec3| m.project_point3(p).z;
    (texel, (z(f.point + f.l * texel) - z(f.point)).abs())
}

/// Lesson 02's floor seen edge-on along its depth gradient: the map's
/// staircase of stored depths, the true surface, and where each bias leaves
/// the surface deeper than the comparison (acne).
pub(super) fn acne_staircase(root: &Path) -> Result<String> {
    let scene = Scene::load(&root.join("scenes/lesson_02.toml"))?;
    let size = lesson_02_map_size(root)?;
    let m = light_view_proj(&scene, 0)
        .context("no light matrix")?
        .as_dmat4();
    let f = floor(&scene)?;
    let cos = f.n.dot(f.l);
    let tan = (1.0 - cos * cos).sqrt() / cos;
    let (texel, step) = texel_step(m, size, &f);
    let clamp = depth_per_texel(&scene, 0, size);
    let hw = hardware_shift(m, size, &f, clamp, &SlopeScaledBias::RECOMMENDED) / step;
    let receiver =
        |b: f64| format!("bias_{b}tx: the receiver moves {b} texel-steps towards the light");
    let panels = [
        ("no bias (lesson 01)".to_string(), 0.0),
        (receiver(0.25), 0.25),
        (receiver(0.5), 0.5),
        (
            format!("slope_hw (RECOMMENDED): stored depths {hw:.3} texel-steps deeper"),
            hw,
        ),
    ];
    let (w, theta) = (780.0, cos.acos().to_degrees());
    let mm = texel * 1000.0;
    let head = format!(
        "The floor at θ = {theta:.1}° to the light, seen edge-on along its depth gradient: its depth \
         grows tan θ = {tan:.3} texel-steps per texel. One texel-step = {step:.3e} of depth: a move \
         along the light's ray by one texel's side along that gradient ({mm:.2} mm, {size}² map)."
    );
    let legend = [
        (
            "#1f5fbf",
            "stored depth (each texel: the depth at its centre)",
        ),
        ("#222", "true surface"),
        ("#e08a00", "comparison depth: stored + bias (dashed)"),
        ("#d62728", "acne: the sample shadows itself"),
        ("#2ca02c", "sample lit"),
    ];
    let title = "Shadow acne: the staircase of stored depths (lesson 02, default scene)";
    let mut s = Svg::new(w, 0.0, title);
    let mut top = s.para((w / 2.0, 46.0), 12.0, "middle", w - 40.0, &head) - 4.0;
    for (name, b) in &panels {
        top = acne_panel(&mut s, top, name, tan, *b);
    }
    for (i, (c, t)) in legend.iter().enumerate() {
        let (x, y) = (
            80.0 + 400.0 * (i % 2) as f64,
            top + 14.0 + 18.0 * (i / 2) as f64,
        );
        s.rect((x, y - 10.0), (14.0, 10.0), &fill(c, "none"));
        s.text((x + 20.0, y), 12.0, "start", t);
    }
    s.h = top + 14.0 + 18.0 * legend.len().div_ceil(2) as f64;
    Ok(s.finish())
}

/// The RECOMMENDED hardware bias on the floor, in depth units:
/// slope_scale × max(|∂z/∂x|, |∂z/∂y|) (per map texel, as the rasteriser
/// takes it) plus `constant` units of 2^(e − 23), e the exponent of depth,
/// at most `clamp`.
fn hardware_shift(m: DMat4, size: u32, f: &Floor, clamp: f64, b: &SlopeScaledBias) -> f64 {
    let texel = |p: DVec3| {
        let c = m.project_point3(p);
        let size = size as f64;
        DVec3::new((c.x + 1.0) * 0.5 * size, (1.0 - c.y) * 0.5 * size, c.z)
    };
    // Two directions in the floor's plane.
    let a = f.n.any_orthonormal_vector();
    let [o, a, c] = [f.point, f.point + a, f.point + f.n.cross(a)].map(texel);
    let (e1, e2) = (a - o, c - o);
    let det = e1.x * e2.y - e1.y * e2.x;
    let dzdx = (e1.z * e2.y - e2.z * e1.y) / det;
    let dzdy = (e2.z * e1.x - e1.z * e2.x) / det;
    let slope = dzdx.abs().max(dzdy.abs());
    let unit = 2f64.powi(o.z.log2().floor() as i32 - 23);
    (b.slope_scale as f64 * slope + b.constant as f64 * unit).min(b.clamp_texels as f64 * clamp)
}

/// One bias's panel below `top`: its name, how much of the surface has
/// acne, and the staircase. Returns the top of whatever comes next.
fn acne_panel(s: &mut Svg, top: f64, name: &str, tan: f64, bias: f64) -> f64 {
    const TEXELS: usize = 6;
    const SAMPLES: usize = 8;
    let (left, px, end) = (80.0, 110.0, TEXELS as f64 - 0.5);
    let (d0, d1) = (-0.5 * tan - 0.3, end * tan + bias + 0.3);
    let ky = 130.0 / (d1 - d0);
    let at = |x: f64, d: f64| (left + (x + 0.5) * px, top + 36.0 + (d - d0) * ky);
    s.text((left, top + 12.0), 13.0, "start", name);
    for i in 0..=TEXELS {
        let x = i as f64 - 0.5;
        s.line(at(x, d0), at(x, d1), &stroke("#ccc", 1.0, ""));
    }
    s.line(at(-0.5, d1), at(end, d1), INK);
    s.line(at(-0.5, d0), at(-0.5, d1), INK);
    s.text(add(at(-0.5, d0), -8.0, 10.0), 12.0, "end", "depth ↓");
    let mut red = 0;
    for i in 0..TEXELS {
        let (x, stored) = (i as f64, tan * i as f64);
        let step = |d: f64| (at(x - 0.5, d), at(x + 0.5, d));
        let (a, b) = step(stored);
        s.line(a, b, &stroke("#1f5fbf", 3.0, ""));
        if bias > 0.0 {
            let (a, b) = step(stored + bias);
            s.line(a, b, &stroke("#e08a00", 2.0, "6,4"));
        }
        for k in 0..SAMPLES {
            let xs = x - 0.5 + (k as f64 + 0.5) / SAMPLES as f64;
            let acne = tan * xs > stored + bias;
            red += acne as usize;
            let colour = if acne { "#d62728" } else { "#2ca02c" };
            s.circle(at(xs, tan * xs), 3.5, &fill(colour, "none"));
        }
        s.text(
            add(at(x, d1), 0.0, 14.0),
            12.0,
            "middle",
            &format!("texel {i}"),
        );
    }
    s.line(at(-0.5, -0.5 * tan), at(end, end * tan), INK);
    let pct = 100.0 * (0.5 - bias / tan).clamp(0.0, 1.0);
    let n = TEXELS * SAMPLES;
    let count = format!("acne on {pct:.1} % of the surface ({red} of {n} samples shown)");
    s.text((left, top + 28.0), 12.0, "start", &count);
    at(0.0, d1).1 + 30.0
}

#[cfg(test)]
mod tests {
    use super::super::svg::tests::{after, texts};
    use super::*;

    /// Lesson 02's shadow map of its floor, emulated from the light's
    /// matrix alone: map coordinates (u, v in texels, depth) of a floor
    /// point, and the floor point under a map position (the plane seen by
    /// an orthographic light is an affine image of the map).
    struct MapOfFloor {
        m: DMat4,
        size: f64,
        o: DVec3,
        ex: DVec3,
        ez: DVec3,
        inv: [[f64; 2]; 2],
    }

    impl MapOfFloor {
        fn new(root: &Path) -> (MapOfFloor, Scene) {
            let scene = Scene::load(&root.join("scenes/lesson_02.toml")).unwrap();
            let m = light_view_proj(&scene, 0).unwrap().as_dmat4();
            let size = lesson_02_map_size(root).unwrap() as f64;
            // The floor is the plane y = 0 of the scene.
            let o = DVec3::new(0.0, -scene.origin().y, 0.0);
            let (ex, ez) = (DVec3::X, DVec3::Z);
            let mut map = MapOfFloor {
                m,
                size,
                o,
                ex,
                ez,
                inv: [[0.0; 2]; 2],
            };
            let (p0, px, pz) = (map.uvz(o), map.uvz(o + ex), map.uvz(o + ez));
            let (a, b, c, d) = (px.x - p0.x, pz.x - p0.x, px.y - p0.y, pz.y - p0.y);
            let det = a * d - b * c;
            map.inv = [[d / det, -b / det], [-c / det, a / det]];
            (map, scene)
        }
        fn uvz(&self, p: DVec3) -> DVec3 {
            let c = self.m.project_point3(p);
            DVec3::new(
                (c.x + 1.0) * 0.5 * self.size,
                (1.0 - c.y) * 0.5 * self.size,
                c.z,
            )
        }
        /// The floor point the map shows at (u, v).
        fn floor_at(&self, u: f64, v: f64) -> DVec3 {
            let p0 = self.uvz(self.o);
            let (du, dv) = (u - p0.x, v - p0.y);
            let (s, t) = (
                self.inv[0][0] * du + self.inv[0][1] * dv,
                self.inv[1][0] * du + self.inv[1][1] * dv,
            );
            self.o + s * self.ex + t * self.ez
        }
        /// What texel (i, j) stores: the floor's depth at its centre.
        fn stored(&self, i: f64, j: f64) -> f64 {
            self.uvz(self.floor_at(i + 0.5, j + 0.5)).z
        }
    }

    /// The staircase's steps and stripes against an emulated map of the
    /// floor. Steps: the depth stored by neighbouring texels along the
    /// floor's gradient differs by tan θ texel-steps, as printed, the
    /// texel-step being the depth along the light's ray of the floor's
    /// stretch between two texel centres seen across the light. Stripes:
    /// on 24 × 24 texels of the floor, at 391² receivers, the share
    /// that a receiver bias of b texel-steps (the point moved b texels
    /// towards the light, as bias.wgsl moves it) or the hardware's bias
    /// (the stored depth raised by slope_scale × the largest depth change
    /// per texel) leaves in shadow of its own texel is the panel's
    /// percentage.
    #[test]
    fn steps_and_stripes_match_an_emulated_map_of_the_floor() {
        let root = &crate::repo_root();
        let svg = acne_staircase(root).unwrap();
        let words: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
        let all = words.join(" ");
        let (tan, step) = (after(&all, "tan θ = "), after(&all, "One texel-step = "));
        let (map, scene) = MapOfFloor::new(root);
        let l = match scene.lights[0].kind {
            LightKind::Directional { direction } => -direction.normalize(),
            _ => unreachable!(),
        };
        // The stored depths' gradient across the map, by finite differences.
        let (i0, j0) = (map.uvz(map.o).x.floor(), map.uvz(map.o).y.floor());
        let z0 = map.stored(i0, j0);
        let (gu, gv) = (map.stored(i0 + 1.0, j0) - z0, map.stored(i0, j0 + 1.0) - z0);
        let g = gu.hypot(gv);
        // The gradient runs along one texel axis here, so the staircase
        // seen edge-on is the whole story.
        assert!(
            gu.abs().min(gv.abs()) < 1e-6 * g,
            "gradient ({gu:e}, {gv:e})"
        );
        // The two centres' floor points, seen across the light: one texel.
        let (a, b) = (
            map.floor_at(i0 + 0.5, j0 + 0.5),
            map.floor_at(i0 + 0.5 + gu / g, j0 + 0.5 + gv / g),
        );
        let across = (b - a) - (b - a).dot(l) * l;
        let texel = across.length();
        let depth_per_metre = (map.uvz(a + l).z - map.uvz(a).z).abs();
        let true_step = texel * depth_per_metre;
        let rel = |x: f64, y: f64| (x - y).abs() / y;
        assert!(
            rel(step, true_step) < 2e-3,
            "texel-step: printed {step:e}, emulated {true_step:e}"
        );
        assert!(
            rel(tan, g / true_step) < 2e-3,
            "printed tan θ {tan}: neighbouring texels store {:.4} texel-steps apart",
            g / true_step
        );
        // The stripes.
        let pcts: Vec<f64> = (words.iter())
            .filter(|w| w.starts_with("acne on "))
            .map(|w| after(w, "acne on "))
            .collect();
        let titles: Vec<&String> = (words.iter())
            .filter(|w| {
                w.starts_with("no bias") || w.starts_with("bias_") || w.starts_with("slope_hw")
            })
            .collect();
        assert_eq!((pcts.len(), titles.len()), (4, 4), "{titles:?}");
        let hw = SlopeScaledBias::RECOMMENDED;
        let unit = 2f64.powi(z0.log2().floor() as i32 - 23);
        let raise = hw.slope_scale as f64 * gu.abs().max(gv.abs()) + hw.constant as f64 * unit;
        for (title, pct) in titles.iter().zip(&pcts) {
            let (receiver_moves, stored_raised) = if title.starts_with("slope_hw") {
                let printed = after(title, "stored depths ");
                assert!(
                    rel(printed, raise / true_step) < 2e-3,
                    "{title}: the hardware raises the floor's depths {:.4} texel-steps",
                    raise / true_step
                );
                (0.0, raise)
            } else if title.starts_with("bias_") {
                (after(title, "bias_"), 0.0)
            } else {
                (0.0, 0.0)
            };
            // A grid whose spacing is no fraction of a texel: its points
            // fall at every offset within their texels.
            let (h, side) = (24.0 / 391.3, 391);
            let (n, mut acne) = (side * side, 0);
            for k in 0..n {
                let u = i0 - 12.0 + ((k % side) as f64 + 0.5) * h;
                let v = j0 - 12.0 + ((k / side) as f64 + 0.5) * h;
                let p = map.floor_at(u, v) + l * (receiver_moves * texel);
                let c = map.uvz(p);
                acne += (c.z > map.stored(c.x.floor(), c.y.floor()) + stored_raised) as usize;
            }
            let share = 100.0 * acne as f64 / n as f64;
            assert!(
                (share - pct).abs() < 0.5,
                "{title}: {pct} % drawn, {share:.2} % of the emulated floor in acne"
            );
        }
    }

    /// The map size the diagram reads is the lesson's.
    #[test]
    fn map_size_is_lesson_02s() {
        let root = &crate::repo_root();
        assert_eq!(lesson_02_map_size(root).unwrap(), 1024);
    }
}
