//! Lesson 04's exercises, the reference solutions
//! (`lessons/lesson_04/exercises.rs` is the starter).

use common::glam::DVec3;

// ANCHOR: cull_faces
/// Which of the six cube faces (+X, −X, +Y, −Y, +Z, −Z) a sphere around
/// `centre` (relative to the light) of `radius` can touch.
pub fn faces_touched(centre: DVec3, radius: f64) -> [bool; 6] {
    let c = centre.to_array();
    std::array::from_fn(|face| {
        let (axis, sign) = (face / 2, if face % 2 == 0 { 1.0 } else { -1.0 });
        let m = sign * c[axis];
        let (a, b) = (c[(axis + 1) % 3], c[(axis + 2) % 3]);
        // Signed distances to the four side planes, all > -radius.
        (m - a.abs()) / 2f64.sqrt() > -radius && (m - b.abs()) / 2f64.sqrt() > -radius
    })
}
// ANCHOR_END: cull_faces

/// `exercise_cube_depth(v, d, near, far)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_04.wgsl");
