//! Nothing a student writes stops the grader: a lesson run that never
//! ends is stopped at the time limit, one that crashes is told from one
//! that refuses, and grading goes on with the next exercise.
//!
//! The lessons here are stand-ins: small shell scripts named `lesson_01`
//! ... `lesson_10` that sleep, panic, are killed or refuse, as a student's
//! answer might make the real lesson do. The runner finds lessons by their
//! folder; the grader takes that folder from `WORKBOOK_LESSON_BIN_DIR`.
//! Each test guards itself with its own limit, so a runner that stops
//! nothing fails here instead of hanging.

#![cfg(unix)]

use common::run::runner;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{mpsc, OnceLock};
use std::time::{Duration, Instant};

use runner::{RunArgs, RunError, Runner};

/// What each stand-in does, chosen by its own name and the variants it is
/// asked for (`$0 $*`).
const STAND_IN: &str = r#"#!/bin/sh
case "$(basename "$0") $*" in
  # The grader's run: chapter 05's first exercise loops, its second panics.
  "lesson_05 "*exercise_edges_in_view*) exec sleep 60 ;;
  "lesson_05 "*exercise_skip_casters*)
    echo "thread 'main' panicked at lessons/lesson_05/exercises.rs:42:5:" >&2
    echo "not yet implemented" >&2
    echo "note: run with RUST_BACKTRACE=1 environment variable to display a backtrace" >&2
    exit 101 ;;
  # Chapter 02: a shader loop the lesson's GPU watchdog ended.
  "lesson_02 "*exercise_slope_bias*)
    echo "error: lesson_02: the GPU did not finish a frame within 120 s (a shader loop that never ends? WORKBOOK_GPU_TIMEOUT_S sets the limit)" >&2
    exit 4 ;;
  # The runner's own cases.
  "lesson_01 "*) exec sleep 60 ;;
  "lesson_03 "*) kill -9 $$ ;;
  "lesson_04 "*)
    echo "thread 'main' panicked at lessons/lesson_04/exercises.rs:7:9:" >&2
    echo "index out of bounds: the len is 6 but the index is 6" >&2
    echo "stack backtrace:" >&2
    echo "   0: rust_begin_unwind" >&2
    exit 101 ;;
  "lesson_06 "*)
    echo "memory allocation of 68719476736 bytes failed" >&2
    kill -6 $$ ;;
  "lesson_07 "*)
    # Far more than a pipe holds, on both pipes, before its one line.
    head -c 3000000 /dev/zero | tr '\0' 'o'
    head -c 3000000 /dev/zero | tr '\0' 'e' >&2
    echo >&2
    echo "error: lesson_07: too chatty to render" >&2
    exit 1 ;;
  "lesson_08 "*)
    echo "error: lesson_08: the GPU did not finish a frame within 120 s (a shader loop that never ends? WORKBOOK_GPU_TIMEOUT_S sets the limit)" >&2
    exit 4 ;;
  *)
    echo "error: $(basename "$0"): this stand-in renders nothing" >&2
    exit 1 ;;
esac
"#;

/// The folder of stand-in lessons, written once before any test runs one
/// (a script written while another thread forks could not be executed).
fn stand_ins() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        use std::os::unix::fs::PermissionsExt;
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("grade_limits/bin");
        std::fs::create_dir_all(&dir).expect("stand-in folder");
        for n in 1..=10 {
            let path = dir.join(format!("lesson_{n:02}"));
            std::fs::write(&path, STAND_IN).expect("stand-in lesson");
            std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755))
                .expect("stand-in lesson mode");
        }
        dir
    })
}

