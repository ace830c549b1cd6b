//! Lesson 03's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_03/exercises.rs`; built with `--features chapter_copies`.

/// `exercise_pcf_kernel(s, radius, gradient)` and
/// `exercise_world_disk(s, world, pixel, radius_m, gradient)`, solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_03.wgsl");
