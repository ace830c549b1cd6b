//! `grade`: grades the chapters' exercises against the exact reference.
//!
//! ```text
//! cargo run --release --bin grade                  # every chapter
//! cargo run --release --bin grade -- lesson_02     # one chapter
//! cargo run --release --bin grade -- lesson_02 --exercise exercise_slope_bias
//! cargo run --release --bin grade -- --scenes hidden/   # an instructor's scenes
//! ```
//!
//! Each exercise runs as its lesson's variant (`--variant exercise_...`) on
//! the scenes its chapter's `exercises.toml` names, and each check compares
//! a measured figure with its target. For each exercise it prints pass or
//! fail, the figures, the likely cause in words, the section to reread and
//! the diff image, and writes the results as JSON (`--json`, default
//! `target/grade/grade.json`). It grades on the student's GPU (`--adapter
//! any`, the default; CI pins `--adapter software`). A grade does not
//! depend on the GPU: every target is set against a variant of the lesson
//! measured in the same run on the same adapter (`slope_hw 0.32 + 0.1`),
//! so what one rasteriser draws differently at an edge, the target moves
//! with. Exit code: 0 when every exercise
//! passed, 1 when one failed, 2 when grading itself could not run.
//! Book: "Coursework: assigning and grading the exercises" (`book/src/coursework.md`).

use common::run::runner;

mod figures;
mod grading;
mod outcome;
mod results;
mod spec;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::Parser;
use workbook::ExerciseSet;

#[derive(Parser, Debug)]
#[command(about = "Grade the workbook's exercises against the exact reference")]
struct Cli {
    /// Chapters to grade (`lesson_02`); every chapter with exercises when none.
    lessons: Vec<String>,
    /// Grade only this exercise (`exercise_slope_bias`).
    #[arg(long)]
    exercise: Option<String>,
    /// A folder of hidden scene files: `DIR/*.toml` for every chapter,
    /// `DIR/lesson_NN/*.toml` for one. Every exercise's hidden checks run on
    /// them (under a `--check-*` flag, only until the exercise has failed).
    #[arg(long, value_name = "DIR")]
    scenes: Option<PathBuf>,
    /// Where to write the results as JSON (default `<out>/grade.json`).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Where the runs' images go (default `target/grade`).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// any (the default: your GPU, else a software rasteriser) | software
    /// (lavapipe/llvmpipe, as CI grades) | part of an adapter's name.
    /// WORKBOOK_ADAPTER is honoured when this is not given.
    #[arg(long)]
    adapter: Option<String>,
    /// vulkan | gl | metal | dx12 (WGPU_BACKEND is honoured too).
    #[arg(long)]
    backend: Option<String>,
    /// Seconds one lesson run (one exercise on one scene) may take; one
    /// still running then is stopped, and its exercise fails as "did not
    /// finish" (a loop that never ends?).
    #[arg(long, value_name = "SECONDS", env = "WORKBOOK_RUN_TIME_LIMIT",
          default_value_t = DEFAULT_TIME_LIMIT_S)]
    time_limit: f64,
    /// For maintainers (CI): grade the starter code and succeed only if
    /// EVERY exercise fails with a likely cause from its hints, which
    /// proves that each exercise's checks can fail and that one says why.
    /// An exercise is graded scene by scene only until a check fails with
    /// a hint; its other scenes are listed as `skip` (grade it without the
    /// flag to see them all).
    #[arg(long)]
    check_starters: bool,
    /// For maintainers (CI), built with `--features chapter_copies`: grade
    /// each exercise answered with the nearest code its chapter prints
    /// (`tests/chapter_copies/`), then again with the copies that call the
    /// lesson's own function, and succeed only if EVERY one fails, which
    /// proves that no chapter hands out its exercises' answers. An exercise
    /// is graded scene by scene only until a check fails; its other scenes
    /// are listed as `skip`.
    #[arg(long)]
    check_copies: bool,
    /// For maintainers (CI), built with `--features chapter_copies`: grade
    /// each exercise answered half right (`tests/half_right/`: the mistake
    /// a student is likely to make, the case its chapter warns about, left
    /// out), and succeed only if EVERY one fails with a likely cause from
    /// its hints, which proves that a graded scene holds that case. An
    /// exercise is graded scene by scene only until a check fails with a
    /// hint; its other scenes are listed as `skip`.
    #[arg(long)]
    check_half_right: bool,
}

