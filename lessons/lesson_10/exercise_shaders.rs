//! Lesson 10's shader modules: the lesson's own, and one per exercise that
//! leaves out the lesson's implementation of the function the exercise
//! asks for, so that no exercise can be answered by calling it.
//!
//! All three are lesson 03's exercises and `pcf.wgsl`, `soft.wgsl` and
//! `peers.wgsl`. The lesson's module has no student code. Exercise 1's
//! module has the student's `exercises.wgsl`, soft.wgsl without its
//! `blocker_search` (the listing between its anchors is blanked), and
//! `exercise_hooks.wgsl`'s `blocker_search`, which calls the student's
//! function: `pcss` runs the student's search under its own name.
//! Exercise 2's likewise without `filter_radius`. An exercise that calls
//! the lesson's function then calls itself, and the module does not
//! compile: the grader fails that exercise with the compiler's line.

use common::gpu::Gpu;
use common::Result;

use crate::lesson_01::shadow_map;

/// Which module: the lesson's variants, or one exercise's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Module {
    Lesson,
    BlockerSearch,
    Penumbra,
}

const SOFT: &str = include_str!("../../shaders/lesson_10/soft.wgsl");
const HOOKS: &str = include_str!("../../shaders/lesson_10/exercise_hooks.wgsl");

impl Module {
    pub const ALL: [Module; 3] = [Module::Lesson, Module::BlockerSearch, Module::Penumbra];

    /// The anchor of `soft.wgsl` this module leaves out and of
    /// `exercise_hooks.wgsl` it takes (none for the lesson's).
    fn anchor(self) -> Option<&'static str> {
        match self {
            Module::Lesson => None,
            Module::BlockerSearch => Some("blocker_search"),
            Module::Penumbra => Some("penumbra"),
        }
    }

    /// The module, compiled: an error names its file and line.
    pub fn compile(self, gpu: &Gpu) -> Result<wgpu::ShaderModule> {
        let cut = self.anchor();
        let soft = match cut {
            Some(a) => anchored(SOFT, a, false),
            None => SOFT.to_string(),
        };
        let lesson_03 = crate::exercises_wgsl_path("lesson_03");
        let exercises = crate::exercises_wgsl_path("lesson_10");
        let mut files = vec![
            (
                lesson_03.as_str(),
                crate::exercise!(lesson_03::EXERCISES_WGSL),
            ),
            (
                "shaders/lesson_03/pcf.wgsl",
                include_str!("../../shaders/lesson_03/pcf.wgsl"),
            ),
            ("shaders/lesson_10/soft.wgsl", soft.as_str()),
        ];
        let hooks = cut.map(|a| anchored(HOOKS, a, true));
        if let Some(hooks) = &hooks {
            files.push((
                exercises.as_str(),
                crate::exercise!(lesson_10::EXERCISES_WGSL),
            ));
            files.push(("shaders/lesson_10/exercise_hooks.wgsl", hooks.as_str()));
        }
        files.push((
            "shaders/lesson_10/peers.wgsl",
            include_str!("../../shaders/lesson_10/peers.wgsl"),
        ));
        let label = format!("lesson_10 {self:?}");
        shadow_map::shader_module_from_files(gpu, &label, &files)
    }
}

/// `text` with only the lines between `// ANCHOR: name` and its end kept
/// (`keep`), or with only those left out: the others blank, so that a line
/// keeps its number.
pub fn anchored(text: &str, name: &str, keep: bool) -> String {
    let (start, end) = (
        format!("// ANCHOR: {name}"),
        format!("// ANCHOR_END: {name}"),
    );
    let mut inside = false;
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let t = line.trim();
        let marker = t == start || t == end;
        if t == start {
            inside = true;
        }
        if !marker && inside == keep {
            out += line;
        }
        out.push('\n');
        if t == end {
            inside = false;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each exercise's module leaves the lesson's function out, and its
    /// hooks give the name to the student's.
    #[test]
    fn the_exercise_modules_leave_the_lessons_function_out() {
        for (cut, f) in [
            ("blocker_search", "fn blocker_search("),
            ("penumbra", "fn filter_radius("),
        ] {
            assert!(SOFT.contains(f));
            let soft = anchored(SOFT, cut, false);
            assert!(!soft.contains(f), "{cut}");
            assert_eq!(soft.lines().count(), SOFT.lines().count());
            let hook = anchored(HOOKS, cut, true);
            assert!(hook.contains(f), "{cut}");
        }
    }
}