/// Runs stand-in `lesson` with a time limit of `limit` seconds; the error
/// it ended with, and how long it took. Fails if the run itself outlasts
/// the limit by more than a few seconds.
fn run_stand_in(lesson: &'static str, limit: f64) -> (RunError, Duration) {
    let mut runner = Runner::in_dir(stand_ins().to_path_buf()).expect("stand-ins");
    runner.time_limit = Some(Duration::from_secs_f64(limit));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("grade_limits/out")
        .join(lesson);
    let (tx, rx) = mpsc::channel();
    let start = Instant::now();
    std::thread::spawn(move || {
        let args = RunArgs {
            lesson,
            scene: None,
            width: 64,
            height: 36,
            frames: 1,
            variants: &[],
            backend: None,
            adapter: Some("software"),
            warm_up_ms: Some(0.0),
            fragile: false,
            fragile_variants: &[],
        };
        let _ = tx.send(runner.run(&args, &out).map(|_| ()));
    });
    let guard = Duration::from_secs_f64(limit + 10.0);
    let result = rx
        .recv_timeout(guard)
        .unwrap_or_else(|_| panic!("{lesson}: the run did not return within {guard:?}"));
    let took = start.elapsed();
    let e = result.expect_err("a stand-in never reports");
    let e = e
        .downcast::<RunError>()
        .unwrap_or_else(|e| panic!("{lesson}: not a RunError: {e:#}"));
    (e, took)
}

#[test]
fn a_run_that_never_ends_is_stopped_at_the_limit() {
    let (e, took) = run_stand_in("lesson_01", 2.0);
    assert!(
        matches!(e, RunError::TimedOut { seconds, .. } if seconds == 2.0),
        "{e:?}"
    );
    assert!(took >= Duration::from_secs(2), "stopped early: {took:?}");
    assert!(took < Duration::from_secs(6), "stopped late: {took:?}");
    assert_eq!(
        e.to_string(),
        "lesson_01 on its default scene did not finish within 2 s, so it was stopped"
    );
}

#[test]
fn a_run_killed_by_a_signal_crashed() {
    let (e, _) = run_stand_in("lesson_03", 30.0);
    let RunError::Crashed { how, .. } = &e else {
        panic!("{e:?}")
    };
    assert!(how.contains("SIGKILL"), "{e}");
}