/// `--time-limit`'s default, in seconds: some 20 times the slowest run of
/// a graded scene on lavapipe (lesson 09's default scene, 8 s on 2 shared
/// cores), and above the lessons' own GPU watchdog (120 s,
/// `common::gpu::watchdog`), whose line names a shader loop.
const DEFAULT_TIME_LIMIT_S: f64 = 180.0;

/// The variable that picks which chapter copy the lessons compile
/// (`common::gpu::render::chapter_copy_calls`): `calls`, or the pasted one.
const COPY_ENV: &str = "WORKBOOK_CHAPTER_COPY";

/// The workbook's root: where this binary was built from.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The chapters that have an `exercises.toml`, in order.
fn chapters_with_exercises(root: &Path) -> Result<Vec<String>> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(root.join("lessons")).context("cannot list lessons/")? {
        let p = e?.path();
        if p.join("exercises.toml").is_file() {
            v.push(
                p.file_name()
                    .unwrap_or_default()
                    .to_string_lossy()
                    .to_string(),
            );
        }
    }
    v.sort();
    Ok(v)
}

/// Under `cargo run`, rebuilds the lesson binaries with this build's
/// features first, so the grade is of the code as it is now.
fn rebuild_lessons() -> Result<()> {
    let Some(cargo) = std::env::var_os("CARGO") else {
        return Ok(());
    };
    let mut cmd = std::process::Command::new(cargo);
    cmd.args(["build", "--release", "--bins", "--quiet"])
        .current_dir(root());
    let features: Vec<&str> = [
        (cfg!(feature = "solutions"), "solutions"),
        (cfg!(feature = "chapter_copies"), "chapter_copies"),
    ]
    .into_iter()
    .filter_map(|(on, f)| on.then_some(f))
    .collect();
    if !features.is_empty() {
        cmd.args(["--features", &features.join(",")]);
    }
    // cargo's messages pass through as they are, and are read for the files
    // that have errors.
    use std::io::{BufRead, IsTerminal};
    if std::io::stderr().is_terminal() {
        cmd.args(["--color", "always"]);
    }
    let mut child = cmd
        .stderr(std::process::Stdio::piped())
        .spawn()
        .context("cannot run cargo to build the lessons")?;
    let mut files: Vec<String> = Vec::new();
    if let Some(err) = child.stderr.take() {
        let mut in_error = false;
        for line in std::io::BufReader::new(err).lines() {
            let line = line.context("cannot read cargo's output")?;
            eprintln!("{line}");
            let plain = strip_ansi(&line);
            let t = plain.trim_start();
            if t.starts_with("error") {
                in_error = true;
            } else if t.starts_with("warning") {
                in_error = false;
            } else if let Some(at) = t.strip_prefix("--> ").filter(|_| in_error) {
                // `lessons/lesson_02/exercises.rs:14:5`: keep the file and line.
                let at: String = at.rsplitn(2, ':').last().unwrap_or(at).to_string();
                if !files.contains(&at) {
                    files.push(at);
                }
            }
        }
    }
    let status = child.wait().context("cannot wait for cargo")?;
    if !status.success() {
        bail!("{}", build_failure(&files));
    }
    Ok(())
}

/// The grader's line when the lessons do not build: which file to fix,
/// and that the lessons are one crate, so one exercise stops them all.
fn build_failure(files: &[String]) -> String {
    let all = "the lessons are one crate, so one exercise that does not compile \
               stops every lesson and the grader";
    if files.is_empty() {
        return format!(
            "the lessons do not build: fix the compile errors above, then grade again \
             ({all}: an error in any lessons/lesson_NN/exercises.rs counts)"
        );
    }
    format!(
        "the lessons do not build: fix {} (the errors above), then grade again ({all})",
        files.join(", ")
    )
}

