//! The chapters' exercises, graded: one test per exercise.
//!
//! Each test grades one exercise as `cargo run --release --bin grade` does
//! (the same code: `grade/grading.rs`): it runs the exercise variant on
//! the scenes of its chapter's `exercises.toml` and checks every target
//! against the exact reference, failing with the grader's feedback (the
//! likely cause, the section to reread, the diff image). Then it compares
//! the result with the snapshot recorded from the reference solution.
//!
//! With the starter code (the default build) every test here fails: that
//! is the student's to-do list. With `--features solutions` every test
//! passes. CI runs both (`.ci/run`).

use common::run::runner;

#[path = "../grade/spec.rs"]
mod spec;

#[path = "../grade/figures.rs"]
mod figures;
#[path = "../grade/grading.rs"]
mod grading;
#[path = "../grade/outcome.rs"]
mod outcome;
#[path = "../grade/results.rs"]
mod results;

use std::path::{Path, PathBuf};

use common::measure::counters::DRAWS;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn options(hidden: Option<PathBuf>) -> grading::Options {
    let hidden_only = hidden.is_some();
    let backend = std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "auto".into());
    grading::Options {
        root: root(),
        out: Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("grade-{backend}")),
        adapter: support::test_adapter(),
        backend: None,
        hidden,
        hidden_only,
        // The snapshots print each figure's bound (`±B`), which
        // tests/support/tolerance.rs allows on another adapter; measured
        // again only on the snapshots' own ([`support::measure_bounds`]).
        fragile: !hidden_only && support::measure_bounds(),
        stop_at: None,
    }
}

fn runner() -> runner::Runner {
    runner::Runner::beside(Path::new(env!("CARGO_BIN_EXE_lesson_01"))).expect("lesson binaries")
}

fn spec(lesson: &str) -> spec::Spec {
    spec::Spec::load(&spec::Spec::path(&root(), lesson), &root().join("scenes"))
        .unwrap_or_else(|e| panic!("{e:#}"))
}

/// `true` when the run found no adapter and skipping is allowed.
fn no_adapter(r: &grading::ExerciseResult) -> bool {
    let none = r.checks.iter().any(|c| {
        c.feedback
            .as_deref()
            .is_some_and(|f| f.contains("no GPU adapter found"))
    });
    if none && !support::gpu_required() {
        eprintln!(
            "SKIPPED {}: no GPU adapter (WORKBOOK_ALLOW_NO_GPU=1)",
            r.exercise
        );
        return true;
    }
    false
}

/// Grades one exercise; fails with the grader's feedback, then compares
/// the snapshot recorded from the reference solution.
fn grade(lesson: &str, exercise: &str) {
    let spec = spec(lesson);
    let ex = spec
        .exercises
        .iter()
        .find(|e| e.variant == exercise)
        .unwrap_or_else(|| panic!("{lesson}: no exercise {exercise} in its exercises.toml"));
    let r = grading::grade_exercise(&runner(), &options(None), lesson, ex)
        .unwrap_or_else(|e| panic!("{lesson} {exercise}: {e:#}"));
    if no_adapter(&r) {
        return;
    }
    assert!(r.passed, "\n{}", grading::describe(&r));
    // One snapshot on every adapter: rasterisers differ by a few edge
    // pixels, which the tolerances of tests/support/tolerance.rs allow.
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(format!("{lesson}__{exercise}"), r.snapshot)
    });
}

/// One test per exercise: `test_name: lesson exercise`.
macro_rules! exercises {
    ($($test:ident : $lesson:ident $exercise:ident),* $(,)?) => {
        /// Every exercise the tests grade, as (lesson, variant).
        const EXERCISES: &[(&str, &str)] = &[$((stringify!($lesson), stringify!($exercise))),*];
        $(
            #[test]
            fn $test() {
                grade(stringify!($lesson), stringify!($exercise));
            }
        )*
    };
}

exercises! {
    l01_tight_frustum: lesson_01 exercise_tight_frustum,
    l01_depth_compare: lesson_01 exercise_depth_compare,
    l02_slope_bias: lesson_02 exercise_slope_bias,
    l02_grazing_bias: lesson_02 exercise_grazing_bias,
    l03_pcf_kernel: lesson_03 exercise_pcf_kernel,
    l03_world_disk: lesson_03 exercise_world_disk,
    l04_cull_faces: lesson_04 exercise_cull_faces,
    l04_cube_faces: lesson_04 exercise_cube_faces,
    l05_edges_in_view: lesson_05 exercise_edges_in_view,
    l05_skip_casters: lesson_05 exercise_skip_casters,
    l06_choose_method: lesson_06 exercise_choose_method,
    l06_light_cap: lesson_06 exercise_light_cap,
    l07_infinite_projection: lesson_07 exercise_infinite_projection,
    l07_adaptive_near: lesson_07 exercise_adaptive_near,
    l08_scissor_rect: lesson_08 exercise_scissor_rect,
    l08_depth_bounds: lesson_08 exercise_depth_bounds,
    l09_practical_splits: lesson_09 exercise_practical_splits,
    l09_snap_tight_box: lesson_09 exercise_snap_tight_box,
    l10_off_axis_radius: lesson_10 exercise_off_axis_radius,
    l10_elliptic_footprint: lesson_10 exercise_elliptic_footprint,
}

