//! Chapter 08's exercises: the reference solutions (same items as
//! `lessons/lesson_08/exercises.rs`; built with `--features solutions`).

use common::glam::{DMat4, DVec3, DVec4};

use crate::lesson_08::range_sphere::{Scissor, DEPTH_MARGIN, SPHERE_MARGIN};

// ANCHOR: scissor_rect
/// Exercise 1. A sphere wholly in front of the near plane: per axis, the
/// two tangent lines from the eye, a = k·(−z), whose slopes k solve
/// (ca + k·cz)² = r²(1 + k²). A sphere crossing the near plane: the
/// corners of its bounding box, cut at the near plane (looser, and safe).
pub fn scissor_rect(
    proj: DMat4,
    near: f64,
    centre_view: DVec3,
    r: f64,
    w: u32,
    h: u32,
) -> Option<Scissor> {
    let r = r * (1.0 + SPHERE_MARGIN);
    let c = centre_view;
    if c.length() <= r {
        return Some(Scissor::full(w, h));
    }
    if c.z - r >= -near {
        return None;
    }
    let (sx, sy) = (proj.x_axis.x, proj.y_axis.y);
    let (x0, x1, y0, y1) = if c.z + r < -near {
        // Tangent slopes: k²(cz² − r²) + 2·ca·cz·k + ca² − r² = 0.
        let slopes = |ca: f64| {
            let a = c.z * c.z - r * r;
            let root = r * (ca * ca + c.z * c.z - r * r).sqrt();
            ((-ca * c.z - root) / a, (-ca * c.z + root) / a)
        };
        let ((kx0, kx1), (ky0, ky1)) = (slopes(c.x), slopes(c.y));
        (
            sx * kx0.min(kx1),
            sx * kx0.max(kx1),
            sy * ky0.min(ky1),
            sy * ky0.max(ky1),
        )
    } else {
        let z_hi = -near; // the box, cut at the near plane
        let (mut lo, mut hi) = ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN));
        for x in [c.x - r, c.x + r] {
            for y in [c.y - r, c.y + r] {
                for z in [c.z - r, z_hi] {
                    let (nx, ny) = (sx * x / -z, sy * y / -z);
                    lo = (lo.0.min(nx), lo.1.min(ny));
                    hi = (hi.0.max(nx), hi.1.max(ny));
                }
            }
        }
        (lo.0, hi.0, lo.1, hi.1)
    };
    let (x0, x1) = (x0.max(-1.0), x1.min(1.0));
    let (y0, y1) = (y0.max(-1.0), y1.min(1.0));
    if x0 >= x1 || y0 >= y1 {
        return None;
    }
    let (wf, hf) = (w as f64, h as f64);
    let px0 = ((x0 + 1.0) * 0.5 * wf).floor() as u32;
    let px1 = (((x1 + 1.0) * 0.5 * wf).ceil() as u32).min(w);
    let py0 = ((1.0 - y1) * 0.5 * hf).floor() as u32;
    let py1 = (((1.0 - y0) * 0.5 * hf).ceil() as u32).min(h);
    (px1 > px0 && py1 > py0).then_some(Scissor {
        x: px0,
        y: py0,
        width: px1 - px0,
        height: py1 - py0,
    })
}
// ANCHOR_END: scissor_rect

// ANCHOR: depth_bounds
/// Exercise 2: the nearest and farthest view distance of the sphere
/// (the nearest no nearer than the near plane), through the projection.
pub fn depth_bounds(proj: DMat4, near: f64, centre_view: DVec3, r: f64) -> Option<(f32, f32)> {
    let r = r * (1.0 + SPHERE_MARGIN);
    let d = -centre_view.z;
    if d + r <= near {
        return None;
    }
    let depth = |d: f64| {
        let c = proj * DVec4::new(0.0, 0.0, -d, 1.0);
        c.z / c.w
    };
    let (a, b) = (depth((d - r).max(near)), depth(d + r));
    let zmin = (a.min(b) - DEPTH_MARGIN).clamp(0.0, 1.0);
    let zmax = (a.max(b) + DEPTH_MARGIN).clamp(0.0, 1.0);
    Some((zmin as f32, zmax as f32))
}
// ANCHOR_END: depth_bounds
