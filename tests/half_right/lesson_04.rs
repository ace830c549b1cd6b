//! Lesson 04's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_04/exercises.rs`; built with `--features chapter_copies`.

use common::glam::DVec3;

// ANCHOR: cull_faces
/// Which of the six cube faces (+X, −X, +Y, −Y, +Z, −Z) a box around
/// `centre` (relative to the light) of half extents `half` can touch.
pub fn faces_touched(centre: DVec3, half: DVec3) -> [bool; 6] {
    let (c, h) = (centre.to_array(), half.to_array());
    std::array::from_fn(|face| {
        let (axis, sign) = (face / 2, if face % 2 == 0 { 1.0 } else { -1.0 });
        // The box's largest distance along the face's axis...
        // THE MISTAKE: the box's centre tested against the face's planes,
        // its half extents forgotten: a box that straddles a plane is dropped.
        let m = sign * c[axis];
        // ... against the plane (1, ∓1): the corner farthest along each
        // normal is m − (|c_o| − h_o); behind it when that is negative.
        let inside = |o: usize| m - c[o].abs() >= 0.0 && h[o] >= 0.0;
        inside((axis + 1) % 3) && inside((axis + 2) % 3)
    })
}
// ANCHOR_END: cull_faces

/// `exercise_cube_texel(v)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_04.wgsl");
