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

/// The two panels: a name, the eye and the surface point it looks at.
const CASES: [(&str, P, P); 2] = [
    ("eye outside the volume", (6.0, 4.5), (1.5, 0.0)),
    ("eye inside the volume", (0.9, 1.2), (0.0, 0.0)),
];

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
    for (k, (name, eye, target)) in CASES.into_iter().enumerate() {
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
    // The ray drawn on past the back cap.
    let t_end = (FAR_Y - 0.5 - eye.1) / d.1;
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

#[cfg(test)]
mod tests {
    use super::super::svg::tests::{elements, is, number, texts};
    use super::*;

    /// Whether `p` is in the occluder's shadow volume, without its faces:
    /// between the occluder's line and the back cap's, and seen from the
    /// light through the occluder.
    fn in_volume(p: P) -> bool {
        let ((a, y), (b, _)) = OCCLUDER;
        if !(FAR_Y..=y).contains(&p.1) || p.1 >= LIGHT.1 {
            return false;
        }
        let x = LIGHT.0 + (p.0 - LIGHT.0) * (LIGHT.1 - y) / (LIGHT.1 - p.1);
        (a.min(b)..=a.max(b)).contains(&x)
    }

    /// Each panel's counts, against the ray marched through the volume in
    /// steps of 10 µm: every change from outside to inside is a face
    /// crossed entering (+1), every change back one crossed leaving (−1).
    /// Z-pass adds those between the eye and the surface point, z-fail
    /// those past it with their signs flipped; the panel draws one green
    /// dot for each crossing in front and one purple dot for each behind,
    /// prints the two sums, and calls the point in shadow where it is
    /// inside the volume.
    #[test]
    fn counts_are_the_rays_crossings_of_the_volume() {
        let svg = zpass_zfail_ray().unwrap();
        let circles = elements(&svg, "circle");
        let words = texts(&svg);
        let line = |key: &str, panel: usize| -> String {
            let mut found: Vec<&(f64, f64, String)> =
                words.iter().filter(|t| t.2.starts_with(key)).collect();
            found.sort_by(|a, b| a.0.total_cmp(&b.0));
            found[panel].2.clone()
        };
        let sum = |text: &str| -> i32 {
            let rhs = text.rsplit_once(" = ").unwrap().1;
            rhs.split(' ')
                .next()
                .unwrap()
                .replace('−', "-")
                .parse()
                .unwrap()
        };
        for (k, (name, eye, target)) in CASES.into_iter().enumerate() {
            let d = (target.0 - eye.0, target.1 - eye.1);
            let at = |t: f64| (eye.0 + t * d.0, eye.1 + t * d.1);
            let t_end = (FAR_Y - 1.0 - eye.1) / d.1;
            let step = 1e-5 / d.0.hypot(d.1);
            let (mut front, mut behind) = (Vec::new(), Vec::new());
            let mut was = in_volume(eye);
            let mut t = 0.0;
            while t < t_end {
                t += step;
                let is = in_volume(at(t));
                if is != was {
                    let sign = if is { 1 } else { -1 };
                    if t < 1.0 {
                        front.push(sign)
                    } else {
                        behind.push(sign)
                    }
                }
                was = is;
            }
            let zpass: i32 = front.iter().sum();
            let zfail: i32 = -behind.iter().sum::<i32>();
            let in_panel = |c: &&std::collections::HashMap<String, String>| {
                (number(c, "cx") > 400.0) == (k == 1)
            };
            let dots = |colour: &str| {
                (circles.iter())
                    .filter(|c| is(c, "fill", colour) && number(c, "r") == 6.0)
                    .filter(in_panel)
                    .count()
            };
            assert_eq!(dots("#2ca02c"), front.len(), "{name}: green dots");
            assert_eq!(dots("#9467bd"), behind.len(), "{name}: purple dots");
            let (pass, fail) = (line("z-pass (", k), line("z-fail (", k));
            assert_eq!(sum(&pass), zpass, "{name}: {pass}");
            assert_eq!(sum(&fail), zfail, "{name}: {fail}");
            let inside = in_volume(target);
            assert_eq!(zfail != 0, inside, "z-fail is right: {name}");
            let truth = line("truth", k);
            assert_eq!(truth.contains("in shadow"), inside, "{name}: {truth}");
        }
    }
}
