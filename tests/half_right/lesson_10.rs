//! Lesson 10's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer in
//! `lesson_10.wgsl` is the reference solution with the mistake its
//! comment names, and the grader must fail it with that likely cause.
//! The same items as `lessons/lesson_10/exercises.rs`; built with
//! `--features chapter_copies`.

/// `exercise_off_axis_radius(s, d_r, d_b)` and
/// `exercise_footprint(s, d_r, d_b)`, half right.
pub const EXERCISES_WGSL: &str = include_str!("lesson_10.wgsl");
