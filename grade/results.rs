//! What grading gives: each check's outcome, each exercise's grade (the
//! grader's JSON), the failure each of CI's checks needs, and the lines a
//! student reads. Shared by the `grade` binary and `tests/exercises.rs`.

use serde::Serialize;

use crate::figures::fmt;

/// How a run of the exercise ended (the JSON's `status`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStatus {
    /// It ran to its end: graded on its figures, or refused by the lesson.
    Finished,
    /// Stopped at the time limit (`grade --time-limit`), or by the
    /// lesson's GPU watchdog: a loop that never ends?
    DidNotFinish,
    /// A panic, a signal, or out of memory.
    Crashed,
}

/// The failure one of CI's checks needs from every exercise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Proof {
    /// Any check failed (`--check-copies`).
    Failed,
    /// A check failed with a hint naming the likely cause
    /// (`--check-starters`, `--check-half-right`).
    FailedWithCause,
}

impl Proof {
    /// The scene of the first check that failed as this proof needs: none
    /// until `checks` hold that failure.
    pub fn failed_on(self, checks: &[CheckResult]) -> Option<&str> {
        checks
            .iter()
            .find(|c| !c.passed && (self == Proof::Failed || c.hinted))
            .map(|c| c.scene.as_str())
    }

    /// What the proof needs, for the `skip` lines.
    pub fn needs(self) -> &'static str {
        match self {
            Proof::Failed => "a failed check",
            Proof::FailedWithCause => "a failed check with its likely cause",
        }
    }
}

/// One check's outcome (the JSON's `checks`).
#[derive(Clone, Debug, Serialize)]
pub struct CheckResult {
    pub scene: String,
    pub hidden: bool,
    pub metric: String,
    pub measured: Option<f64>,
    pub target: Option<f64>,
    /// `"<= 0.42 (slope_hw 0.32 + 0.1)"`.
    pub target_text: String,
    pub passed: bool,
    /// The likely cause, when it failed.
    pub feedback: Option<String>,
    /// Whether `feedback` came from one of the exercise's hints.
    pub hinted: bool,
    pub diff_image: Option<String>,
    /// How the run on this scene ended.
    pub status: RunStatus,
}

/// One exercise's grade: the grader's JSON has one per exercise.
#[derive(Clone, Debug, Serialize)]
pub struct ExerciseResult {
    pub lesson: String,
    pub exercise: String,
    pub title: String,
    pub passed: bool,
    /// `did_not_finish` or `crashed` when a run of it did, else `finished`.
    pub status: RunStatus,
    /// The deciding check: the first that failed, else the first.
    pub metric: String,
    pub scene: String,
    pub measured: Option<f64>,
    pub target: Option<f64>,
    /// One line: pass, or the likely cause of the failure.
    pub feedback: String,
    pub diff_image: Option<String>,
    /// The chapter section to reread.
    pub section: String,
    pub task: String,
    pub checks: Vec<CheckResult>,
    /// Scenes not graded, each with why: hidden scenes the lesson itself
    /// refuses (its own line), and, under a `--check-*` flag, the scenes
    /// after the one where the exercise failed as the check needs.
    pub skipped_scenes: Vec<String>,
    /// The adapter and backend the runs used (`"llvmpipe (LLVM 15.0.6,
    /// 256 bits)"`, `"Vulkan"`); empty when nothing ran.
    pub adapter: String,
    pub backend: String,
    /// The snapshot text (mask, error figures, counters) on the spec's
    /// scenes; `tests/exercises.rs` compares it with the one recorded from
    /// the reference solution on the same backend.
    #[serde(skip)]
    pub snapshot: String,
}

/// The lines a student reads for one exercise.
pub fn describe(r: &ExerciseResult) -> String {
    let verdict = match (r.passed, r.status) {
        (true, _) => "PASS",
        (false, RunStatus::DidNotFinish) => "FAIL (did not finish)",
        (false, RunStatus::Crashed) => "FAIL (crashed)",
        (false, RunStatus::Finished) => "FAIL",
    };
    let mut s = format!("{verdict} {} {}: {}\n", r.lesson, r.exercise, r.title);
    if !r.passed {
        s += &format!("     task: {}\n", r.task);
    }
    for c in &r.checks {
        let mark = if c.passed { "ok  " } else { "FAIL" };
        let hidden = if c.hidden { " (hidden scene)" } else { "" };
        s += &format!(
            "  {mark} {}{hidden}: {} {} (target {})\n",
            c.scene,
            c.metric,
            c.measured.map_or("not measured".into(), fmt),
            c.target_text
        );
        if let Some(f) = &c.feedback {
            s += &format!("       likely cause: {f}\n");
        }
        if let (false, Some(d)) = (c.passed, &c.diff_image) {
            s += &format!("       diff image (red: false shadow, green: false lit): {d}\n");
        }
    }
    for k in &r.skipped_scenes {
        s += &format!("  skip {k}\n");
    }
    if !r.passed {
        s += &format!("     reread: {}\n", r.section);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(passed: bool, hinted: bool) -> CheckResult {
        CheckResult {
            scene: "default".into(),
            hidden: false,
            metric: "misclassified_pct".into(),
            measured: Some(1.0),
            target: Some(0.5),
            target_text: "<= 0.5".into(),
            passed,
            feedback: hinted.then(|| "a cause".into()),
            hinted,
            diff_image: None,
            status: RunStatus::Finished,
        }
    }

    /// A copy check stops at any failure; a starter's or a half-right
    /// answer's only at one whose hint names the cause; passes prove
    /// nothing.
    #[test]
    fn each_check_stops_at_the_failure_it_needs() {
        let passed = [check(true, false), check(true, false)];
        let unhinted = [check(true, false), check(false, false)];
        let hinted = [check(false, false), check(false, true)];
        for (checks, failed, with_cause) in [
            (&passed[..], false, false),
            (&unhinted[..], true, false),
            (&hinted[..], true, true),
            (&[][..], false, false),
        ] {
            assert_eq!(Proof::Failed.failed_on(checks).is_some(), failed);
            assert_eq!(
                Proof::FailedWithCause.failed_on(checks).is_some(),
                with_cause
            );
        }
    }
}
