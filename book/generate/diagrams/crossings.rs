//! Counting a view ray through a 2D shadow volume: the volume's faces with
//! their outward normals, where the ray crosses each (+1 entering, −1
//! leaving), and whether a point lies inside. Chapters 05 and 06 draw it.

use super::svg::P;

/// One face of a 2D shadow volume, with its outward normal.
pub(crate) struct Face {
    pub(crate) a: P,
    pub(crate) b: P,
    pub(crate) name: &'static str,
    pub(crate) out: P,
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
