//! `workbook`: each lesson's technique, one module per lesson folder.
//!
//! `lessons/lesson_NN/` holds the lesson's binary (`main.rs`: its variants
//! and its `Lesson` impl) and the technique's own modules, declared in its
//! `mod.rs`. A later lesson uses an earlier lesson's technique from here
//! (lesson 06 uses `lesson_05::silhouette`), never a copy of it, and never
//! the other way round (`tests/layout.rs` checks). What no chapter teaches
//! (the GPU context, scenes, render targets, the runners, measurement) is
//! in the `common` crate.

pub mod lesson_01;
pub mod lesson_02;
pub mod lesson_03;
pub mod lesson_04;
pub mod lesson_05;
pub mod lesson_06;
pub mod lesson_07;
pub mod lesson_08;
pub mod lesson_09;
pub mod lesson_10;

/// The file that a chapter's `exercises::EXERCISES_WGSL` is read from in
/// this build (the starter, the solution, or CI's chapter copy): a WGSL
/// error in it names this file and its own line.
pub fn exercises_wgsl_path(lesson: &str) -> String {
    if cfg!(feature = "solutions") {
        format!("solutions/{lesson}.wgsl")
    } else if cfg!(feature = "chapter_copies") {
        format!("tests/chapter_copies/{lesson}.wgsl")
    } else {
        format!("shaders/{lesson}/exercises.wgsl")
    }
}
