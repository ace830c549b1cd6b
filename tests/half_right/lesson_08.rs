//! Lesson 08's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_08/exercises.rs`; built with `--features chapter_copies`.

use common::glam::{DMat4, DVec3};

use crate::lesson_08::range_sphere::{window_depth, DEPTH_MARGIN, SPHERE_MARGIN};

// ANCHOR: cone_sphere
/// Exercise 1. The cap's rim is a circle at distance range·cos θ along the
/// axis, of radius range·sin θ. Below 45° the smallest sphere passes
/// through the apex and the rim: its centre c on the axis is as far from
/// both, c = range / (2 cos θ). From 45° the rim's own circle is a great
/// circle, and that sphere already holds the apex.
pub fn cone_sphere(position: DVec3, direction: DVec3, range: f64, half_angle: f64) -> (DVec3, f64) {
    let (sin, cos) = half_angle.sin_cos();
    // THE MISTAKE: the rim's own circle for every angle; below 45° that
    // sphere leaves the apex out.
    let (along, radius) = if half_angle < 0.0 {
        let c = range / (2.0 * cos);
        (c, c)
    } else {
        (range * cos, range * sin)
    };
    (position + direction * along, radius)
}
// ANCHOR_END: cone_sphere

// ANCHOR: cone_depth_bounds
/// Exercise 2. Depth along the view axis v = −z is linear, so its extremes
/// over the cone are at the apex or on the cap. Over the cap's directions
/// (within θ of the axis) the largest v·u is 1 if v is within θ of the
/// axis, else cos(φ − θ), φ the angle from the axis to v; the smallest is
/// the same for −v.
pub fn cone_depth_bounds(
    proj: DMat4,
    near: f64,
    apex: DVec3,
    axis: DVec3,
    range: f64,
    half_angle: f64,
) -> Option<(f32, f32)> {
    let range = range * (1.0 + SPHERE_MARGIN);
    let v = DVec3::NEG_Z; // view distance d = v·p
    let reach = |v: DVec3| {
        let phi = v.dot(axis).clamp(-1.0, 1.0).acos();
        // THE MISTAKE: cos(φ − θ) even where v lies within θ of the axis,
        // where the cone reaches a full range along v.
        (phi - half_angle).cos().max(0.0) * range
    };
    let d = v.dot(apex);
    let (d_near, d_far) = (d - reach(-v), d + reach(v));
    if d_far <= near {
        return None;
    }
    let (a, b) = (
        window_depth(proj, d_near.max(near)),
        window_depth(proj, d_far),
    );
    let zmin = (a.min(b) - DEPTH_MARGIN).clamp(0.0, 1.0);
    let zmax = (a.max(b) + DEPTH_MARGIN).clamp(0.0, 1.0);
    Some((zmin as f32, zmax as f32))
}
// ANCHOR_END: cone_depth_bounds
