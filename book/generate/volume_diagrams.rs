//! Chapter 05's pictures of shadow volumes, drawn from lesson 05's own
//! code (`adjacency`, `silhouette`, `extrusion`) on the cube of
//! `scenes/lesson_05.toml`: the silhouette, the volume's sides and caps,
//! the z-pass count along two view rays, the stencil counts of a frame and
//! the extrusion to w = 0. Every number a picture shows is computed here.

use std::path::Path;

use anyhow::{bail, Context, Result};
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec3, DVec4, Vec3};
use common::reference::bvh::Bvh;
use common::reference::primary_ray;
use common::scene::camera::{camera_matrices, perspective};
use common::scene::mesh::{builtin, face_normal};
use common::scene::{Far, LightKind, Scene};
use workbook::lesson_05::adjacency::Adjacency;
use workbook::lesson_05::extrusion::cpu_volume;
use workbook::lesson_05::silhouette::{
    casts_two_sided, face_facing, light_facing_triangles_for, silhouette_edges_for, LightDir,
};

use crate::diagrams::{add, crossings, fill, inside, signed, stroke, Face, Svg, INK, P};
use workbook::lesson_05::stencil::{lit_stencil, segment_crosses, Counting};
use workbook::lesson_05::volumes::CasterDraw;

/// Writes chapter 05's diagrams into `dir` and returns the names written.
pub fn write_all(root: &Path, dir: &Path) -> Result<Vec<String>> {
    crate::diagrams::write_svgs(dir, render(root)?)
}

fn render(root: &Path) -> Result<[(&'static str, String); 6]> {
    let scene = Scene::load(&root.join("scenes/lesson_05.toml"))?;
    let caster = Caster::from_scene(&scene)?;
    Ok([
        ("volume_silhouette.svg", silhouette(&caster)),
        ("volume_sides_caps.svg", sides_and_caps(&caster)),
        ("volume_zpass_count.svg", zpass_count()?),
        ("volume_stencil_counts.svg", stencil_counts(&scene)?),
        ("volume_w_zero.svg", w_zero(&scene, &caster)?),
        ("volume_passes.svg", passes()),
    ])
}

const BLUE: &str = "#1f5fbf";
const LIT: &str = "#ffd66e";
const AWAY: &str = "#a9b1bc";
const SIL: &str = "#d62728";

/// Points `pts` fitted, aspect kept, into the rectangle at `at` of `size`.
struct Fit {
    k: f64,
    from: P,
    to: P,
}

impl Fit {
    fn new(pts: &[P], at: P, size: P) -> Fit {
        let lo = pts
            .iter()
            .fold((f64::MAX, f64::MAX), |a, p| (a.0.min(p.0), a.1.min(p.1)));
        let hi = pts
            .iter()
            .fold((f64::MIN, f64::MIN), |a, p| (a.0.max(p.0), a.1.max(p.1)));
        let k = (size.0 / (hi.0 - lo.0)).min(size.1 / (hi.1 - lo.1));
        let pad = (
            (size.0 - k * (hi.0 - lo.0)) / 2.0,
            (size.1 - k * (hi.1 - lo.1)) / 2.0,
        );
        Fit {
            k,
            from: lo,
            to: add(at, pad.0, pad.1),
        }
    }
    fn at(&self, p: P) -> P {
        (
            self.to.0 + (p.0 - self.from.0) * self.k,
            self.to.1 + (p.1 - self.from.1) * self.k,
        )
    }
}

/// The point of the segment `from → to` farthest along it that is still
/// inside the rectangle `lo`..`hi` (`from` is inside).
fn clip(from: P, to: P, lo: P, hi: P) -> P {
    let mut t: f64 = 1.0;
    for (f, d, l, h) in [
        (from.0, to.0 - from.0, lo.0, hi.0),
        (from.1, to.1 - from.1, lo.1, hi.1),
    ] {
        if d > 1e-12 {
            t = t.min((h - f) / d);
        } else if d < -1e-12 {
            t = t.min((l - f) / d);
        }
    }
    (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1))
}

/// The light's marker, or where the way to it leaves the panel.
fn light_marker(s: &mut Svg, centre: P, light: P, lo: P, hi: P) {
    let end = clip(centre, light, lo, hi);
    if end == light {
        s.circle(light, 10.0, &fill("#ffd400", "#a80"));
        s.text(add(light, -14.0, 5.0), 13.0, "end", "point light");
    } else {
        s.arrow(centre, end, "#a80");
        s.text(add(end, -10.0, 4.0), 13.0, "end", "to the point light");
    }
}

