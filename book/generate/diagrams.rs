//! The book's conceptual diagrams (chapter 05's are in `volume_diagrams.rs`), drawn as hand-built SVG from the
//! workbook's own code and scenes (issue 9): every number a picture shows
//! is computed here, from the lesson's functions, not typed in.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{bail, Context, Result};
use common::glam::{DMat4, DVec3};
use common::scene::camera::{camera_matrices, light_view_proj};
use common::scene::{LightKind, Scene};
use workbook::lesson_02::bias::{depth_per_texel, SlopeScaledBias};
use workbook::lesson_04::faces::{face_view_proj, CUBE_FACES};
use workbook::lesson_08::range_sphere::{sphere_depth_bounds, sphere_scissor, SPHERE_MARGIN};

/// Lesson 02's shadow-map size (`MAP_SIZE` in `lessons/lesson_02/main.rs`).
const LESSON_02_MAP_SIZE: u32 = 1024;
/// Lesson 08's default image size, the one its tables are measured at.
const SCREEN: (u32, u32) = (640, 360);

pub(crate) type P = (f64, f64);

/// Writes the diagrams into `dir` and returns the file names written.
pub fn write_all(root: &Path, dir: &Path) -> Result<Vec<String>> {
    write_svgs(dir, render(root)?)
}

/// Writes `(file name, SVG text)` pairs into `dir`; returns the names.
pub(crate) fn write_svgs(
    dir: &Path,
    svgs: impl IntoIterator<Item = (&'static str, String)>,
) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
    let mut names = Vec::new();
    for (name, svg) in svgs {
        let path = dir.join(name);
        std::fs::write(&path, svg).with_context(|| format!("{}: cannot write", path.display()))?;
        names.push(name.to_string());
    }
    Ok(names)
}