/// Every exercise of every chapter's spec has its test above, and every
/// chapter has at least two.
#[test]
fn every_exercise_is_graded() {
    for n in 1..=10 {
        let lesson = format!("lesson_{n:02}");
        let spec = spec(&lesson);
        assert!(
            spec.exercises.len() >= 2,
            "{lesson}: {} exercises in its spec, want at least 2",
            spec.exercises.len()
        );
        let chapter = std::fs::read_to_string(root().join(format!("book/src/{lesson}.md")))
            .expect("the chapter");
        let coursework =
            std::fs::read_to_string(root().join("book/src/coursework.md")).expect("coursework.md");
        for ex in &spec.exercises {
            assert!(
                EXERCISES.contains(&(lesson.as_str(), ex.variant.as_str())),
                "{lesson} {}: in the spec but not graded by tests/exercises.rs",
                ex.variant
            );
            // The section to reread is a heading of the chapter's Exercises.
            let (file, anchor) = ex.section.split_once('#').expect("section has #anchor");
            assert_eq!(file, format!("{lesson}.md"), "{}: section file", ex.variant);
            let exercises = chapter
                .split_once("\n## Exercises\n")
                .unwrap_or_else(|| panic!("{lesson}.md has no `## Exercises` section"))
                .1;
            assert!(
                exercises
                    .lines()
                    .any(|l| l.starts_with("### ") && slug(&l[4..]) == anchor),
                "{lesson} {}: no `### ` heading in its chapter's Exercises gives #{anchor}",
                ex.variant
            );
            assert!(
                exercises.contains(&format!("--variant {}", ex.variant)),
                "{lesson} {}: the chapter does not show the command that runs it",
                ex.variant
            );
            assert!(
                coursework.contains(&format!("{lesson}.md#{anchor}")),
                "{lesson} {}: coursework.md does not list it",
                ex.variant
            );
        }
    }
}

/// The marker line of a WGSL chapter copy: the calls follow it
/// (`common::gpu::render::CHAPTER_COPY_CALLS`).
const CHAPTER_COPY_CALLS: &str = "// ==== calls the lesson's own functions ====";

/// A copy's function at line `at`: its comments above and its body, to
/// the next line that closes an item.
fn copy_block(lines: &[&str], at: usize) -> String {
    let from = (0..at)
        .rev()
        .take_while(|&i| {
            lines[i].trim_start().starts_with("//") || lines[i].trim_start().starts_with("#[")
        })
        .last()
        .unwrap_or(at);
    let to = (at..lines.len())
        .find(|&i| i > at && lines[i].starts_with('}'))
        .unwrap_or(lines.len() - 1);
    lines[from..=to].join("\n")
}

/// Whether `block` names, in backticks, an anchor some chapter includes.
fn names_listing(block: &str, anchors: &std::collections::BTreeSet<String>) -> bool {
    block.split('`').skip(1).step_by(2).any(|t| {
        let anchor = t.rsplit(':').next().unwrap_or(t);
        anchors.contains(anchor)
    })
}

/// mdBook's heading anchor: lower case, spaces to '-', punctuation dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

#[test]
fn slug_matches_mdbook() {
    assert_eq!(
        slug("Exercise 1: Slope-scaled bias"),
        "exercise-1-slope-scaled-bias"
    );
    assert_eq!(
        slug("Exercise 2: A `tight` frustum (beyond the lesson)"),
        "exercise-2-a-tight-frustum-beyond-the-lesson"
    );
}

/// An instructor's hidden scenes (`grade --scenes tests/hidden_scenes`):
/// two scenes that no chapter and no snapshot uses, a low sun and a point
/// lamp. Every exercise's hidden checks run on those its lesson accepts
/// (each lesson accepts at least one), and the reference solutions pass.
#[test]
fn hidden_scenes_are_graded() {
    let dir = root().join("tests/hidden_scenes");
    let mut failures = String::new();
    for n in 1..=10 {
        let lesson = format!("lesson_{n:02}");
        let results = grading::grade_lesson(&runner(), &options(Some(dir.clone())), &lesson, None)
            .unwrap_or_else(|e| panic!("{lesson}: {e:#}"));
        for r in &results {
            if no_adapter(r) {
                return;
            }
            assert!(
                r.checks.iter().any(|c| c.hidden),
                "{lesson} {}: no hidden scene was graded (skipped: {:?})",
                r.exercise,
                r.skipped_scenes
            );
            if !r.passed {
                failures += &grading::describe(r);
            }
        }
    }
    assert!(failures.is_empty(), "on the hidden scenes:\n{failures}");
}

