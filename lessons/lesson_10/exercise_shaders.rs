//! Lesson 10's shader modules: the lesson's own, and one per exercise, in
//! which PCSS places its taps where the student's function says.
//!
//! All three are lesson 03's exercises and `pcf.wgsl`, `soft.wgsl` and
//! `peers.wgsl`. The lesson's module has no student code. An exercise's
//! module has the student's `exercises.wgsl`, soft.wgsl without its `pcss`
//! (the listing between its anchors is blanked), and two parts of
//! `exercise_hooks.wgsl`: `shaped_pcss`, a `pcss` of the same three steps
//! whose search and filter disks are a matrix `footprint_shape(s, d_r,
//! d_b)`, and the exercise's own `footprint_shape`, which calls the
//! student's function: a round disk of `exercise_off_axis_radius`, or the
//! matrix of `exercise_footprint`. Neither is in the lesson, which ignores
//! the footprint's stretch off the spot's axis (the chapter's "The
//! penumbra's width"); answered with the lesson's `filter_radius`, either
//! runs exactly as `pcss`.

use common::gpu::Gpu;
use common::Result;

use crate::lesson_01::shadow_map;

/// Which module: the lesson's variants, or one exercise's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Module {
    Lesson,
    OffAxisRadius,
    Footprint,
}

const SOFT: &str = include_str!("../../shaders/lesson_10/soft.wgsl");
const HOOKS: &str = include_str!("../../shaders/lesson_10/exercise_hooks.wgsl");

/// The anchor of `soft.wgsl` an exercise's module leaves out, and the one
/// of `exercise_hooks.wgsl` every exercise's module takes.
const CUT: &str = "pcss";
const SHAPED: &str = "shaped_pcss";

impl Module {
    pub const ALL: [Module; 3] = [Module::Lesson, Module::OffAxisRadius, Module::Footprint];

    /// The exercise's own anchor of `exercise_hooks.wgsl` (none for the
    /// lesson's module).
    fn anchor(self) -> Option<&'static str> {
        match self {
            Module::Lesson => None,
            Module::OffAxisRadius => Some("off_axis_radius"),
            Module::Footprint => Some("footprint"),
        }
    }

    /// The module, compiled: an error names its file and line.
    pub fn compile(self, gpu: &Gpu) -> Result<wgpu::ShaderModule> {
        let own = self.anchor();
        let soft = match own {
            Some(_) => anchored(SOFT, &[CUT], false),
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
        let hooks = own.map(|a| anchored(HOOKS, &[SHAPED, a], true));
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
/// (`keep`), for any of `names`, or with only those left out: the others
/// blank, so that a line keeps its number.
pub fn anchored(text: &str, names: &[&str], keep: bool) -> String {
    let marker = |kind: &str, t: &str| {
        t.strip_prefix(kind)
            .is_some_and(|name| names.contains(&name))
    };
    let mut inside = false;
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let t = line.trim();
        let (start, end) = (marker("// ANCHOR: ", t), marker("// ANCHOR_END: ", t));
        if start {
            inside = true;
        }
        if !(start || end) && inside == keep {
            out += line;
        }
        out.push('\n');
        if end {
            inside = false;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An exercise's module leaves the lesson's pcss out, and its hooks
    /// give the name to a pcss that calls the exercise's footprint.
    #[test]
    fn the_exercise_modules_replace_the_lessons_pcss() {
        let f = "fn pcss(";
        assert!(SOFT.contains(f));
        let soft = anchored(SOFT, &[CUT], false);
        assert!(!soft.contains(f));
        assert!(soft.contains("fn filter_radius("));
        assert_eq!(soft.lines().count(), SOFT.lines().count());
        for (m, student) in [
            (Module::OffAxisRadius, "exercise_off_axis_radius("),
            (Module::Footprint, "exercise_footprint("),
        ] {
            let a = m.anchor().expect("an exercise's anchor");
            let hook = anchored(HOOKS, &[SHAPED, a], true);
            assert!(hook.contains(f), "{m:?}");
            assert_eq!(hook.matches("fn footprint_shape(").count(), 1, "{m:?}");
            assert!(hook.contains(student), "{m:?}");
        }
    }
}
