//! Lesson 02's exercises answered HALF RIGHT, as a student who missed
//! one case might (CI's `grade --check-half-right`): each answer below
//! is the reference solution with the mistake its comment names, and
//! the grader must fail it with that likely cause. The same items as
//! `lessons/lesson_02/exercises.rs`; built with `--features chapter_copies`.

/// The WGSL of the exercises: `slope_bias(world, n)` (exercise 1) and
/// `grazing_bias(world, n)` (exercise 2), solved.
pub const EXERCISES_WGSL: &str = include_str!("lesson_02.wgsl");