/// Every exercise has a copy in `tests/chapter_copies/` (what CI grades
/// with `--features chapter_copies` and `grade --check-copies`), and the
/// copy names, in backticks beside its function, the chapter listing it
/// calls or pastes: an anchor some chapter includes. A copy that names no
/// printed listing would prove nothing when it fails. Each exercise also
/// has the copy that calls the lesson's own function, which the check's
/// second pass grades (`WORKBOOK_CHAPTER_COPY=calls`).
#[test]
fn every_copy_names_the_listing_it_copies() {
    let mut anchors = std::collections::BTreeSet::new();
    for e in std::fs::read_dir(root().join("book/src"))
        .expect("book/src")
        .flatten()
    {
        let text = std::fs::read_to_string(e.path()).unwrap_or_default();
        for piece in text.split("{{#include ").skip(1) {
            let Some(end) = piece.find("}}") else {
                continue;
            };
            if let Some((_, anchor)) = piece[..end].rsplit_once(':') {
                anchors.insert(anchor.trim().to_string());
            }
        }
    }
    let mut errors = Vec::new();
    for n in 1..=10 {
        let lesson = format!("lesson_{n:02}");
        for ex in &spec(&lesson).exercises {
            // `write NAME() in FILE`: the copy of FILE holds NAME.
            let name = ex
                .task
                .strip_prefix("write ")
                .and_then(|t| t.split_once("()"))
                .map(|(f, _)| f.to_string())
                .unwrap_or_else(|| panic!("{lesson} {}: task {:?}", ex.variant, ex.task));
            let ext = if ex.task.ends_with(".wgsl") {
                "wgsl"
            } else {
                "rs"
            };
            let path = root().join(format!("tests/chapter_copies/{lesson}.{ext}"));
            let text = std::fs::read_to_string(&path)
                .unwrap_or_else(|_| panic!("{}: missing", path.display()));
            let lines: Vec<&str> = text.lines().collect();
            // A Rust copy answers both passes of the check (`if
            // chapter_copy_calls()`, or one call in both); a WGSL copy holds
            // the calls after its marker line.
            let calls_from = lines
                .iter()
                .position(|l| l.trim() == CHAPTER_COPY_CALLS)
                .unwrap_or(lines.len());
            let defines = |i: usize| {
                lines[i].contains(&format!("fn {name}("))
                    && !lines[i].trim_start().starts_with("//")
            };
            let Some(at) = (0..calls_from).find(|&i| defines(i)) else {
                errors.push(format!("{}: no fn {name}", path.display()));
                continue;
            };
            let block = copy_block(&lines, at);
            if !names_listing(&block, &anchors) {
                errors.push(format!(
                    "{}: fn {name} names no listing a chapter includes (write it in backticks, `file:anchor`)",
                    path.display()
                ));
            }
            let calls = if ext == "rs" {
                block.contains("chapter_copy_calls()") || block.contains("both passes")
            } else {
                (calls_from..lines.len())
                    .find(|&i| defines(i))
                    .is_some_and(|i| names_listing(&copy_block(&lines, i), &anchors))
            };
            if !calls {
                errors.push(format!(
                    "{}: fn {name} has no copy that calls the lesson's own function (a Rust copy: \
                     `if chapter_copy_calls()`, or a call named as serving both passes; a WGSL copy: \
                     a second fn {name} after the line {CHAPTER_COPY_CALLS:?}, naming the listing it calls)",
                    path.display()
                ));
            }
        }
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// A spec's counters are the lessons' own (`common::measure::counters`): a
/// misspelt one in `snapshot_counters` or a check's `metric` is refused in
/// one line naming the file, the field and the name, before any run.
#[test]
fn a_spec_names_only_real_counters() {
    let path = spec::Spec::path(&root(), "lesson_04");
    let text = std::fs::read_to_string(&path).unwrap();
    let real = format!("\"{}\"", DRAWS.name);
    assert!(text.contains(&real), "lesson 04's spec snapshots its draws");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("misspelt_counter");
    std::fs::create_dir_all(&dir).unwrap();
    let scenes = root().join("scenes");
    let cases = [
        (text.replacen(&real, "\"drawz\"", 1), "snapshot_counters"),
        (
            text.replacen("metric = \"", "metric = \"counters.drawz\" #", 1),
            "metric",
        ),
    ];
    for (i, (bad, field)) in cases.iter().enumerate() {
        let file = dir.join(format!("exercises_{i}.toml"));
        std::fs::write(&file, bad).unwrap();
        let e = match spec::Spec::load(&file, &scenes) {
            Ok(_) => panic!("{}: a misspelt counter was accepted", file.display()),
            Err(e) => format!("{e:#}"),
        };
        for part in [
            &file.display().to_string(),
            *field,
            "\"drawz\" is not a counter",
        ] {
            assert!(e.contains(part), "{e}: should name {part}");
        }
        assert_eq!(e.lines().count(), 1, "{e}");
    }
    assert!(
        spec::Spec::load(&path, &scenes).is_ok(),
        "the real spec loads"
    );
}