#[test]
fn a_panic_crashed_and_names_its_line() {
    let (e, took) = run_stand_in("lesson_04", 30.0);
    let RunError::Crashed { how, line, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(how, "panic");
    assert_eq!(
        line,
        "panicked at lessons/lesson_04/exercises.rs:7:9: \
         index out of bounds: the len is 6 but the index is 6"
    );
    // A crash is told at once, not at the time limit.
    assert!(took < Duration::from_secs(10), "{took:?}");
}

#[test]
fn running_out_of_memory_crashed() {
    let (e, _) = run_stand_in("lesson_06", 30.0);
    let RunError::Crashed { how, line, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(how, "out of memory");
    assert_eq!(line, "memory allocation of 68719476736 bytes failed");
}

#[test]
fn a_chatty_lesson_cannot_block_on_its_pipes() {
    // 3 MB on each pipe: unread, a pipe (64 KiB) would block it until the limit.
    let (e, _) = run_stand_in("lesson_07", 30.0);
    let RunError::Failed { line, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(line, "error: lesson_07: too chatty to render");
}

#[test]
fn the_lessons_gpu_watchdog_is_did_not_finish() {
    let (e, _) = run_stand_in("lesson_08", 30.0);
    let RunError::GpuHung { line, .. } = &e else {
        panic!("{e:?}")
    };
    assert!(line.contains("the GPU did not finish a frame"), "{line}");
}

#[test]
fn a_refusal_is_neither() {
    let (e, _) = run_stand_in("lesson_09", 30.0);
    let RunError::Failed { line, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(line, "error: lesson_09: this stand-in renders nothing");
    assert_eq!(
        e.to_string(),
        "lesson_09 on its default scene failed: error: lesson_09: this stand-in renders nothing"
    );
}

/// Runs the grader on the stand-ins; its exit code, stdout and stderr.
/// Fails if it does not return within `guard`.
fn grade(
    name: &str,
    args: &[&str],
    env: &[(&str, &str)],
    guard: Duration,
) -> (Option<i32>, String, String) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("grade_limits")
        .join(name);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_grade"));
    cmd.args(args)
        .arg("--out")
        .arg(&dir)
        .arg("--json")
        .arg(dir.join("grade.json"))
        .args(["--adapter", "software"])
        // Not under cargo: the grader then does not rebuild the lessons.
        .env_remove("CARGO")
        .env_remove("WORKBOOK_RUN_TIME_LIMIT")
        .env("WORKBOOK_LESSON_BIN_DIR", stand_ins())
        .envs(env.iter().copied())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("grade");
    let start = Instant::now();
    while child.try_wait().expect("grade").is_none() {
        if start.elapsed() > guard {
            let _ = child.kill();
            panic!("grade did not return within {guard:?}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().expect("grade");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn the_grader_goes_on_past_a_loop_and_a_crash() {
    let start = Instant::now();
    let (code, out, err) = grade(
        "grade",
        &["lesson_02", "lesson_05", "--time-limit", "3"],
        &[],
        Duration::from_secs(60),
    );
    let took = start.elapsed();
    assert_eq!(code, Some(1), "exit code\n{out}\n{err}");
    // The loop: stopped once, at the limit; its other scenes are not run.
    assert!(
        out.contains("FAIL (did not finish) lesson_05 exercise_edges_in_view"),
        "{out}"
    );
    assert!(
        out.contains(
            "did not finish within 3 s on default: a loop in your answer that never ends? \
             (file to fix: lessons/lesson_05/exercises.rs)"
        ),
        "{out}"
    );
    assert!(
        out.contains("not run: exercise_edges_in_view did not finish on default"),
        "{out}"
    );
    assert!(
        took < Duration::from_secs(20),
        "one limit, not one a scene: {took:?}"
    );
    // The panic, graded after it, with its line and its file.
    assert!(
        out.contains("FAIL (crashed) lesson_05 exercise_skip_casters"),
        "{out}"
    );
    assert!(
        out.contains(
            "crashed on default (panic): panicked at lessons/lesson_05/exercises.rs:42:5: \
             not yet implemented; file to fix: lessons/lesson_05/exercises.rs"
        ),
        "{out}"
    );
    // A shader loop the lesson's watchdog ended names the shader file.
    assert!(
        out.contains("FAIL (did not finish) lesson_02 exercise_slope_bias"),
        "{out}"
    );
    assert!(
        out.contains("(file to fix: shaders/lesson_02/exercises.wgsl)"),
        "{out}"
    );
    // An ordinary refusal stays one: neither did-not-finish nor crashed.
    assert!(
        out.contains("FAIL lesson_02 exercise_grazing_bias"),
        "{out}"
    );
    assert!(
        out.contains(
            "graded 4 exercises: 0 passed, 4 failed, of which 2 did not finish and 1 crashed"
        ),
        "{out}"
    );
    let json = Path::new(env!("CARGO_TARGET_TMPDIR")).join("grade_limits/grade/grade.json");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(json).expect("grade.json")).expect("JSON");
    let status: Vec<(&str, &str)> = json
        .as_array()
        .expect("one entry per exercise")
        .iter()
        .map(|r| {
            (
                r["exercise"].as_str().unwrap_or("?"),
                r["status"].as_str().unwrap_or("?"),
            )
        })
        .collect();
    assert_eq!(
        status,
        [
            ("exercise_slope_bias", "did_not_finish"),
            ("exercise_grazing_bias", "finished"),
            ("exercise_edges_in_view", "did_not_finish"),
            ("exercise_skip_casters", "crashed"),
        ]
    );
}

#[test]
fn a_bad_time_limit_is_one_line() {
    let guard = Duration::from_secs(30);
    let (code, _, err) = grade("bad", &["lesson_05", "--time-limit", "0"], &[], guard);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err.trim(),
        "error: grade: --time-limit 0: give a number of seconds above 0 (or WORKBOOK_RUN_TIME_LIMIT)"
    );
    let env = [("WORKBOOK_RUN_TIME_LIMIT", "soon")];
    let (code, _, err) = grade("bad", &["lesson_05"], &env, guard);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.lines().next().unwrap_or("").contains("'soon'"), "{err}");
}

#[test]
fn the_limit_may_come_from_the_environment() {
    let env = [("WORKBOOK_RUN_TIME_LIMIT", "2")];
    let args = ["lesson_05", "--exercise", "exercise_edges_in_view"];
    let (code, out, err) = grade("env", &args, &env, Duration::from_secs(30));
    assert_eq!(code, Some(1), "{out}\n{err}");
    assert!(
        out.contains("did not finish within 2 s on default"),
        "{out}"
    );
}
