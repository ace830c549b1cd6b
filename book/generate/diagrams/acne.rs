//! Chapter 02's acne staircase (`acne_staircase.svg`): lesson 02's floor
//! edge-on, the map's stored depths, and where each bias leaves acne,
//! computed from lesson 02's own bias functions on its scene.

use std::path::Path;

use anyhow::{bail, Context, Result};
use common::glam::DVec3;
use common::scene::camera::light_view_proj;
use common::scene::{LightKind, Scene};
use workbook::lesson_02::bias::{depth_per_texel, SlopeScaledBias};

use super::svg::{add, fill, stroke, Svg, INK};

/// Lesson 02's shadow-map size (`MAP_SIZE` in `lessons/lesson_02/main.rs`).
const LESSON_02_MAP_SIZE: u32 = 1024;

/// Lesson 02's floor seen edge-on along its depth gradient: the map's
/// staircase of stored depths, the true surface, and where each bias leaves
/// the surface deeper than the comparison (acne).
pub(super) fn acne_staircase(root: &Path) -> Result<String> {
    let scene = Scene::load(&root.join("scenes/lesson_02.toml"))?;
    let dpt = depth_per_texel(&scene, 0, LESSON_02_MAP_SIZE);
    let cos = floor_cos(&scene)?;
    let tan = (1.0 - cos * cos).sqrt() / cos;
    let hw = hardware_shift(&scene, dpt, &SlopeScaledBias::RECOMMENDED)?;
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
    let head = format!(
        "The floor at θ = {theta:.1}° to the light, seen edge-on along its depth gradient: its depth \
         grows tan θ = {tan:.3} texel-steps per texel; one texel-step = {dpt:.3e} depth \
         (depth_per_texel, {LESSON_02_MAP_SIZE}² map)."
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

/// cos θ between the floor (object 0, a plane) and light 0 (directional).
fn floor_cos(scene: &Scene) -> Result<f64> {
    let LightKind::Directional { direction } = scene.lights[0].kind else {
        bail!("lesson_02.toml: light 0 is not directional");
    };
    if scene.objects[0].mesh_name != "plane" {
        bail!("lesson_02.toml: object 0 is not the floor plane");
    }
    let tris = scene.world_triangles();
    let (t, _) = tris.iter().find(|(_, o)| *o == 0).context("no floor")?;
    let n = (t[1] - t[0]).cross(t[2] - t[0]).as_dvec3().normalize();
    Ok(n.dot(direction.normalize()).abs())
}

/// The RECOMMENDED hardware bias on the floor, in texel-steps of depth:
/// slope_scale × max(|∂z/∂x|, |∂z/∂y|) (per map texel, as the rasteriser
/// takes it) plus `constant` units of 2^(e − 23), e the exponent of depth.
fn hardware_shift(scene: &Scene, dpt: f64, b: &SlopeScaledBias) -> Result<f64> {
    let m = light_view_proj(scene, 0)
        .context("no light matrix")?
        .as_dmat4();
    let texel = |p: DVec3| {
        let c = m.project_point3(p);
        let size = LESSON_02_MAP_SIZE as f64;
        DVec3::new((c.x + 1.0) * 0.5 * size, (1.0 - c.y) * 0.5 * size, c.z)
    };
    // The floor is y = 0 in the scene, so y = −origin.y origin-relative.
    let y = -scene.origin().y;
    let [o, a, c] = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, z)| texel(DVec3::new(x, y, z)));
    let (e1, e2) = (a - o, c - o);
    let det = e1.x * e2.y - e1.y * e2.x;
    let dzdx = (e1.z * e2.y - e2.z * e1.y) / det;
    let dzdy = (e2.z * e1.x - e1.z * e2.x) / det;
    let slope = dzdx.abs().max(dzdy.abs());
    let unit = 2f64.powi(o.z.log2().floor() as i32 - 23);
    let clamp = b.clamp_texels as f64 * dpt;
    Ok((b.slope_scale as f64 * slope + b.constant as f64 * unit).min(clamp) / dpt)
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
