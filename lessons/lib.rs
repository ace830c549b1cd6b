//! `workbook`: each lesson's technique, one module per lesson folder.
//!
//! `lessons/lesson_NN/` holds the lesson's binary (`main.rs`: its variants
//! and its `Lesson` impl) and the technique's own modules, declared in its
//! `mod.rs`. A later lesson uses an earlier lesson's technique from here
//! (lesson 06 uses `lesson_05::silhouette`), never a copy of it, and never
//! the other way round (`tests/layout/` checks). What no chapter teaches
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

/// The environment variable that picks a run's exercise set:
/// `starter`, `solutions`, `chapter_copies` or `half_right` ([`ExerciseSet`]).
pub const EXERCISES_ENV: &str = "WORKBOOK_EXERCISES";

/// Which answers a chapter's exercises run with. Every build holds the
/// starter code; `--features solutions` adds the reference solutions and
/// `--features chapter_copies` (CI) the chapters' copies, so that one
/// build grades all three (`grade --check-starters`, `--check-copies`)
/// without compiling the lessons again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExerciseSet {
    /// `lessons/lesson_NN/exercises.rs` and `shaders/lesson_NN/exercises.wgsl`:
    /// the student's.
    Starter,
    /// `solutions/lesson_NN.rs` and `.wgsl`.
    Solutions,
    /// `tests/chapter_copies/lesson_NN.rs` and `.wgsl`.
    ChapterCopies,
    /// `tests/half_right/lesson_NN.rs` and `.wgsl`: each exercise answered
    /// with a mistake a student is likely to make, which `grade
    /// --check-half-right` must see fail, each with its likely cause. Built
    /// with `--features chapter_copies`, beside the chapters' copies.
    HalfRight,
}

impl ExerciseSet {
    /// The set's name, as [`EXERCISES_ENV`] takes it.
    pub fn name(self) -> &'static str {
        match self {
            ExerciseSet::Starter => "starter",
            ExerciseSet::Solutions => "solutions",
            ExerciseSet::ChapterCopies => "chapter_copies",
            ExerciseSet::HalfRight => "half_right",
        }
    }

    /// Whether this build holds the set.
    pub fn built(self) -> bool {
        match self {
            ExerciseSet::Starter => true,
            ExerciseSet::Solutions => cfg!(feature = "solutions"),
            ExerciseSet::ChapterCopies | ExerciseSet::HalfRight => {
                cfg!(feature = "chapter_copies")
            }
        }
    }

    /// The build's own set: the reference solutions where it holds them,
    /// else the student's code.
    pub fn default_for_build() -> ExerciseSet {
        if cfg!(feature = "solutions") {
            ExerciseSet::Solutions
        } else {
            ExerciseSet::Starter
        }
    }

    /// The set [`EXERCISES_ENV`] names (the build's own where it is unset),
    /// or one line saying what is wrong with it.
    pub fn from_env() -> Result<ExerciseSet, String> {
        let Some(v) = std::env::var_os(EXERCISES_ENV) else {
            return Ok(ExerciseSet::default_for_build());
        };
        let v = v.to_string_lossy();
        let set = [
            ExerciseSet::Starter,
            ExerciseSet::Solutions,
            ExerciseSet::ChapterCopies,
            ExerciseSet::HalfRight,
        ]
        .into_iter()
        .find(|s| s.name() == v)
        .ok_or_else(|| {
            format!("{EXERCISES_ENV}={v}: not an exercise set (starter, solutions, chapter_copies, half_right)")
        })?;
        if !set.built() {
            return Err(format!(
                "{EXERCISES_ENV}={v}: this build does not hold that set; build with --features {}",
                if set == ExerciseSet::HalfRight {
                    "chapter_copies"
                } else {
                    &v
                }
            ));
        }
        Ok(set)
    }
}

/// The exercise set this process runs ([`ExerciseSet::from_env`], read
/// once; a lesson's `main` has checked it, [`lesson_main`]).
pub fn exercise_set() -> ExerciseSet {
    static SET: std::sync::OnceLock<ExerciseSet> = std::sync::OnceLock::new();
    *SET.get_or_init(|| {
        ExerciseSet::from_env().unwrap_or_else(|_| ExerciseSet::default_for_build())
    })
}

/// A chapter's exercise, from the set this run uses: `exercise!(lesson_05::
/// volume_can_matter)` is the function (or constant) of that name in
/// `lesson_05::exercises`, `::solutions`, `::chapter_copies` or
/// `::half_right`; with
/// arguments, `exercise!(lesson_05::volume_can_matter(a, b))` calls it.
#[macro_export]
macro_rules! exercise {
    ($lesson:ident :: $($item:tt)*) => {
        match $crate::exercise_set() {
            #[cfg(feature = "solutions")]
            $crate::ExerciseSet::Solutions => $crate::$lesson::solutions::$($item)*,
            #[cfg(feature = "chapter_copies")]
            $crate::ExerciseSet::ChapterCopies => $crate::$lesson::chapter_copies::$($item)*,
            #[cfg(feature = "chapter_copies")]
            $crate::ExerciseSet::HalfRight => $crate::$lesson::half_right::$($item)*,
            _ => $crate::$lesson::exercises::$($item)*,
        }
    };
}

/// A lesson binary's `main`: checks [`EXERCISES_ENV`] (one line and exit
/// code 2 if it names no set of this build), then runs the lesson.
pub fn lesson_main<L: common::run::instruments::Instruments>() -> std::process::ExitCode {
    // In a web page (the web build): the window on the page's canvas.
    #[cfg(target_arch = "wasm32")]
    {
        common::run::web::start::<L>();
        std::process::ExitCode::SUCCESS
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        if let Err(e) = ExerciseSet::from_env() {
            eprintln!("error: {}: {e}", L::NAME);
            return std::process::ExitCode::from(2);
        }
        common::run::app::main::<L>()
    }
}

/// The file that a chapter's `EXERCISES_WGSL` is read from in this run
/// (the starter, the solution, or CI's chapter copy): a WGSL error in it
/// names this file and its own line.
pub fn exercises_wgsl_path(lesson: &str) -> String {
    match exercise_set() {
        ExerciseSet::Solutions => format!("solutions/{lesson}.wgsl"),
        ExerciseSet::ChapterCopies => format!("tests/chapter_copies/{lesson}.wgsl"),
        ExerciseSet::HalfRight => format!("tests/half_right/{lesson}.wgsl"),
        ExerciseSet::Starter => format!("shaders/{lesson}/exercises.wgsl"),
    }
}
