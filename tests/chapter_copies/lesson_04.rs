//! Lesson 04's exercises answered with the nearest code the chapter prints
//! (`--features chapter_copies`, for `grade --check-copies`): each must
//! fail its grade, or the chapter hands out the answer.

use common::glam::DVec3;

/// Exercise 1, copied: the lesson's sphere test, on the sphere around the box.
pub fn faces_touched(centre: DVec3, half: DVec3) -> [bool; 6] {
    // Chapter 04's listing `culling.rs:sphere_in_face`, called as printed:
    // the call of the lesson's own function, in both passes of the check.
    std::array::from_fn(|face| super::culling::sphere_touches_face(centre, half.length(), face))
}

/// `exercise_cube_texel(v)`, copied from the chapter.
pub const EXERCISES_WGSL: &str = include_str!("lesson_04.wgsl");
