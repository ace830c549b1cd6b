//! Lesson 04's exercises, the reference solutions
//! (`lessons/lesson_04/exercises.rs` is the starter).

use common::glam::DVec3;

// ANCHOR: cull_faces
/// Which of the six cube faces (+X, −X, +Y, −Y, +Z, −Z) a box around
/// `centre` (relative to the light) of half extents `half` can touch.
pub fn faces_touched(centre: DVec3, half: DVec3) -> [bool; 6] {
    let (c, h) = (centre.to_array(), half.to_array());
    std::array::from_fn(|face| {
        let (axis, sign) = (face / 2, if face % 2 == 0 { 1.0 } else { -1.0 });
        // The box's largest distance along the face's axis...
        let m = sign * c[axis] + h[axis];
        // ... against the plane (1, ∓1): the corner farthest along each
        // normal is m − (|c_o| − h_o); behind it when that is negative.
        let inside = |o: usize| m - (c[o].abs() - h[o]) >= 0.0;
        inside((axis + 1) % 3) && inside((axis + 2) % 3)
    })
}
// ANCHOR_END: cull_faces

/// `exercise_cube_texel(v)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_04.wgsl");
