//! Shared by the lesson tests: run a lesson binary headless, read its outputs.
//!
//! The tests drive the real command line (`--headless --out DIR ...`), so
//! what they check is what a learner runs. Its modules, whose items the
//! tests mostly call from here (`support::run_lesson`, `support::counter`):
//!
//! - [`paths`]: the repository's root, the tests' scratch and output
//!   folders, the committed scenes;
//! - [`gpu`]: the adapter the tests run on, and what happens without one;
//! - [`run`]: running a lesson binary, headless or watched;
//! - [`report`]: a report's variants, error figures and counters, and the
//!   snapshot lines made of them;
//! - [`images`]: visibility PNGs, their text masks, reference images;
//! - [`portable`]: which figures are compared within their bound on
//!   another adapter;
//! - [`tolerance`]: how a snapshot is compared with a new run's text;
//! - [`window`]: a lesson's window on a private display.

pub mod gpu;
pub mod images;
pub mod paths;
pub mod portable;
pub mod report;
pub mod run;
pub mod tolerance;
pub mod window;

pub use gpu::{gpu_required, measure_bounds, test_adapter, test_gpu};
pub use images::{ascii_levels, ascii_of, compare_with_reference, read_visibility};
pub use paths::{out_dir, root, scene_path, target_tmp};
pub use report::{
    bound, counter, counter_bound, counter_lines, error, error_line, misclassified, variant,
};
pub use run::{
    lesson_command, run_lesson, run_lesson_env, run_small, run_times_only, run_watched, shared_run,
    tiny_headless, LessonRun, SMALL, TIMED,
};
