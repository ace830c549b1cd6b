//! Chapters 05 and 06's view ray (`zpass_zfail_ray.svg`): one ray, two
//! ways to count the shadow volume's faces, z-pass and z-fail, with the
//! eye outside the volume and inside it.

use anyhow::Result;

use super::crossings::{crossings, inside, signed, Face};
use super::svg::{add, fill, stroke, Svg, P};

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

pub(super) fn zpass_zfail_ray() -> Result<String> {
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