/// A line of cargo's output without its colour codes.
fn strip_ansi(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            // ESC [ ... letter
            for d in chars.by_ref() {
                if d.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

fn run(cli: Cli) -> Result<bool> {
    if [cli.check_starters, cli.check_copies, cli.check_half_right]
        .iter()
        .filter(|&&c| c)
        .count()
        > 1
    {
        bail!("--check-starters, --check-copies and --check-half-right: one check a run");
    }
    // The exercise set the lessons run with (`WORKBOOK_EXERCISES`, read by
    // them): the checks name theirs; else the environment's, or the
    // build's own (the solutions where it holds them, else your code).
    let set = if cli.check_starters {
        ExerciseSet::Starter
    } else if cli.check_copies {
        if !ExerciseSet::ChapterCopies.built() {
            bail!(
                "--check-copies grades the chapters' copies: build with --features chapter_copies"
            );
        }
        ExerciseSet::ChapterCopies
    } else if cli.check_half_right {
        if !ExerciseSet::HalfRight.built() {
            bail!(
                "--check-half-right grades tests/half_right/: build with --features chapter_copies"
            );
        }
        ExerciseSet::HalfRight
    } else {
        ExerciseSet::from_env().map_err(anyhow::Error::msg)?
    };
    std::env::set_var(workbook::EXERCISES_ENV, set.name());
    let root = root();
    let lessons = if cli.lessons.is_empty() {
        chapters_with_exercises(&root)?
    } else {
        cli.lessons.clone()
    };
    for l in &lessons {
        if !spec::Spec::path(&root, l).is_file() {
            bail!("{l}: no such chapter with exercises (expected lessons/{l}/exercises.toml)");
        }
    }
    if let Some(d) = &cli.scenes {
        if !d.is_dir() {
            bail!("--scenes: {} is not a folder", d.display());
        }
    }
    if !(cli.time_limit > 0.0 && cli.time_limit < 1e9) {
        bail!(
            "--time-limit {}: give a number of seconds above 0 (or WORKBOOK_RUN_TIME_LIMIT)",
            cli.time_limit
        );
    }
    let adapter = match &cli.adapter {
        Some(a) => {
            common::gpu::AdapterChoice::parse(a)?;
            a.clone()
        }
        None => {
            let a = std::env::var("WORKBOOK_ADAPTER")
                .ok()
                .filter(|v| !v.trim().is_empty())
                .unwrap_or_else(|| "any".into());
            common::gpu::AdapterChoice::parse(&a).context("WORKBOOK_ADAPTER")?;
            a
        }
    };
    rebuild_lessons()?;
    let exe = std::env::current_exe().context("cannot find the grade binary's own path")?;
    // The lessons from another folder: tests/grade_limits.rs's stand-ins.
    let mut runner = match std::env::var_os("WORKBOOK_LESSON_BIN_DIR").filter(|d| !d.is_empty()) {
        Some(dir) => runner::Runner::in_dir(dir.into()).context("WORKBOOK_LESSON_BIN_DIR")?,
        None => runner::Runner::beside(&exe)?,
    };
    runner.time_limit = Some(std::time::Duration::from_secs_f64(cli.time_limit));
    let out = cli.out.clone().unwrap_or_else(|| root.join("target/grade"));
    // The copy check grades every exercise twice: answered with the
    // chapter's listing pasted, then with a call of the lesson's own
    // function (`WORKBOOK_CHAPTER_COPY=calls`, read by the lessons).
    let passes: &[Option<&str>] = if cli.check_copies {
        &[None, Some("calls")]
    } else {
        &[None]
    };
    let mut all = Vec::new();
    for &pass in passes {
        if let Some(kind) = pass {
            std::env::set_var(COPY_ENV, kind);
        }
        let out = pass.map_or(out.clone(), |kind| out.join(kind));
        let opts = grading::Options {
            root: root.clone(),
            out: out.clone(),
            adapter: adapter.clone(),
            backend: cli.backend.clone(),
            hidden: cli.scenes.clone(),
            hidden_only: false,
            fragile: false,
            stop_at: if cli.check_copies {
                Some(grading::Proof::Failed)
            } else if cli.check_starters || cli.check_half_right {
                Some(grading::Proof::FailedWithCause)
            } else {
                None
            },
        };
        for l in &lessons {
            let mut results = grading::grade_lesson(&runner, &opts, l, cli.exercise.as_deref())?;
            // No adapter: nothing can be graded; say what to install, once.
            if let Some(line) = results
                .iter()
                .flat_map(|r| &r.checks)
                .filter_map(|c| c.feedback.as_deref())
                .find_map(|f| f.find("no GPU adapter found").map(|at| &f[at..]))
            {
                bail!("{}", line.lines().next().unwrap_or(line));
            }
            for r in &mut results {
                // Beside the runs: what `tests/exercises.rs` compares with the
                // snapshot recorded from the reference solution.
                let dir = out.join(&r.lesson).join(&r.exercise);
                std::fs::create_dir_all(&dir)
                    .and_then(|()| std::fs::write(dir.join("snapshot.txt"), &r.snapshot))
                    .with_context(|| format!("cannot write {}", dir.display()))?;
                if let Some(kind) = pass {
                    r.exercise = format!("{} [{kind}]", r.exercise);
                }
                print!("{}", grading::describe(r));
            }
            all.extend(results);
        }
    }
    std::env::remove_var(COPY_ENV);
    if all.is_empty() {
        bail!(
            "--exercise {}: no such exercise in {}",
            cli.exercise.as_deref().unwrap_or("?"),
            lessons.join(", ")
        );
    }
    let json = cli.json.unwrap_or_else(|| out.join("grade.json"));
    if let Some(dir) = json.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let text = serde_json::to_string_pretty(&all)? + "\n";
    std::fs::write(&json, text).with_context(|| format!("cannot write {}", json.display()))?;
    let passed = all.iter().filter(|r| r.passed).count();
    let on = all
        .iter()
        .find(|r| !r.adapter.is_empty())
        .map_or("no adapter".into(), |r| {
            format!("{} ({})", r.adapter, r.backend)
        });
    println!(
        "graded {} exercises: {passed} passed, {} failed{} ({}; on {on}; results in {})",
        all.len(),
        all.len() - passed,
        stopped_count(&all),
        match set {
            ExerciseSet::Solutions => "reference solutions",
            ExerciseSet::ChapterCopies => "the chapters' own code, copied",
            ExerciseSet::HalfRight => "half-right answers",
            ExerciseSet::Starter => "your code",
        },
        json.display()
    );
    if cli.check_starters || cli.check_half_right {
        let what = if cli.check_starters {
            "starters"
        } else {
            "half-right answers"
        };
        let bad: Vec<String> = all
            .iter()
            .filter(|r| r.passed || !r.checks.iter().any(|c| c.hinted))
            .map(|r| format!("{} {}", r.lesson, r.exercise))
            .collect();
        if !bad.is_empty() {
            println!(
                "{what} check FAILED: these pass, or fail without a hint naming the cause: {}",
                bad.join(", ")
            );
            return Ok(false);
        }
        println!(
            "{what} check passed: all {} {what} fail, each with its likely cause",
            all.len()
        );
        return Ok(true);
    }
    if cli.check_copies {
        let bad: Vec<String> = all
            .iter()
            .filter(|r| r.passed)
            .map(|r| format!("{} {}", r.lesson, r.exercise))
            .collect();
        if !bad.is_empty() {
            println!(
                "copy check FAILED: the chapter's own code passes these exercises: {}",
                bad.join(", ")
            );
            return Ok(false);
        }
        println!(
            "copy check passed: all {} exercises fail when answered with the chapter's code, \
             pasted or calling the lesson's own functions ({} gradings)",
            all.len() / passes.len(),
            all.len()
        );
        return Ok(true);
    }
    Ok(passed == all.len())
}

/// The summary's count of the exercises that did not finish or crashed:
/// `", of which 1 did not finish and 1 crashed"`, or nothing.
fn stopped_count(all: &[grading::ExerciseResult]) -> String {
    use grading::RunStatus::{Crashed, DidNotFinish};
    let parts: Vec<String> = [(DidNotFinish, "did not finish"), (Crashed, "crashed")]
        .into_iter()
        .map(|(s, what)| (all.iter().filter(|r| r.status == s).count(), what))
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    if parts.is_empty() {
        return String::new();
    }
    format!(", of which {}", parts.join(" and "))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: grade: {}", format!("{e:#}").replace('\n', " "));
            ExitCode::from(2)
        }
    }
}
