//! Chapter 08's range sphere (`range_sphere.svg`): a point light's range
//! from above and on the screen, with the depth bounds and the scissor
//! lesson 08 computes from it.

use std::path::Path;

use anyhow::{bail, Context, Result};
use common::glam::{DMat4, DVec3};
use common::scene::camera::camera_matrices;
use common::scene::{Far, LightKind, Scene};
use workbook::lesson_08::range_sphere::{sphere_depth_bounds, sphere_scissor, SPHERE_MARGIN};

use super::svg::{add, fill, stroke, text_span, vec_text, Svg, INK, P};
use crate::record::Record;

/// Lesson 08's image size, the one its tables are measured at: its
/// default run's record.
fn screen(root: &Path) -> Result<(u32, u32)> {
    let path = root.join("book/src/generated/lesson_08/results.json");
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    let record: Record =
        serde_json::from_str(&text).with_context(|| format!("{}: not a record", path.display()))?;
    Ok((record.width, record.height))
}

pub(super) fn range_sphere(root: &Path) -> Result<String> {
    let scene = Scene::load(&root.join("scenes/lesson_08.toml"))?;
    let LightKind::Point { position, range } = scene.lights[0].kind else {
        bail!("lesson_08.toml: light 0 is not a point light");
    };
    let (w, h) = screen(root)?;
    let cam = camera_matrices(&scene, w, h);
    let (view, proj, near) = (cam.view.as_dmat4(), cam.proj.as_dmat4(), scene.camera.near);
    let c = view.transform_point3(position - scene.origin());
    let bounds = sphere_depth_bounds(proj, near, c, range).context("sphere behind the camera")?;
    let sc = sphere_scissor(proj, near, c, range, w, h).context("sphere off screen")?;
    let title = "A point light's range sphere: depth bounds and scissor (lesson 08, light 0)";
    let mut s = Svg::new(800.0, 0.0, title);
    let (p, eye) = (vec_text(position), vec_text(scene.camera.eye));
    let far = match scene.camera.far {
        Far::Finite(f) => format!("far {f}"),
        Far::Infinite => "far infinite".into(),
    };
    let head =
        format!("light 0 at {p}, range {range}; camera at {eye}, {w}×{h}, near {near}, {far}");
    s.text((400.0, 46.0), 13.0, "middle", &head);
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
mod tests {
    use super::super::svg::tests::{after, elements, is, number, texts};
    use super::*;

    /// The scissor drawn and printed bounds the sphere's image, tightly,
    /// and the depth bounds printed hold its depths: light 0's range sphere
    /// sampled at 360 × 720 points of its surface, each projected with the
    /// scene's camera at the record's size, gives the pixels and window
    /// depths the sphere covers.
    #[test]
    fn scissor_and_depth_bounds_hold_the_sampled_sphere() {
        let root = &crate::repo_root();
        let svg = range_sphere(root).unwrap();
        let scene = Scene::load(&root.join("scenes/lesson_08.toml")).unwrap();
        let LightKind::Point { position, range } = scene.lights[0].kind else {
            panic!("light 0 is not a point light");
        };
        let (w, h) = screen(root).unwrap();
        let cam = camera_matrices(&scene, w, h);
        let view_proj = cam.view_proj.as_dmat4();
        let centre = position - scene.origin();
        let (mut lo, mut hi) = ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN));
        let (mut zlo, mut zhi) = (f64::MAX, f64::MIN);
        for i in 0..=360 {
            let polar = std::f64::consts::PI * i as f64 / 360.0;
            for j in 0..720 {
                let az = std::f64::consts::TAU * j as f64 / 720.0;
                let dir = DVec3::new(polar.sin() * az.cos(), polar.cos(), polar.sin() * az.sin());
                let c = view_proj * (centre + range * dir).extend(1.0);
                assert!(c.w > 0.0, "the sphere is in front of the camera");
                let ndc = c.truncate() / c.w;
                let px = (
                    (ndc.x + 1.0) * 0.5 * w as f64,
                    (1.0 - ndc.y) * 0.5 * h as f64,
                );
                (lo, hi) = (
                    (lo.0.min(px.0), lo.1.min(px.1)),
                    (hi.0.max(px.0), hi.1.max(px.1)),
                );
                (zlo, zhi) = (zlo.min(ndc.z), zhi.max(ndc.z));
            }
        }
        // The scissor as printed, and as drawn on the screen's rectangle.
        let all: Vec<String> = texts(&svg).into_iter().map(|t| t.2).collect();
        let note = all
            .iter()
            .find(|t| t.starts_with("x "))
            .expect("the scissor's numbers");
        let (x, y) = (after(note, "x "), after(note, "y "));
        let (sw, sh) = (after(note, &format!("y {y}, ")), after(note, "× "));
        let rects = elements(&svg, "rect");
        let frame = (rects.iter())
            .find(|r| is(r, "stroke", "#222") && is(r, "fill", "none"))
            .expect("the screen");
        let k = number(frame, "width") / w as f64;
        assert!((number(frame, "height") / h as f64 - k).abs() < 1e-3);
        let red = (rects.iter())
            .find(|r| is(r, "stroke", "#d62728"))
            .expect("the scissor");
        let drawn = [
            (number(red, "x") - number(frame, "x")) / k,
            (number(red, "y") - number(frame, "y")) / k,
            number(red, "width") / k,
            number(red, "height") / k,
        ];
        for (d, p) in drawn.iter().zip([x, y, sw, sh]) {
            assert!((d - p).abs() < 0.05, "drawn {drawn:?}, printed {note:?}");
        }
        // It holds every sampled pixel, and is no more than the rounding
        // outwards (and the lesson's 0.1 % margin) larger.
        let (x1, y1) = (x + sw, y + sh);
        assert!(
            x <= lo.0 && y <= lo.1 && hi.0 <= x1 && hi.1 <= y1,
            "scissor x {x}..{x1}, y {y}..{y1}; the sphere covers x {:.2}..{:.2}, y {:.2}..{:.2}",
            lo.0,
            hi.0,
            lo.1,
            hi.1
        );
        let slack = [lo.0 - x, lo.1 - y, x1 - hi.0, y1 - hi.1];
        assert!(slack.iter().all(|s| *s < 1.5), "slack {slack:?}");
        // The yellow outline is the sphere's image.
        let poly = (elements(&svg, "polygon").into_iter())
            .find(|p| is(p, "stroke", "#a80"))
            .expect("the outline");
        let pts: Vec<(f64, f64)> = (poly["points"].split(' '))
            .map(|p| {
                let (a, b) = p.split_once(',').unwrap();
                let (a, b): (f64, f64) = (a.parse().unwrap(), b.parse().unwrap());
                ((a - number(frame, "x")) / k, (b - number(frame, "y")) / k)
            })
            .collect();
        let fold = |f: fn(f64, f64) -> f64, g: fn(&(f64, f64)) -> f64, init| {
            pts.iter().map(g).fold(init, f)
        };
        let outline = [
            fold(f64::min, |p| p.0, f64::MAX),
            fold(f64::min, |p| p.1, f64::MAX),
            fold(f64::max, |p| p.0, f64::MIN),
            fold(f64::max, |p| p.1, f64::MIN),
        ];
        for (o, s) in outline.iter().zip([lo.0, lo.1, hi.0, hi.1]) {
            assert!(
                (o - s).abs() < 0.3,
                "outline {outline:?}, sphere {lo:?} {hi:?}"
            );
        }
        // The depth bounds printed hold the sampled depths, just: within
        // the lesson's margins (0.1 % of the radius, 4 steps of 24-bit
        // depth) and the printing's rounding, 1e-5 here.
        let bounds = all
            .iter()
            .find(|t| t.contains("(sphere_depth_bounds): ["))
            .unwrap();
        let zmin = after(bounds, "[");
        let zmax = after(bounds, ", ");
        assert!(
            zmin <= zlo && zhi <= zmax && zlo - zmin < 1e-5 && zmax - zhi < 1e-5,
            "printed [{zmin}, {zmax}], the sphere's depths {zlo:.7}..{zhi:.7}"
        );
    }
}
