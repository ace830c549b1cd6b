//! How an exercise's run ended when it gave no report: stopped at the
//! time limit, ended by the lesson's GPU watchdog, crashed, or refused by
//! the lesson; the student's line for each, naming the file to fix.
//! Shared by the `grade` binary and `tests/exercises.rs`, with `grading`.

use crate::figures::fmt;
use crate::results::{CheckResult, RunStatus};
use crate::runner::RunError;
use crate::spec::{Check, Exercise};

/// The file a student fixes for `task` (`"write slope_bias() in
/// shaders/lesson_02/exercises.wgsl"`): the path it names, else the
/// lesson's `exercises.rs`.
pub fn file_to_fix(task: &str, lesson: &str) -> String {
    task.split_whitespace()
        .map(|w| w.trim_matches(|c: char| matches!(c, '`' | ',' | ';' | '(' | ')' | ':')))
        .map(|w| w.trim_end_matches('.'))
        .find(|w| {
            (w.starts_with("lessons/") || w.starts_with("shaders/"))
                && (w.ends_with(".rs") || w.ends_with(".wgsl"))
        })
        .map_or_else(|| format!("lessons/{lesson}/exercises.rs"), str::to_string)
}

/// Why a run on `label` gave no report, in the student's words, and how
/// it ended.
pub fn why_not_run(
    e: &anyhow::Error,
    ex: &Exercise,
    lesson: &str,
    label: &str,
) -> (String, RunStatus) {
    let fix = file_to_fix(&ex.task, lesson);
    match e.downcast_ref::<RunError>() {
        Some(RunError::TimedOut { seconds, .. }) => (
            format!(
                "did not finish within {} s on {label}: a loop in your answer that never ends? \
                 (file to fix: {fix})",
                fmt(*seconds)
            ),
            RunStatus::DidNotFinish,
        ),
        Some(RunError::GpuHung { line, .. }) => (
            format!("did not finish on {label}: {line} (file to fix: {fix})"),
            RunStatus::DidNotFinish,
        ),
        Some(RunError::Crashed { how, line, .. }) => (
            format!("crashed on {label} ({how}): {line}; file to fix: {fix}"),
            RunStatus::Crashed,
        ),
        _ => (
            format!("{} did not run on {label}: {e:#}", ex.variant),
            RunStatus::Finished,
        ),
    }
}

/// A failed run's result for every check on that scene.
pub fn failed_run(
    checks: &[&Check],
    label: &str,
    hidden: bool,
    why: &str,
    status: RunStatus,
) -> Vec<CheckResult> {
    checks
        .iter()
        .map(|c| CheckResult {
            scene: label.to_string(),
            hidden,
            metric: c.metric.clone(),
            measured: None,
            target: None,
            target_text: "(not run)".into(),
            passed: false,
            feedback: Some(why.to_string()),
            hinted: false,
            diff_image: None,
            status,
        })
        .collect()
}