/// The diagrams, as (file name, SVG text).
fn render(root: &Path) -> Result<[(&'static str, String); 5]> {
    Ok([
        ("shadow_map_idea.svg", shadow_map_idea()?),
        ("acne_staircase.svg", acne_staircase(root)?),
        ("zpass_zfail_ray.svg", zpass_zfail_ray()?),
        ("cube_faces.svg", cube_faces()?),
        ("range_sphere.svg", range_sphere(root)?),
    ])
}

/// Estimated width of one line of text: 0.6 em a character, generous for
/// sans-serif, so that what fits by this estimate fits when rendered.
pub(crate) fn text_width(s: &str, size: f64) -> f64 {
    0.6 * size * s.chars().count() as f64
}

/// The estimated horizontal extent of a text drawn at `x` with `anchor`.
pub(crate) fn text_span(x: f64, size: f64, anchor: &str, s: &str) -> (f64, f64) {
    let w = text_width(s, size);
    match anchor {
        "start" => (x, x + w),
        "end" => (x - w, x),
        _ => (x - w / 2.0, x + w / 2.0),
    }
}

/// Greedy word wrap of `s` into lines no wider than `width` (estimated).
pub(crate) fn wrap(s: &str, size: f64, width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in s.split_whitespace() {
        match lines.last_mut() {
            Some(l) if text_width(l, size) + text_width(&format!(" {word}"), size) <= width => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Two attributes from a point: `x="…" y="…"`.
pub(crate) fn xy(x: &str, y: &str, p: P) -> String {
    format!(r#"{x}="{:.2}" {y}="{:.2}""#, p.0, p.1)
}

/// A hand-built SVG: white background, a title, then whatever is drawn.
pub(crate) struct Svg {
    pub(crate) w: f64,
    pub(crate) h: f64,
    body: String,
}

pub(crate) const INK: &str = r##"stroke="#222" stroke-width="1.5" fill="none""##;

/// A stroke style: colour, width, and a dash pattern ("" for none).
pub(crate) fn stroke(colour: &str, width: f64, dash: &str) -> String {
    format!(r#"stroke="{colour}" stroke-width="{width}" stroke-dasharray="{dash}" fill="none""#)
}

pub(crate) fn fill(colour: &str, edge: &str) -> String {
    format!(r#"fill="{colour}" stroke="{edge}" stroke-width="1.5""#)
}

pub(crate) fn add(p: P, dx: f64, dy: f64) -> P {
    (p.0 + dx, p.1 + dy)
}

impl Svg {
    pub(crate) fn new(w: f64, h: f64, title: &str) -> Svg {
        let mut s = Svg {
            w,
            h,
            body: String::new(),
        };
        s.text((w / 2.0, 24.0), 17.0, "middle", title);
        s
    }
    pub(crate) fn line(&mut self, a: P, b: P, style: &str) {
        let (a, b) = (xy("x1", "y1", a), xy("x2", "y2", b));
        let _ = writeln!(self.body, "<line {a} {b} {style}/>");
    }
    pub(crate) fn arrow(&mut self, a: P, b: P, colour: &str) {
        let style = stroke(colour, 1.5, "") + r#" marker-end="url(#arrow)""#;
        self.line(a, b, &style);
    }
    pub(crate) fn poly(&mut self, pts: &[P], closed: bool, style: &str) {
        let pts: Vec<String> = pts
            .iter()
            .map(|p| format!("{:.2},{:.2}", p.0, p.1))
            .collect();
        let tag = if closed { "polygon" } else { "polyline" };
        let _ = writeln!(self.body, r#"<{tag} points="{}" {style}/>"#, pts.join(" "));
    }
    pub(crate) fn rect(&mut self, at: P, size: P, style: &str) {
        let (at, size) = (xy("x", "y", at), xy("width", "height", size));
        let _ = writeln!(self.body, "<rect {at} {size} {style}/>");
    }
    pub(crate) fn circle(&mut self, c: P, r: f64, style: &str) {
        let c = xy("cx", "cy", c);
        let _ = writeln!(self.body, r#"<circle {c} r="{r:.2}" {style}/>"#);
    }
    pub(crate) fn text(&mut self, at: P, size: f64, anchor: &str, s: &str) {
        let s = s.replace('&', "&amp;").replace('<', "&lt;");
        let at = xy("x", "y", at);
        let attrs = format!(r#"{at} font-size="{size:.0}" text-anchor="{anchor}""#);
        let _ = writeln!(self.body, "<text {attrs}>{s}</text>");
    }
    /// Lines one under another; returns the baseline a next line would take.
    pub(crate) fn texts(&mut self, at: P, size: f64, anchor: &str, lines: &[String]) -> f64 {
        for (i, l) in lines.iter().enumerate() {
            self.text((at.0, at.1 + (size + 5.0) * i as f64), size, anchor, l);
        }
        at.1 + (size + 5.0) * lines.len() as f64
    }
    /// `s` wrapped to `width` and drawn as lines; returns the next baseline.
    pub(crate) fn para(&mut self, at: P, size: f64, anchor: &str, width: f64, s: &str) -> f64 {
        self.texts(at, size, anchor, &wrap(s, size, width))
    }
    /// The document; the white background is drawn here, so that `h` may
    /// be set once the content's height is known.
    pub(crate) fn finish(mut self) -> String {
        let body = std::mem::take(&mut self.body);
        self.rect((0.0, 0.0), (self.w, self.h), r##"fill="#fff""##);
        self.body += &body;
        format!(
            concat!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" font-family="sans-serif">"#,
                "\n<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" markerHeight=\"7\" orient=\"auto\">",
                "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"#222\"/></marker></defs>\n{body}</svg>\n"
            ),
            w = self.w,
            h = self.h,
            body = self.body
        )
    }
}

// ---------------------------------------------------------------- shadow map idea

/// The shadow-map family's idea in a side view: a point light, a box caster
/// over a floor, and two receiver points, each compared with the depth the
/// map stores along its ray (the nearest surface the light sees).
const MAP_LIGHT: P = (-1.0, 6.0);
const MAP_BOX: (P, P) = ((0.2, 2.4), (2.2, 3.2));

/// The distance from the light to the first surface along the ray
/// towards `dir`: the box's sides or the floor (y = 0).
fn first_hit(dir: P) -> f64 {
    let (lo, hi) = MAP_BOX;
    let mut best = -MAP_LIGHT.1 / dir.1;
    let sides = [
        ((lo.0, lo.1), (hi.0, lo.1)),
        ((lo.0, hi.1), (hi.0, hi.1)),
        ((lo.0, lo.1), (lo.0, hi.1)),
        ((hi.0, lo.1), (hi.0, hi.1)),
    ];
    for (a, b) in sides {
        let e = (b.0 - a.0, b.1 - a.1);
        let den = dir.0 * e.1 - dir.1 * e.0;
        if den.abs() < 1e-12 {
            continue;
        }
        let w = (a.0 - MAP_LIGHT.0, a.1 - MAP_LIGHT.1);
        let (t, u) = (
            (w.0 * e.1 - w.1 * e.0) / den,
            (w.0 * dir.1 - w.1 * dir.0) / den,
        );
        if t > 0.0 && (0.0..=1.0).contains(&u) {
            best = best.min(t);
        }
    }
    best
}

fn shadow_map_idea() -> Result<String> {
    let title = "The shadow-map idea: store the nearest depth per ray, then compare";
    let mut s = Svg::new(800.0, 0.0, title);
    let (lo, hi) = MAP_BOX;
    // The box's shadow on the floor, from its lower-left and upper-right corners.
    let on_floor = |p: P| MAP_LIGHT.0 + (p.0 - MAP_LIGHT.0) * MAP_LIGHT.1 / (MAP_LIGHT.1 - p.1);
    let (s0, s1) = (on_floor((lo.0, hi.1)), on_floor((hi.0, lo.1)));
    let receivers = [("A", ((s0 + s1) / 2.0, 0.0)), ("B", (s1 + 1.6, 0.0))];
    let (x0, y1, k) = (-2.0, 6.6, 62.0);
    let at = |p: P| (40.0 + (p.0 - x0) * k, 50.0 + (y1 - p.1) * k);
    s.line(
        at((x0, 0.0)),
        at((x0 + 11.5, 0.0)),
        &stroke("#8b5a2b", 3.0, ""),
    );
    s.text(
        add(at((x0, 0.0)), 4.0, 18.0),
        12.0,
        "start",
        "receiver (floor)",
    );
    let corner = at((lo.0, hi.1));
    s.rect(
        corner,
        ((hi.0 - lo.0) * k, (hi.1 - lo.1) * k),
        &fill("#c9553f", "#222"),
    );
    s.text(add(at((hi.0, hi.1)), 8.0, -4.0), 12.0, "start", "caster");
    let (a, b) = (at((s0, 0.0)), at((s1, 0.0)));
    s.line(a, b, &stroke("#555", 7.0, ""));
    s.text(add(at((s0, 0.0)), 0.0, 18.0), 12.0, "start", "shadow");
    let mut lines = Vec::new();
    for (name, p) in receivers {
        let d = (p.0 - MAP_LIGHT.0, p.1 - MAP_LIGHT.1);
        let depth = (d.0 * d.0 + d.1 * d.1).sqrt();
        let dir = (d.0 / depth, d.1 / depth);
        let stored = first_hit(dir);
        let hit = (MAP_LIGHT.0 + stored * dir.0, MAP_LIGHT.1 + stored * dir.1);
        let shadowed = depth > stored + 1e-9;
        let colour = ["#2ca02c", "#d62728"][shadowed as usize];
        s.line(at(MAP_LIGHT), at(hit), &stroke("#a80", 2.0, ""));
        if shadowed {
            s.line(at(hit), at(p), &stroke("#a80", 1.5, "5,4"));
        }
        s.circle(at(hit), 5.0, &fill("#1f5fbf", "none"));
        s.circle(at(p), 6.0, &fill(colour, "#222"));
        s.text(add(at(p), 0.0, 34.0), 14.0, "middle", name);
        let (sign, verdict) = if shadowed {
            (">", "in shadow")
        } else {
            ("≤", "lit")
        };
        lines.push(format!(
            "{name}: its depth {depth:.2} {sign} stored {stored:.2} → {verdict}"
        ));
    }
    s.circle(at(MAP_LIGHT), 10.0, &fill("#ffd400", "#a80"));
    s.text(add(at(MAP_LIGHT), 14.0, 5.0), 12.0, "start", "light");
    let legend = [
        (
            "#1f5fbf",
            "the depth the map stores: the first surface along the ray",
        ),
        ("#2ca02c", "receiver point as far as the stored depth: lit"),
        (
            "#d62728",
            "receiver point farther than the stored depth: shadowed",
        ),
    ];
    let mut y = at((0.0, 0.0)).1 + 64.0;
    for (c, t) in legend {
        s.rect((40.0, y - 10.0), (14.0, 10.0), &fill(c, "none"));
        s.text((62.0, y), 12.0, "start", t);
        y += 18.0;
    }
    y = s.texts((40.0, y + 8.0), 13.0, "start", &lines);
    let note = "Pass 1 renders the scene from the light and keeps, per texel (per ray), the         distance to the nearest surface. Pass 2 takes each point the eye sees, finds its texel         and compares: farther than what the light saw means something is in between.";
    s.h = s.para((40.0, y + 4.0), 12.0, "start", 720.0, note);
    Ok(s.finish())
}

// ---------------------------------------------------------------- acne

/// Lesson 02's floor seen edge-on along its depth gradient: the map's
/// staircase of stored depths, the true surface, and where each bias leaves
/// the surface deeper than the comparison (acne).
fn acne_staircase(root: &Path) -> Result<String> {
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

// ---------------------------------------------------------------- z-pass / z-fail

/// One face of a 2D shadow volume, with its outward normal.
pub(crate) struct Face {
    pub(crate) a: P,
    pub(crate) b: P,
    pub(crate) name: &'static str,
    pub(crate) out: P,
}

/// The 2D layout: a point light, an occluder segment, its volume's four
/// faces (front cap, two sides, back cap standing for infinity), the floor.
const LIGHT: P = (-2.0, 6.0);
const OCCLUDER: (P, P) = ((-1.0, 2.0), (1.0, 2.0));
const FAR_Y: f64 = -4.0;

fn volume() -> Vec<P> {
    let extrude = |p: P| {
        let t = (FAR_Y - p.1) / (p.1 - LIGHT.1);
        (p.0 + t * (p.0 - LIGHT.0), FAR_Y)
    };
    let (a, b) = OCCLUDER;
    vec![a, b, extrude(b), extrude(a)]
}

fn faces(poly: &[P]) -> Vec<Face> {
    let names = [
        "occluder = front cap",
        "side",
        "back cap (infinity)",
        "side",
    ];
    let n = poly.len() as f64;
    let c = poly
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let mut out = (b.1 - a.1, a.0 - b.0);
            if out.0 * (a.0 - c.0) + out.1 * (a.1 - c.1) < 0.0 {
                out = (-out.0, -out.1);
            }
            let name = names[i];
            Face { a, b, name, out }
        })
        .collect()
}

/// Where the ray `eye + t (target − eye)` crosses each face: (t, ±1 as seen
/// from the ray: +1 entering through a front face, −1 leaving by a back face).
pub(crate) fn crossings(eye: P, target: P, faces: &[Face]) -> Vec<(f64, i32, &'static str)> {
    let d = (target.0 - eye.0, target.1 - eye.1);
    let mut out = Vec::new();
    for f in faces {
        let e = (f.b.0 - f.a.0, f.b.1 - f.a.1);
        let den = d.0 * e.1 - d.1 * e.0;
        if den.abs() < 1e-12 {
            continue;
        }
        let w = (f.a.0 - eye.0, f.a.1 - eye.1);
        let (t, u) = ((w.0 * e.1 - w.1 * e.0) / den, (w.0 * d.1 - w.1 * d.0) / den);
        if t > 0.0 && (0.0..=1.0).contains(&u) {
            let dot = d.0 * f.out.0 + d.1 * f.out.1;
            let sign = if dot < 0.0 { 1 } else { -1 };
            out.push((t, sign, f.name));
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// "+1", "−1" with a true minus sign.
pub(crate) fn signed(x: i32) -> String {
    format!("{x:+}").replace('-', "−")
}

pub(crate) fn inside(poly: &[P], p: P) -> bool {
    let mut odd = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            odd = !odd;
        }
    }
    odd
}

fn zpass_zfail_ray() -> Result<String> {
    let title = "One view ray, two ways to count shadow-volume faces (lessons 05 and 06)";
    let mut s = Svg::new(800.0, 0.0, title);
    let poly = volume();
    let cases = [
        ("eye outside the volume", (6.0, 4.5), (1.5, 0.0)),
        ("eye inside the volume", (0.9, 1.2), (0.0, 0.0)),
    ];
    for (k, (name, eye, target)) in cases.into_iter().enumerate() {
        ray_panel(&mut s, 20.0 + 395.0 * k as f64, name, &poly, eye, target);
    }
    let notes = "Each crossing counts +1 where the ray enters the volume (a front face), −1 where it \
        leaves (a back face). z-pass adds those between the eye and the surface (green: the depth \
        test passes); z-fail adds those behind it (purple: the depth test fails), signs flipped, out \
        to the back cap at infinity. A non-zero count means shadow.";
    s.h = s.para((400.0, 500.0), 12.0, "middle", 760.0, notes);
    Ok(s.finish())
}

fn ray_panel(s: &mut Svg, left: f64, name: &str, poly: &[P], eye: P, target: P) {
    let (x0, y1, k) = (-3.5, 6.6, 33.0);
    let at = |p: P| (left + (p.0 - x0) * k, 45.0 + (y1 - p.1) * k);
    let fs = faces(poly);
    s.text((at((2.0, 0.0)).0, 50.0), 14.0, "middle", name);
    let outline: Vec<P> = poly.iter().map(|&p| at(p)).collect();
    s.poly(&outline, true, &fill("#ddd", "#777"));
    for f in &fs {
        let m = at(((f.a.0 + f.b.0) / 2.0, (f.a.1 + f.b.1) / 2.0));
        let side = f.out.0.signum() * (f.out.0.abs() > 1e-9) as u8 as f64;
        let anchor = ["end", "middle", "start"][(side + 1.0) as usize];
        let dy = if f.out.1 > 0.0 { -6.0 } else { 14.0 };
        s.text(add(m, 6.0 * side, dy), 12.0, anchor, f.name);
    }
    s.line(at((-3.5, 0.0)), at((7.5, 0.0)), &stroke("#8b5a2b", 3.0, ""));
    s.text(at((-3.3, 0.2)), 12.0, "start", "floor");
    for end in [OCCLUDER.0, OCCLUDER.1] {
        s.line(at(LIGHT), at(end), &stroke("#a80", 1.0, "3,3"));
    }
    s.line(at(OCCLUDER.0), at(OCCLUDER.1), &stroke("#000", 5.0, ""));
    s.circle(at(LIGHT), 9.0, &fill("#ffd400", "#a80"));
    s.text(add(at(LIGHT), 13.0, 4.0), 12.0, "start", "light");
    let d = (target.0 - eye.0, target.1 - eye.1);
    let t_end = (-4.5 - eye.1) / d.1;
    let end = (eye.0 + t_end * d.0, eye.1 + t_end * d.1);
    s.line(at(eye), at(target), &stroke("#1f5fbf", 2.0, ""));
    s.line(at(target), at(end), &stroke("#1f5fbf", 2.0, "6,4"));
    s.circle(at(eye), 6.0, &fill("#1f5fbf", "none"));
    s.text(add(at(eye), 9.0, -6.0), 12.0, "start", "eye");
    s.circle(at(target), 5.0, &fill("#fff", "#1f5fbf"));
    let (mut zpass, mut zfail) = (Vec::new(), Vec::new());
    for (t, sign, _) in crossings(eye, target, &fs) {
        let p = at((eye.0 + t * d.0, eye.1 + t * d.1));
        let in_front = t < 1.0;
        s.circle(
            p,
            6.0,
            &fill(if in_front { "#2ca02c" } else { "#9467bd" }, "none"),
        );
        s.text(add(p, 9.0, 4.0), 13.0, "start", &signed(sign));
        if in_front {
            zpass.push(sign)
        } else {
            zfail.push(-sign)
        }
    }
    let truth = inside(poly, target);
    let total = |v: &[i32]| -> String {
        let terms: Vec<String> = v.iter().map(|x| signed(*x)).collect();
        let sum: i32 = v.iter().sum();
        let verdict = ["lit", "shadow"][(sum != 0) as usize];
        let right = ["WRONG", "right"][((sum != 0) == truth) as usize];
        let terms = [terms.join(" "), "nothing".into()][terms.is_empty() as usize].clone();
        format!("{terms} = {sum} → {verdict} ({right})")
    };
    let where_ = ["outside the volume: lit", "inside the volume: in shadow"][truth as usize];
    let lines = [
        format!("z-pass (green): {}", total(&zpass)),
        format!("z-fail (purple): {}", total(&zfail)),
        format!("truth: the point is {where_}"),
    ];
    s.texts((left + 4.0, 440.0), 13.0, "start", &lines);
}

// ---------------------------------------------------------------- cube faces

/// Lesson 04's cross (`cross.rs`): +Y above; −X +Z +X −Z; −Y below, as
/// (forward axis, column, row).
const CROSS: [(DVec3, usize, usize); 6] = [
    (DVec3::Y, 1, 0),
    (DVec3::NEG_X, 0, 1),
    (DVec3::Z, 1, 1),
    (DVec3::X, 2, 1),
    (DVec3::NEG_Z, 3, 1),
    (DVec3::NEG_Y, 1, 2),
];

fn axis_name(v: DVec3) -> String {
    let (i, c) = (0..3)
        .map(|i| (i, v[i]))
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .unwrap_or((0, 0.0));
    format!("{}{}", if c < 0.0 { "−" } else { "+" }, ["X", "Y", "Z"][i])
}

fn vec_text(v: DVec3) -> String {
    let c = |x: f64| {
        if x < 0.0 {
            format!("−{}", -x)
        } else {
            format!("{}", x + 0.0)
        }
    };
    format!("({}, {}, {})", c(v.x), c(v.y), c(v.z))
}

/// A face's texel directions from its real view-projection: u = the axis
/// that moves right in the window, v = the one that moves down.
fn face_uv(face: usize) -> Result<(DVec3, DVec3)> {
    let m = face_view_proj(DVec3::ZERO, face, 0.1, 10.0).as_dmat4();
    let axes = [DVec3::X, DVec3::Y, DVec3::Z].map(|e| [e, -e]).concat();
    let ndc = |e: DVec3| m.project_point3(CUBE_FACES[face].0 + 0.5 * e);
    let u = axes
        .iter()
        .find(|&&e| ndc(e).x > 0.4)
        .context("no u axis")?;
    let v = axes
        .iter()
        .find(|&&e| ndc(e).y < -0.4)
        .context("no v axis")?;
    Ok((*u, *v))
}

fn cube_faces() -> Result<String> {
    let (cell, left, top) = (165.0, 30.0, 50.0);
    let title = "The six cube faces as lesson 04's cross writes them (CUBE_FACES)";
    let mut s = Svg::new(left * 2.0 + 4.0 * cell, 0.0, title);
    let mut placed = Vec::new();
    for (face, &(forward, up)) in CUBE_FACES.iter().enumerate() {
        let cross = CROSS.iter().find(|c| c.0 == forward);
        let &(_, col, row) = cross.context("face missing from the cross")?;
        let (u, v) = face_uv(face)?;
        placed.push((col, row, forward, u, v));
        let (x, y) = (left + col as f64 * cell, top + row as f64 * cell);
        s.rect((x, y), (cell, cell), &fill("#eef3fb", "#222"));
        let name = format!("face {face}: {}", axis_name(forward));
        s.text((x + cell / 2.0, y + 28.0), 17.0, "middle", &name);
        let lines = [
            format!("forward {}", vec_text(forward)),
            format!("up {}", vec_text(up)),
        ];
        s.texts((x + cell / 2.0, y + 52.0), 12.0, "middle", &lines);
        s.arrow((x + 40.0, y + 148.0), (x + 135.0, y + 148.0), "#1f5fbf");
        let u = format!("u → {}", axis_name(u));
        s.text((x + 88.0, y + 140.0), 13.0, "middle", &u);
        s.arrow((x + 16.0, y + 84.0), (x + 16.0, y + 150.0), "#d62728");
        let v = format!("v ↓ {}", axis_name(v));
        s.text((x + 24.0, y + 104.0), 13.0, "start", &v);
    }
    // Neighbouring cells must share their edge: the diagram checks itself.
    for &(c1, r1, f1, u1, v1) in &placed {
        for &(c2, r2, f2, u2, v2) in &placed {
            let right = c2 == c1 + 1 && r2 == r1 && (f1 + u1 != f2 - u2 || v1 != v2);
            let below = r2 == r1 + 1 && c2 == c1 && (f1 + v1 != f2 - v2 || u1 != u2);
            if right || below {
                let (a, b) = (axis_name(f1), axis_name(f2));
                bail!("cube cross: {a} and {b} do not share an edge");
            }
        }
    }
    let notes =
        "Index = the layer wgpu reads for that face. u, v: the texel column (right) and row \
        (down) directions of each face's view-projection (face_view_proj), checked to match at \
        every shared edge. The empty cells are black in the lesson's PNG.";
    let width = s.w - 2.0 * left;
    s.h = s.para((left, top + 3.0 * cell + 30.0), 13.0, "start", width, notes);
    Ok(s.finish())
}

// ---------------------------------------------------------------- range sphere

fn range_sphere(root: &Path) -> Result<String> {
    let scene = Scene::load(&root.join("scenes/lesson_08.toml"))?;
    let LightKind::Point { position, range } = scene.lights[0].kind else {
        bail!("lesson_08.toml: light 0 is not a point light");
    };
    let (w, h) = SCREEN;
    let cam = camera_matrices(&scene, w, h);
    let (view, proj, near) = (cam.view.as_dmat4(), cam.proj.as_dmat4(), scene.camera.near);
    let c = view.transform_point3(position - scene.origin());
    let bounds = sphere_depth_bounds(proj, near, c, range).context("sphere behind the camera")?;
    let sc = sphere_scissor(proj, near, c, range, w, h).context("sphere off screen")?;
    let title = "A point light's range sphere: depth bounds and scissor (lesson 08, light 0)";
    let mut s = Svg::new(800.0, 0.0, title);
    let (p, eye) = (vec_text(position), vec_text(scene.camera.eye));
    let head = format!("light 0 at {p}, range {range}; camera at {eye}, {w}×{h}, near {near}");
    s.text(
        (400.0, 46.0),
        13.0,
        "middle",
        &format!("{head}, far infinite"),
    );
    let bottom = range_top_view(&mut s, c, range, proj, near, bounds);
    // (b) The screen, with the sphere's outline and the scissor.
    let (sx, sy, ks) = (430.0, 95.0, 0.55);
    let px = |p: P| (sx + p.0 * ks, sy + p.1 * ks);
    s.text(
        (sx, 80.0),
        14.0,
        "start",
        &format!("(b) the {w}×{h} screen"),
    );
    s.rect(px((0.0, 0.0)), (w as f64 * ks, h as f64 * ks), INK);
    let outline: Vec<P> = sphere_outline(c, range, proj, w, h)
        .into_iter()
        .map(px)
        .collect();
    s.poly(&outline, true, &fill("#ffd40055", "#a80"));
    let size = (sc.width as f64 * ks, sc.height as f64 * ks);
    s.rect(
        px((sc.x as f64, sc.y as f64)),
        size,
        &stroke("#d62728", 2.0, "6,3"),
    );
    let pct = 100.0 * sc.area() as f64 / (w * h) as f64;
    let (zmin, zmax) = bounds;
    let (x, y, sw, sh) = (sc.x, sc.y, sc.width, sc.height);
    let notes = [
        format!(
            "(a) Depth bounds (sphere_depth_bounds): [{zmin:.6}, {zmax:.6}]; a pixel whose stored \
             depth lies outside them cannot be lit by this light, and its shadow-volume fragments \
             are dropped."
        ),
        "(b) Yellow: the sphere's outline on screen; red dashed: its scissor (sphere_scissor):"
            .into(),
        format!("x {x}, y {y}, {sw} × {sh} px = {pct:.1} % of the screen."),
    ];
    let mut y = bottom + 34.0;
    for n in notes {
        y = s.para((25.0, y), 13.0, "start", 750.0, &n);
    }
    s.h = y - 4.0;
    Ok(s.finish())
}

/// Panel (a): the camera, its view axis, the sphere, and the near, zmin
/// and zmax planes, seen from above (view distance right, view x down).
/// Returns the baseline of its lowest labels.
fn range_top_view(s: &mut Svg, c: DVec3, range: f64, proj: DMat4, near: f64, z: (f32, f32)) -> f64 {
    let r = range * (1.0 + SPHERE_MARGIN);
    let (d_c, x_c) = (-c.z, c.x);
    let far_d = d_c + r + 1.0;
    let x_hi = x_c.abs() + r + 0.5;
    let k = (370.0 / far_d).min(215.0 / (2.0 * x_hi));
    let (ox, oy) = (25.0, 100.0 + x_hi * k);
    let at = |d: f64, x: f64| (ox + d * k, oy + x * k);
    s.text(
        (25.0, 80.0),
        14.0,
        "start",
        "(a) seen along the camera's up axis",
    );
    s.rect(
        at(0.0, -x_hi),
        (far_d * k, 2.0 * x_hi * k),
        &stroke("#bbb", 1.0, ""),
    );
    let tan_h = 1.0 / proj.x_axis.x;
    for sign in [-1.0, 1.0] {
        let d = far_d.min(x_hi / tan_h);
        s.line(
            at(0.0, 0.0),
            at(d, sign * tan_h * d),
            &stroke("#999", 1.0, ""),
        );
    }
    s.arrow(at(0.0, 0.0), at(2.5, 0.0), "#222");
    s.circle(at(0.0, 0.0), 5.0, &fill("#1f5fbf", "none"));
    s.text(add(at(0.0, 0.0), 6.0, 16.0), 12.0, "start", "camera");
    s.circle(at(d_c, x_c), range * k, &fill("#ffd40055", "#a80"));
    s.circle(at(d_c, x_c), 3.0, &fill("#a80", "none"));
    s.text(add(at(d_c, x_c), 0.0, -6.0), 12.0, "middle", "light");
    let (y_lo, y_hi) = (at(0.0, -x_hi).1, at(0.0, x_hi).1);
    let (d_near, d_far) = ((d_c - r).max(near), d_c + r);
    let (zmin, zmax) = (z.0, z.1);
    let planes = [
        (near, format!("near {near}"), "#777", "start", y_lo - 4.0),
        (
            d_near,
            format!("zmin {zmin:.6} (d {d_near:.3})"),
            "#2ca02c",
            "end",
            y_hi + 14.0,
        ),
        (
            d_far,
            format!("zmax {zmax:.6} (d {d_far:.3})"),
            "#d62728",
            "start",
            y_hi + 14.0,
        ),
    ];
    for (d, label, colour, anchor, y) in planes {
        let x = at(d, 0.0).0;
        s.line((x, y_lo), (x, y_hi), &stroke(colour, 2.0, ""));
        // An end-anchored label that would leave the canvas starts at its line instead.
        let anchor = if text_span(x, 12.0, anchor, &label).0 < 0.0 {
            "start"
        } else {
            anchor
        };
        s.text((x, y), 12.0, anchor, &label);
    }
    y_hi + 14.0
}

/// The sphere's silhouette on screen, in pixels: its tangent circle seen
/// from the eye (centre `c` in view space), projected.
fn sphere_outline(c: DVec3, r: f64, proj: DMat4, w: u32, h: u32) -> Vec<P> {
    let l2 = c.length_squared();
    let centre = c * (1.0 - r * r / l2);
    let radius = r * (l2 - r * r).sqrt() / l2.sqrt();
    let axis = c.normalize();
    let e1 = axis.cross(DVec3::Y).normalize();
    let e2 = axis.cross(e1);
    (0..96)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 96.0;
            let p = proj.project_point3(centre + radius * (a.cos() * e1 + a.sin() * e2));
            ((p.x + 1.0) * 0.5 * w as f64, (1.0 - p.y) * 0.5 * h as f64)
        })
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The value of attribute `name` in a tag's attribute text.
    fn attr(tag: &str, name: &str) -> f64 {
        let key = format!(" {name}=\"");
        let at = tag.find(&key).map(|i| i + key.len()).expect(name);
        tag[at..at + tag[at..].find('"').unwrap()]
            .parse()
            .expect(name)
    }

    /// Every text of `svg` lies inside its canvas by the same width
    /// estimate the layout uses, and no two texts' boxes overlap.
    pub(crate) fn assert_texts_fit(name: &str, svg: &str) {
        let svg_tag = &svg[..svg.find('>').unwrap()];
        let (w, h) = (attr(svg_tag, "width"), attr(svg_tag, "height"));
        let mut boxes: Vec<(f64, f64, f64, f64, String)> = Vec::new();
        for part in svg.split("<text").skip(1) {
            let (tag, rest) = part.split_once('>').unwrap();
            let text = rest.split_once("</text>").unwrap().0;
            let text = text.replace("&lt;", "<").replace("&amp;", "&");
            let anchor = tag
                .split("text-anchor=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next();
            let (x, y, size) = (attr(tag, "x"), attr(tag, "y"), attr(tag, "font-size"));
            let (x0, x1) = text_span(x, size, anchor.unwrap(), &text);
            let (y0, y1) = (y - 0.8 * size, y + 0.25 * size);
            assert!(
                x0 >= 0.0 && x1 <= w,
                "{name}: {text:?} spans x {x0:.0}..{x1:.0} of {w}"
            );
            assert!(
                y0 >= 0.0 && y1 <= h,
                "{name}: {text:?} spans y {y0:.0}..{y1:.0} of {h}"
            );
            for (a0, a1, b0, b1, other) in &boxes {
                let apart = x1 <= *a0 || *a1 <= x0 || y1 <= *b0 || *b1 <= y0;
                assert!(apart, "{name}: {text:?} overlaps {other:?}");
            }
            boxes.push((x0, x1, y0, y1, text));
        }
    }

    #[test]
    fn texts_inside_the_canvas_and_apart() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for (name, svg) in render(root).unwrap() {
            assert_texts_fit(name, &svg);
        }
    }
}