/// A 3D point through a view-projection, to pixels of a `w`×`h` image
/// (y down). `None` behind the eye.
fn pixel(m: DMat4, w: f64, h: f64, p: DVec4) -> Option<P> {
    let c = m * p;
    (c.w > 1e-9).then(|| ((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h))
}

fn v3(v: DVec3) -> String {
    let c = |x: f64| signed_f(x, 2);
    format!("({}, {}, {})", c(v.x), c(v.y), c(v.z))
}

/// A number with `d` decimals and a true minus sign.
fn signed_f(x: f64, d: usize) -> String {
    format!("{:.*}", d, x + 0.0).replace('-', "−")
}

// ---------------------------------------------------------------- the caster

/// Lesson 05's cube caster in world space, lit by the scene's point light.
struct Caster {
    adj: Adjacency,
    light: DVec3,
    facing: Vec<bool>,
    centre: DVec3,
    /// A fixed camera that sees the lit faces and the volume behind them.
    view: DMat4,
    proj: DMat4,
}

impl Caster {
    fn from_scene(scene: &Scene) -> Result<Caster> {
        let cube = scene.objects.iter().find(|o| o.mesh_name == "cube");
        let cube = cube.context("lesson_05.toml: no cube caster")?;
        let light = scene.lights.iter().find_map(|l| match l.kind {
            LightKind::Point { position, .. } => Some(position),
            _ => None,
        });
        let light = light.context("lesson_05.toml: no point light")?;
        let world: Vec<Vec3> = cube
            .mesh
            .positions
            .iter()
            .map(|p| cube.model.transform_point3(p.as_dvec3()).as_vec3())
            .collect();
        let adj = Adjacency::from_triangles(&world, &cube.mesh.indices);
        let facing = face_facing(&adj, LightDir::Point(light.as_vec3()));
        let centre = cube.model.transform_point3(DVec3::ZERO);
        let eye = centre + DVec3::new(-1.4, 2.4, 4.6);
        let view = look_at_mat4(eye, centre + DVec3::new(-0.6, -0.4, 0.0), DVec3::Y);
        let proj = perspective(40.0, 1.0, 0.1, Far::Finite(100.0));
        Ok(Caster {
            adj,
            light,
            facing,
            centre,
            view,
            proj,
        })
    }
    fn pos(&self, i: u32) -> DVec3 {
        self.adj.positions[i as usize].as_dvec3()
    }
    fn screen(&self, p: DVec3) -> P {
        pixel(self.proj * self.view, 2.0, 2.0, p.extend(1.0)).unwrap_or((0.0, 0.0))
    }
    fn depth(&self, pts: &[DVec3]) -> f64 {
        pts.iter()
            .map(|p| self.view.transform_point3(*p).z)
            .sum::<f64>()
            / pts.len() as f64
    }
}

/// Legend rows (colour swatch, text) from `top`; returns the next baseline.
fn legend(s: &mut Svg, x: f64, top: f64, rows: &[(String, String)]) -> f64 {
    let mut y = top;
    for (style, t) in rows {
        s.rect((x, y - 10.0), (16.0, 11.0), style);
        y = s.para((x + 24.0, y), 12.0, "start", s.w - x - 40.0, t) + 3.0;
    }
    y
}

// ---------------------------------------------------------------- (a) silhouette

fn silhouette(c: &Caster) -> String {
    let (w, title) = (
        760.0,
        "The silhouette of lesson 05's cube under its point light",
    );
    let mut s = Svg::new(w, 0.0, title);
    let sil = silhouette_edges_for(&c.adj, &c.facing);
    let px: Vec<P> = c
        .adj
        .positions
        .iter()
        .map(|p| c.screen(p.as_dvec3()))
        .collect();
    let (lo, hi) = ((20.0, 40.0), (440.0, 420.0));
    let fit = Fit::new(&px, (90.0, 140.0), (280.0, 260.0));
    let at = |p: DVec3| fit.at(c.screen(p));
    // Faces far to near; a face turned from the eye is drawn paler.
    let mut order: Vec<usize> = (0..c.adj.triangles.len()).collect();
    let tri = |f: usize| c.adj.triangles[f].map(|i| c.pos(i));
    order.sort_by(|&a, &b| c.depth(&tri(a)).total_cmp(&c.depth(&tri(b))));
    let eye = c.view.inverse().transform_point3(DVec3::ZERO);
    let seen = |f: usize| c.adj.face_normals[f].as_dvec3().dot(eye - tri(f)[0]) > 0.0;
    for &f in &order {
        let colour = if c.facing[f] { LIT } else { AWAY };
        let style = if seen(f) {
            fill(colour, "#555")
        } else {
            format!(r##"fill="{colour}" fill-opacity="0.35" stroke="#999" stroke-width="1""##)
        };
        s.poly(&tri(f).map(at), true, &style);
    }
    for e in &sil {
        let v = at(c.pos(e.a));
        s.line(v, clip(v, at(c.light), lo, hi), &stroke("#a80", 1.0, "3,3"));
    }
    // A silhouette edge is hidden when both of its faces turn from the eye.
    for e in &sil {
        let (a, b) = (c.pos(e.a), c.pos(e.b));
        let hidden = (0..c.adj.triangles.len())
            .filter(|&f| c.adj.triangles[f].contains(&e.a) && c.adj.triangles[f].contains(&e.b))
            .all(|f| !seen(f));
        let dash = if hidden { "6,4" } else { "" };
        s.line(at(a), at(b), &stroke(SIL, 4.0, dash));
    }
    light_marker(&mut s, at(c.centre), at(c.light), lo, hi);
    let lit = c.facing.iter().filter(|f| **f).count();
    let n = c.adj.triangles.len();
    let rows = [
        (
            fill(LIT, "#555"),
            format!("faces the light (face_facing): {lit} of {n} triangles"),
        ),
        (
            fill(AWAY, "#555"),
            format!("faces away: {} triangles", n - lit),
        ),
        (
            fill(SIL, "none"),
            format!(
                "silhouette edge (silhouette_edges): {} edges, each between a lit and an unlit \
                 face; dashed where hidden behind the cube",
                sil.len()
            ),
        ),
        (
            stroke("#a80", 1.0, "3,3"),
            "grazing rays: from the light past each silhouette vertex".into(),
        ),
    ];
    let y = legend(&mut s, 460.0, 90.0, &rows);
    let note = "The silhouette is a closed loop around the lit faces: extruded away from \
                the light, it becomes the sides of the shadow volume.";
    let y = s.para((460.0, y + 14.0), 12.0, "start", 280.0, note);
    s.h = y.max(420.0);
    s.finish()
}

// ---------------------------------------------------------------- (b) sides and caps

/// How far from the light the drawing puts the far ends: `FAR` times
/// the vertex's distance. The lesson puts them at infinity (w = 0).
const FAR: f64 = 2.2;

fn sides_and_caps(c: &Caster) -> String {
    let title = "The cube's shadow volume: sides and caps (cpu_volume, lesson 05)";
    let (w, mut s) = (760.0, Svg::new(760.0, 0.0, title));
    let mut verts = Vec::new();
    let ranges = cpu_volume(&c.adj, LightDir::Point(c.light.as_vec3()), &mut verts);
    let place = |v: &workbook::lesson_05::extrusion::CpuVertex| {
        let p = Vec3::from(v.position).as_dvec3();
        if v.w == 0.0 {
            c.light + FAR * (p - c.light)
        } else {
            p
        }
    };
    // Polygons: (points, style, depth). The unlit faces of the cube first.
    let mut polys: Vec<(Vec<DVec3>, String)> = Vec::new();
    for (f, t) in c.adj.triangles.iter().enumerate() {
        if !c.facing[f] {
            polys.push((t.map(|i| c.pos(i)).to_vec(), fill(AWAY, "#888")));
        }
    }
    let part = |r: &std::ops::Range<u32>| -> Vec<Vec<DVec3>> {
        verts[r.start as usize..r.end as usize]
            .chunks_exact(3)
            .map(|t| t.iter().map(place).collect())
            .collect()
    };
    let side = r##"fill="#1f5fbf" fill-opacity="0.22" stroke="#1f5fbf" stroke-width="1.2""##;
    let back = r##"fill="#9467bd" fill-opacity="0.25" stroke="#9467bd" stroke-width="1.5" stroke-dasharray="5,3""##;
    for t in part(&ranges.sides) {
        polys.push((t, side.to_string()));
    }
    for t in part(&ranges.front) {
        polys.push((t, fill(LIT, "#a80")));
    }
    for t in part(&ranges.back) {
        polys.push((t, back.to_string()));
    }
    let px: Vec<P> = polys
        .iter()
        .flat_map(|(t, _)| t.iter().map(|&p| c.screen(p)))
        .collect();
    let (lo, hi) = ((20.0, 40.0), (460.0, 480.0));
    let fit = Fit::new(&px, (30.0, 80.0), (420.0, 390.0));
    let at = |p: DVec3| fit.at(c.screen(p));
    polys.sort_by(|a, b| c.depth(&a.0).total_cmp(&c.depth(&b.0)));
    for (t, style) in &polys {
        let pts: Vec<P> = t.iter().map(|&p| at(p)).collect();
        s.poly(&pts, true, style);
    }
    light_marker(&mut s, at(c.centre), at(c.light), lo, hi);
    let count = |r: &std::ops::Range<u32>| (r.end - r.start) / 3;
    let edges = silhouette_edges_for(&c.adj, &c.facing).len();
    // Which caps lesson 05's z-pass draws (none): lesson 06's z-fail does.
    let zpass = CasterDraw::zpass(0);
    let drawn = |cap: bool| match cap {
        true => " (z-pass draws it)",
        false => " (not drawn by z-pass; lesson 06's z-fail draws it)",
    };
    let rows = [
        (
            fill(LIT, "#a80"),
            format!(
                "front cap: the {} light-facing triangles{}",
                count(&ranges.front),
                drawn(zpass.front_cap)
            ),
        ),
        (
            side.to_string(),
            format!(
                "sides: {} triangles, two for each of the {edges} silhouette edges, \
                 extruded away from the light (lesson 05's z-pass draws these)",
                count(&ranges.sides)
            ),
        ),
        (
            back.to_string(),
            format!(
                "back cap: the same {} triangles, reversed, at infinity{}",
                count(&ranges.back),
                drawn(zpass.back_cap)
            ),
        ),
        (
            fill(AWAY, "#888"),
            "the cube's faces turned from the light".into(),
        ),
    ];
    let y = legend(&mut s, 480.0, 90.0, &rows);
    let note = format!(
        "Drawn here at {FAR} times each vertex's distance from the light; the lesson's far \
         vertices have w = 0 and lie at infinity. Inside the closed volume, every point is \
         hidden from the light by the cube."
    );
    let y = s.para((480.0, y + 14.0), 12.0, "start", w - 500.0, &note);
    s.h = y.max(490.0);
    s.finish()
}

// ---------------------------------------------------------------- (c) the z-pass count

/// The cross-section: lesson 05's functions on a long box (a prism along
/// z) lit from a point in the plane z = 0, then cut by that plane.
const LIGHT_2D: P = (-2.6, 6.4);
const EYE_2D: P = (7.6, 4.6);
const FAR_Y: f64 = -2.6;

/// A segment of the cross-section.
type Segment = (P, P);

/// The prism's cross-section: (front cap segments, silhouette points).
fn prism_section() -> Result<(Vec<Segment>, Vec<P>)> {
    let model = DMat4::from_translation(DVec3::new(0.2, 2.7, 0.0))
        * DMat4::from_rotation_z(20f64.to_radians())
        * DMat4::from_scale(DVec3::new(1.8, 0.8, 4.0));
    let cube = builtin("cube")?;
    let world: Vec<Vec3> = cube
        .positions
        .iter()
        .map(|p| model.transform_point3(p.as_dvec3()).as_vec3())
        .collect();
    let adj = Adjacency::from_triangles(&world, &cube.indices);
    let light = LightDir::Point(Vec3::new(LIGHT_2D.0 as f32, LIGHT_2D.1 as f32, 0.0));
    let facing = face_facing(&adj, light);
    let xy = |i: u32| {
        let p = adj.positions[i as usize];
        (p.x as f64, p.y as f64)
    };
    let close = |a: P, b: P| (a.0 - b.0).abs() + (a.1 - b.1).abs() < 1e-5;
    // Silhouette edges along z cut the plane in one point each.
    let points: Vec<P> = silhouette_edges_for(&adj, &facing)
        .iter()
        .filter(|e| close(xy(e.a), xy(e.b)))
        .map(|e| xy(e.a))
        .collect();
    let mut caps: Vec<(P, P)> = Vec::new();
    for t in light_facing_triangles_for(&adj, &facing) {
        let mut ends: Vec<P> = Vec::new();
        for p in t.map(xy) {
            if !ends.iter().any(|q| close(*q, p)) {
                ends.push(p);
            }
        }
        let [a, b] = ends[..] else { continue };
        if !caps
            .iter()
            .any(|&(c, d)| (close(a, c) && close(b, d)) || (close(a, d) && close(b, c)))
        {
            caps.push((a, b));
        }
    }
    if points.len() != 2 || caps.is_empty() {
        bail!(
            "prism section: {} silhouette points, {} cap segments",
            points.len(),
            caps.len()
        );
    }
    Ok((caps, points))
}

/// A silhouette point pushed away from the light to y = `y`.
fn extrude_to(p: P, y: f64) -> P {
    let t = (y - p.1) / (p.1 - LIGHT_2D.1);
    (p.0 + t * (p.0 - LIGHT_2D.0), y)
}

/// The volume's section as faces: front cap segments, two sides, back cap.
fn section_faces(caps: &[(P, P)], sil: &[P]) -> (Vec<P>, Vec<Face>) {
    // The section is convex: its hull, counter-clockwise.
    let mut pts: Vec<P> = caps.iter().flat_map(|&(a, b)| [a, b]).collect();
    pts.extend(sil.iter().map(|&p| extrude_to(p, FAR_Y)));
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    pts.dedup_by(|a, b| (a.0 - b.0).abs() + (a.1 - b.1).abs() < 1e-9);
    let cross = |o: P, a: P, b: P| (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0);
    let mut hull: Vec<P> = Vec::new();
    for pass in [pts.clone(), pts.iter().rev().copied().collect()] {
        let start = hull.len();
        for p in pass {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    let n = hull.len() as f64;
    let c = hull
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    let far = |p: P| (p.1 - FAR_Y).abs() < 1e-9;
    let faces = (0..hull.len())
        .map(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            let name = match (far(a), far(b)) {
                (true, true) => "back cap (∞)",
                (false, false) => "front cap",
                _ => "side",
            };
            let mut out = (b.1 - a.1, a.0 - b.0);
            if out.0 * (a.0 - c.0) + out.1 * (a.1 - c.1) < 0.0 {
                out = (-out.0, -out.1);
            }
            Face { a, b, name, out }
        })
        .collect();
    (hull, faces)
}

fn zpass_count() -> Result<String> {
    let (caps, sil) = prism_section()?;
    let (hull, faces) = section_faces(&caps, &sil);
    let floor: Vec<f64> = sil.iter().map(|&p| extrude_to(p, 0.0).0).collect();
    let (x0, x1) = (floor[0].min(floor[1]), floor[0].max(floor[1]));
    let targets = [
        ("a lit point", (x0 - 1.4, 0.0)),
        ("a shadowed point", ((x0 + x1) / 2.0, 0.0)),
    ];
    let title = "Z-pass: counting volume faces along two view rays (a cross-section)";
    let mut s = Svg::new(800.0, 0.0, title);
    let (wx, wy) = ((-3.6, 9.0), (FAR_Y - 0.2, 7.0));
    let k = 740.0 / (wx.1 - wx.0);
    let at = |p: P| (30.0 + (p.0 - wx.0) * k, 50.0 + (wy.1 - p.1) * k);
    let region: Vec<P> = hull.iter().map(|&p| at(p)).collect();
    s.poly(&region, true, &fill("#ddd", "none"));
    for f in &faces {
        let style = match f.name {
            "front cap" => stroke("#a80", 3.0, ""),
            "side" => stroke("#555", 2.0, ""),
            _ => stroke("#9467bd", 2.0, "6,4"),
        };
        s.line(at(f.a), at(f.b), &style);
    }
    for p in &sil {
        s.line(at(LIGHT_2D), at(*p), &stroke("#a80", 1.0, "3,3"));
    }
    s.line(
        at((wx.0, 0.0)),
        at((wx.1, 0.0)),
        &stroke("#8b5a2b", 3.0, ""),
    );
    s.text(
        add(at((wx.0, 0.0)), 4.0, -6.0),
        12.0,
        "start",
        "floor (the receiver)",
    );
    s.circle(at(LIGHT_2D), 9.0, &fill("#ffd400", "#a80"));
    s.text(add(at(LIGHT_2D), 13.0, 4.0), 12.0, "start", "light");
    s.circle(at(EYE_2D), 6.0, &fill(BLUE, "none"));
    s.text(add(at(EYE_2D), 0.0, -12.0), 12.0, "middle", "eye");
    let names = [
        ("front cap", "front cap (the lit faces)"),
        ("side", "side"),
        ("back cap (∞)", "back cap (∞, lesson 06)"),
    ];
    let mut labelled = Vec::new();
    for f in &faces {
        if labelled.contains(&f.name) {
            continue;
        }
        labelled.push(f.name);
        let label = names.iter().find(|n| n.0 == f.name).map_or(f.name, |n| n.1);
        let m = ((f.a.0 + f.b.0) / 2.0, (f.a.1 + f.b.1) / 2.0);
        let (anchor, d) = if f.out.0 < -1e-9 {
            ("end", -8.0)
        } else {
            ("start", 8.0)
        };
        let dy = match f.name {
            "front cap" => -6.0,
            "side" => 4.0,
            _ => 16.0,
        };
        s.text(add(at(m), d, dy), 12.0, anchor, label);
    }
    let colours = ["#2ca02c", BLUE];
    let mut lines = Vec::new();
    for ((what, target), colour) in targets.iter().zip(colours) {
        s.line(at(EYE_2D), at(*target), &stroke(colour, 2.0, ""));
        s.circle(at(*target), 5.0, &fill("#fff", colour));
        let d = (target.0 - EYE_2D.0, target.1 - EYE_2D.1);
        let mut count = 0;
        let mut steps = Vec::new();
        for (t, sign, _) in crossings(EYE_2D, *target, &faces) {
            if t >= 1.0 {
                continue;
            }
            count += sign;
            let p = at((EYE_2D.0 + t * d.0, EYE_2D.1 + t * d.1));
            s.circle(p, 5.0, &fill(colour, "none"));
            let label = format!("{} → {count}", signed(sign));
            s.text(add(p, 2.0, -9.0), 13.0, "start", &label);
            steps.push(signed(sign));
        }
        let shadow = inside(&hull, *target);
        if (count != 0) != shadow {
            bail!("z-pass count {count} disagrees with the section for {what}");
        }
        let verdict = ["lit", "in shadow"][(count != 0) as usize];
        let sum = if steps.is_empty() {
            "no crossing".into()
        } else {
            steps.join(" ")
        };
        s.text(
            add(at(*target), 0.0, 18.0),
            12.0,
            "middle",
            &format!("count {count}"),
        );
        lines.push(format!(
            "Ray to {what}: {sum} = {count} at the surface → {verdict}."
        ));
    }
    let mut y = at((0.0, FAR_Y)).1 + 30.0;
    y = s.texts((30.0, y), 13.0, "start", &lines) + 4.0;
    let note = "Each face crossed in front of the surface adds +1 where the ray enters the volume \
                (a face turned towards the eye) and −1 where it leaves; the number after the arrow \
                is the running count. The lesson's cube, extended along z into a long box, cut \
                through the light: its silhouette edges and lit faces are silhouette_edges and \
                light_facing_triangles.";
    s.h = s.para((30.0, y), 12.0, "start", 740.0, note);
    Ok(s.finish())
}

// ---------------------------------------------------------------- (d) stencil counts

const COLS: u32 = 96;
const ROWS: u32 = 54;
const CELL: f64 = 3.9;
const COUNT_COLOURS: [&str; 5] = ["#f2f2f2", "#9ecae1", "#4292c6", "#08519c", "#08306b"];

/// Lesson 05's z-pass stencil value at the surface each cell's ray hits:
/// the number of light-facing caster triangles between the point and the
/// light, each one's own volume holding the point (as `max_volume_overlap`
/// counts it). `None` where the ray hits nothing.
fn stencil_grid(scene: &Scene, light: usize) -> Result<Vec<Option<u32>>> {
    let tris = scene.world_triangles();
    let bvh = Bvh::try_build(tris.iter().map(|(t, _)| *t).collect())?;
    let o = scene.origin();
    let l = match scene.lights[light].kind {
        LightKind::Directional { direction } => LightDir::Directional(direction.as_vec3()),
        LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
            LightDir::Point((position - o).as_vec3())
        }
    };
    let two: Vec<bool> = scene
        .objects
        .iter()
        .map(|o| casts_two_sided(&o.mesh))
        .collect();
    let lit: Vec<[Vec3; 3]> = tris
        .iter()
        .filter(|(_, i)| scene.objects[*i as usize].casts_shadow)
        .filter(|(t, i)| {
            let n = face_normal(t[0], t[1], t[2]);
            let towards = match l {
                LightDir::Point(p) => n.dot(p - t[0]),
                LightDir::Directional(d) => n.dot(-d),
            };
            towards > 0.0 || (two[*i as usize] && towards < 0.0)
        })
        .map(|(t, _)| *t)
        .collect();
    let inv = camera_matrices(scene, COLS, ROWS)
        .view_proj
        .as_dmat4()
        .inverse();
    let mut out = Vec::new();
    for j in 0..ROWS {
        for i in 0..COLS {
            let (org, d) = primary_ray(inv, i, j, COLS, ROWS);
            let Some(hit) = bvh.closest_hit(org, d, f32::INFINITY) else {
                out.push(None);
                continue;
            };
            let p = org + d * hit.t;
            let (to, t_max) = match l {
                LightDir::Point(lp) => ((lp - p).normalize(), (lp - p).length()),
                LightDir::Directional(dir) => (-dir.normalize(), f32::INFINITY),
            };
            out.push(Some(
                lit.iter()
                    .filter(|t| segment_crosses(p, to, t_max, t))
                    .count() as u32,
            ));
        }
    }
    Ok(out)
}

fn stencil_counts(scene: &Scene) -> Result<String> {
    let title = "The stencil after the volume pass: lesson 05's default scene, one count per light";
    let (pw, gap, left) = (COLS as f64 * CELL, 24.0, 28.0);
    let mut s = Svg::new(2.0 * pw + gap + 2.0 * left, 0.0, title);
    let mut tally = vec![0u32; COUNT_COLOURS.len()];
    let mut sky = 0;
    let names = ["light 0 (point)", "light 1 (directional)"];
    for (k, name) in names.iter().enumerate() {
        let grid = stencil_grid(scene, k)?;
        let x0 = left + k as f64 * (pw + gap);
        s.text((x0, 54.0), 13.0, "start", name);
        for j in 0..ROWS {
            // One rectangle per run of equal values along the row.
            let row = &grid[(j * COLS) as usize..((j + 1) * COLS) as usize];
            let mut i = 0;
            while i < row.len() {
                let run = row[i..].iter().take_while(|v| **v == row[i]).count();
                let colour = match row[i] {
                    None => "#fff",
                    Some(c) => COUNT_COLOURS[(c as usize).min(COUNT_COLOURS.len() - 1)],
                };
                let at = (x0 + i as f64 * CELL, 62.0 + j as f64 * CELL);
                let style = format!(r#"fill="{colour}" stroke="none""#);
                s.rect(at, (run as f64 * CELL + 0.3, CELL + 0.3), &style);
                i += run;
            }
        }
        s.rect((x0, 62.0), (pw, ROWS as f64 * CELL), INK);
        for v in &grid {
            match v {
                None => sky += 1,
                Some(c) => tally[(*c as usize).min(COUNT_COLOURS.len() - 1)] += 1,
            }
        }
    }
    let mut y = 62.0 + ROWS as f64 * CELL + 26.0;
    let top = COUNT_COLOURS.len() - 1;
    let mut rows: Vec<(String, String)> = Vec::new();
    for (v, n) in tally.iter().enumerate() {
        if *n == 0 {
            continue;
        }
        let value = if v == top {
            format!("{v} or more")
        } else {
            v.to_string()
        };
        let meaning = match v {
            0 => "outside every volume: lit".to_string(),
            1 => "inside one volume: in shadow".to_string(),
            _ => format!("inside {v} volumes at once: in shadow"),
        };
        rows.push((
            fill(COUNT_COLOURS[v], "#888"),
            format!("{value}: {meaning} ({n} cells)"),
        ));
    }
    rows.push((fill("#fff", "#888"), format!("no surface ({sky} cells)")));
    let half = rows.len().div_ceil(2);
    for (c, chunk) in rows.chunks(half).enumerate() {
        let x = left + c as f64 * (pw + gap);
        for (i, (style, t)) in chunk.iter().enumerate() {
            let yy = y + 18.0 * i as f64;
            s.rect((x, yy - 10.0), (16.0, 11.0), style);
            s.text((x + 24.0, yy), 12.0, "start", t);
        }
    }
    y += 18.0 * half as f64 + 8.0;
    let note = format!(
        "Each cell is one pixel of a {COLS}×{ROWS} frame from the scene's camera: the z-pass \
         count at the surface it sees, computed on the CPU as the number of lit caster triangles \
         between that point and the light (each holds the point in its own volume). The lit \
         pass adds the light only where the count is 0."
    );
    s.h = s.para((left, y), 12.0, "start", s.w - 2.0 * left, &note);
    Ok(s.finish())
}

// ---------------------------------------------------------------- (e) w = 0

const W0_SIZE: (u32, u32) = (640, 360);

fn w_zero(scene: &Scene, c: &Caster) -> Result<String> {
    let title = "Extrusion to w = 0: homogeneous points at infinity on lesson 05's screen";
    let (pw, left) = (370.0, 20.0);
    let mut s = Svg::new(2.0 * pw + 3.0 * left, 0.0, title);
    let (w, h) = W0_SIZE;
    let o = scene.origin();
    let vp = camera_matrices(scene, w, h).view_proj.as_dmat4();
    let px = |p: DVec4| pixel(vp, w as f64, h as f64, p);
    let rel = |p: DVec3| (p - o).extend(1.0);
    let dir = scene.lights.iter().find_map(|l| match l.kind {
        LightKind::Directional { direction } => Some(direction),
        _ => None,
    });
    let dir = dir.context("lesson_05.toml: no directional light")?;
    let mut bottom: f64 = 0.0;
    for (k, light) in [
        LightDir::Point(c.light.as_vec3()),
        LightDir::Directional(dir.as_vec3()),
    ]
    .into_iter()
    .enumerate()
    {
        let facing = face_facing(&c.adj, light);
        let mut verts: Vec<u32> = silhouette_edges_for(&c.adj, &facing)
            .iter()
            .map(|e| e.a)
            .collect();
        verts.sort_unstable();
        verts.dedup();
        // Where each silhouette vertex goes: its direction away from the light, w = 0.
        let away = |v: DVec3| match light {
            LightDir::Point(_) => v - c.light,
            LightDir::Directional(_) => dir,
        };
        let mut pts = vec![(0.0, 0.0), (w as f64, h as f64)];
        let mut ends = Vec::new();
        for &i in &verts {
            let v = c.pos(i);
            let inf = px(away(v).extend(0.0)).context("a vanishing point behind the eye")?;
            let near = px(rel(v)).context("the cube behind the eye")?;
            pts.extend([inf, near]);
            ends.push((v, near, inf));
        }
        let x0 = left + k as f64 * (pw + left);
        let fit = Fit::new(&pts, (x0, 80.0), (pw, 240.0));
        let (a, b) = (fit.at((0.0, 0.0)), fit.at((w as f64, h as f64)));
        s.rect(a, (b.0 - a.0, b.1 - a.1), &fill("#f4f7fb", "#222"));
        for (f, t) in c.adj.triangles.iter().enumerate() {
            let tri: Option<Vec<P>> = t
                .iter()
                .map(|&i| px(rel(c.pos(i))).map(|p| fit.at(p)))
                .collect();
            let colour = if facing[f] { LIT } else { AWAY };
            s.poly(
                &tri.context("the cube behind the eye")?,
                true,
                &fill(colour, "#666"),
            );
        }
        for &(v, near, inf) in &ends {
            s.line(fit.at(near), fit.at(inf), &stroke(SIL, 1.2, "5,3"));
            for t in [1.0, 3.0, 9.0] {
                if let Some(p) = px(rel(v + t * away(v))) {
                    s.circle(fit.at(p), 2.5, &fill(SIL, "none"));
                }
            }
        }
        let (v, _, inf) = ends[0];
        s.circle(fit.at(inf), 6.0, &fill("#9467bd", "#222"));
        let heading = ["(a) point light p", "(b) directional light d"][k];
        s.text((x0, 62.0), 14.0, "start", heading);
        let at_px = format!("→ pixel ({:.0}, {:.0})", inf.0, inf.1);
        let lines = match light {
            LightDir::Point(_) => vec![
                format!("p = {}, light 0", v3(c.light)),
                format!("v = {}, w = 1 (a silhouette vertex)", v3(v)),
                format!(
                    "(v − p, 0) = ({}, 0)",
                    &v3(v - c.light)[1..v3(v - c.light).len() - 1]
                ),
                format!("{at_px}: v's own vanishing point"),
            ],
            LightDir::Directional(_) => vec![
                format!("d = {}, light 1", v3(dir)),
                format!("(d, 0) = ({}, 0)", &v3(dir)[1..v3(dir).len() - 1]),
                format!("{at_px}: every extruded vertex"),
                format!("lands here ({} silhouette vertices)", verts.len()),
            ],
        };
        let mut y = 80.0 + 240.0 + 24.0;
        for l in &lines {
            y = s.para((x0, y), 12.0, "start", pw, l);
        }
        bottom = bottom.max(y);
    }
    let note = format!(
        "The {w}×{h} screen of the scene's camera (light blue) with the cube. Dashed red: each \
         silhouette vertex v pushed away from the light; the dots are v + t·(direction) for \
         t = 1, 3, 9, closing in on the purple point, the projection of the w = 0 point: where \
         that direction vanishes on screen. The rasteriser draws the volume's far vertices \
         there, with no finite length to choose and nothing for a far plane to clip."
    );
    s.h = s.para(
        (left, bottom + 10.0),
        12.0,
        "start",
        s.w - 2.0 * left,
        &note,
    );
    Ok(s.finish())
}

// ---------------------------------------------------------------- the passes

/// One pass's row: its background, then its cells (pass, depth, stencil,
/// colour), each a list of lines.
type PassRow = (
    &'static str,
    Vec<String>,
    Vec<String>,
    Vec<String>,
    Vec<String>,
);

/// A stencil face's rule, as the pipeline states it.
fn face_rule(f: &wgpu::StencilFaceState) -> String {
    format!(
        "compare {:?}; depth pass {:?}, depth fail {:?}, fail {:?}",
        f.compare, f.pass_op, f.depth_fail_op, f.fail_op
    )
}

/// Lesson 05's three passes in a frame, one row each, with the depth,
/// stencil and colour state each sets. The stencil cells and the parts of
/// the volume drawn are read from the lesson's code (`Counting::zpass`,
/// `lit_stencil`, `CasterDraw::zpass`); the depth and colour cells are
/// typed here, as `SceneGpu::new`, the volume pipelines and
/// `SceneGpu::lit_pipeline` set them inside pipeline creation, which needs
/// a device.
fn passes() -> String {
    let counting = Counting::zpass();
    let (zpass, lit) = (counting.zpass, lit_stencil());
    let draw = CasterDraw::zpass(0);
    let parts = match (draw.front_cap, draw.back_cap) {
        (false, false) => "the sides only, no caps",
        (true, false) => "the sides and the front cap",
        (false, true) => "the sides and the back cap",
        (true, true) => "the sides and both caps",
    };
    let both = |st: &wgpu::StencilState| -> Vec<String> {
        if st.front == st.back {
            vec![format!("both faces: {}", face_rule(&st.front))]
        } else {
            vec![
                format!("front faces: {}", face_rule(&st.front)),
                format!("back faces: {}", face_rule(&st.back)),
            ]
        }
    };
    let mask = |st: &wgpu::StencilState| {
        format!(
            "read mask 0x{:02x}, write mask 0x{:02x}",
            st.read_mask, st.write_mask
        )
    };
    let mut volume_stencil = vec!["cleared to 0 (LoadOp::Clear(0))".to_string()];
    volume_stencil.extend(both(&zpass));
    volume_stencil.push(mask(&zpass));
    let mut lit_stencil_cell = both(&lit);
    lit_stencil_cell.push("reference 0: draws where the count is 0".into());
    lit_stencil_cell.push(mask(&lit));
    let rows: [PassRow; 3] = [
        (
            "#eef3fb",
            vec![
                "1. base pass".into(),
                "once a frame".into(),
                "draws every object".into(),
            ],
            vec![
                "test Less".into(),
                "write on: the visible surface's depth".into(),
            ],
            vec!["not used".into()],
            vec![
                "writes the ambient term and the object id".into(),
                "no blending".into(),
            ],
        ),
        (
            "#fff6dc",
            vec![
                "2. volume pass".into(),
                "per light".into(),
                format!("draws the volumes: {parts}"),
                "cull none: both faces count".into(),
            ],
            vec![
                "test Less against pass 1's depth".into(),
                "write off".into(),
            ],
            volume_stencil,
            vec!["none: no fragment stage, no colour target".into()],
        ),
        (
            "#eaf6ea",
            vec![
                "3. lit pass".into(),
                "per light".into(),
                "draws every object again".into(),
            ],
            vec![
                "test LessEqual: equal to pass 1's depth".into(),
                "write off".into(),
            ],
            lit_stencil_cell,
            vec![
                "adds the light: blend One + One (colour)".into(),
                "writes the light's visibility".into(),
            ],
        ),
    ];
    let title = "Lesson 05's passes: what each tests and writes";
    let w = 860.0;
    let mut s = Svg::new(w, 0.0, title);
    let cols = [
        (20.0, 165.0),
        (185.0, 160.0),
        (345.0, 340.0),
        (685.0, 155.0),
    ];
    let heads = ["pass", "depth", "stencil", "colour"];
    let mut y = 58.0;
    for (&(x, _), h) in cols.iter().zip(heads) {
        s.text((x + 6.0, y), 13.0, "start", h);
    }
    y += 10.0;
    for (bg, a, b, c, d) in rows {
        // Each cell wrapped to its column; the row as tall as its tallest.
        let cells: Vec<Vec<String>> = [a, b, c, d]
            .iter()
            .zip(cols)
            .map(|(lines, (_, cw))| {
                lines
                    .iter()
                    .flat_map(|l| crate::diagrams::wrap(l, 12.0, cw - 14.0))
                    .collect()
            })
            .collect();
        let rows_h = cells.iter().map(|c| c.len()).max().unwrap_or(1) as f64 * 17.0 + 14.0;
        s.rect((20.0, y), (w - 40.0, rows_h), &fill(bg, "#999"));
        for (cell, &(x, _)) in cells.iter().zip(&cols) {
            s.texts((x + 6.0, y + 20.0), 12.0, "start", cell);
        }
        y += rows_h;
    }
    for &(x, _) in &cols[1..] {
        s.line((x, 68.0), (x, y), &stroke("#999", 1.0, ""));
    }
    let note = "The stencil cells and the volume's parts are read from the lesson's code \
        (Counting::zpass, lit_stencil, CasterDraw::zpass); the depth and colour cells are as \
        SceneGpu and the volume pipelines set them. The volume pass loads pass 1's depth and \
        never writes it, so every light's volumes are tested against the same surfaces.";
    s.h = s.para((20.0, y + 24.0), 12.0, "start", w - 40.0, note);
    s.finish()
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
