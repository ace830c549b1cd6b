//! Grading: run each exercise of a chapter as its lesson's variant, on the
//! scenes its spec names (and an instructor's hidden scenes), measure it
//! against the exact reference like every other variant, and say in words
//! what a failure most likely means.
//!
//! Shared by the `grade` binary and `tests/exercises.rs`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde_json::Value;

use crate::figures::{bound, fmt, metric, resolve, variant};
use crate::outcome::{failed_run, why_not_run};
pub use crate::results::{describe, CheckResult, ExerciseResult, Proof, RunStatus};
use crate::runner::{RunArgs, Runner};
use crate::spec::{Check, Exercise, Side, Spec};

/// How to grade.
pub struct Options {
    /// The workbook's root (specs, `scenes/`).
    pub root: PathBuf,
    /// Where the runs go: `<out>/<lesson>/<exercise>/<scene>/`.
    pub out: PathBuf,
    /// `--adapter`: `any` (the student's GPU) unless asked for another.
    pub adapter: String,
    pub backend: Option<String>,
    /// An instructor's hidden scenes (`--scenes DIR`): `DIR/*.toml` for
    /// every lesson, `DIR/lesson_NN/*.toml` for one.
    pub hidden: Option<PathBuf>,
    /// Grade on the hidden scenes only (not on the spec's own scenes).
    pub hidden_only: bool,
    /// Measure how far each figure may move on another adapter
    /// (`--fragile`): the snapshot prints the exercise's bounds.
    pub fragile: bool,
    /// CI's checks (`--check-starters`, `--check-copies`,
    /// `--check-half-right`) only need each exercise to fail, as [`Proof`]
    /// says: once it has, its other scenes are not run (listed as skipped).
    /// A student's grading runs every scene (`None`).
    pub stop_at: Option<Proof>,
}

/// The scene files of `--scenes DIR` that apply to `lesson`.
pub fn hidden_scenes(dir: &Path, lesson: &str) -> Result<Vec<PathBuf>> {
    let mut found = Vec::new();
    for d in [dir.to_path_buf(), dir.join(lesson)] {
        if !d.is_dir() {
            continue;
        }
        let entries = std::fs::read_dir(&d)
            .with_context(|| format!("--scenes: cannot read {}", d.display()))?;
        for e in entries {
            let p = e?.path();
            if p.extension().is_some_and(|x| x == "toml") {
                found.push(p);
            }
        }
    }
    found.sort();
    Ok(found)
}

/// The likely cause: of the hints whose condition holds on this run (of
/// scene `scene`), the first about the failing check's own metric, else
/// the first; filled in. A hint for one scene only counts on that scene,
/// and there comes before the others: it names what the scene is for.
fn likely_cause(
    ex: &Exercise,
    report: &Value,
    scene: &str,
    failing_metric: &str,
) -> Option<String> {
    let mut hints: Vec<_> = ex
        .hints
        .iter()
        .filter(|h| h.scene.as_deref().is_none_or(|s| s == scene))
        .collect();
    hints.sort_by_key(|h| h.scene.is_none());
    let holding: Vec<(&str, String)> = hints
        .into_iter()
        .filter_map(|h| {
            let value = metric(report, &ex.variant, &h.metric)?;
            let (limit, _) = resolve(&h.target(), report, &h.metric)?;
            let holds = match h.target().side {
                Side::AtLeast => value > limit,
                Side::AtMost => value < limit,
            };
            let say = h.say.replace("{value}", &fmt(value));
            // The fix states the answer: the grader's output only.
            let say = match &h.fix {
                Some(fix) => format!("{say}; {fix}"),
                None => say,
            };
            holds.then_some((h.metric.as_str(), say))
        })
        .collect();
    let own = holding.iter().find(|(m, _)| *m == failing_metric);
    own.or(holding.first()).map(|(_, say)| say.clone())
}

/// A scene's label and its path (`None`: the lesson's default scene).
fn scene_of(root: &Path, scene: &str) -> (String, Option<PathBuf>) {
    if scene == "default" {
        ("default".into(), None)
    } else {
        (scene.into(), Some(root.join("scenes").join(scene)))
    }
}

/// One run of the exercise (and the variants it is compared with) on a
/// scene. `Err` carries the lesson's own error line.
fn run_scene(
    runner: &Runner,
    opts: &Options,
    lesson: &str,
    ex: &Exercise,
    scene: Option<&Path>,
    out: &Path,
    variants: &[String],
) -> Result<Value> {
    let names: Vec<&str> = variants.iter().map(String::as_str).collect();
    let measured: Vec<&str> = names.iter().copied().filter(|n| *n == ex.variant).collect();
    let args = RunArgs {
        lesson,
        scene,
        width: ex.width,
        height: ex.height,
        frames: 1,
        variants: &names,
        backend: opts.backend.as_deref(),
        adapter: Some(&opts.adapter),
        // The grade reads errors, never times.
        warm_up_ms: Some(0.0),
        // The snapshot prints the exercise's bounds only (`snapshot_part`).
        fragile: opts.fragile && !measured.is_empty(),
        fragile_variants: &measured,
    };
    let report = runner.run(&args, out)?;
    Ok(serde_json::to_value(report)?)
}

/// The text mask and figures the snapshot records for one scene.
fn snapshot_part(ex: &Exercise, label: &str, report: &Value, out: &Path) -> Result<String> {
    let png = out.join(format!("{}_visibility_l0.png", ex.variant));
    let img = image::open(&png)
        .with_context(|| format!("{}: cannot read", png.display()))?
        .to_luma_alpha8();
    let (w, h) = img.dimensions();
    let ids: Vec<u32> = img.pixels().map(|p| u32::from(p.0[1] > 0)).collect();
    let vis: Vec<f32> = img.pixels().map(|p| p.0[0] as f32 / 255.0).collect();
    let mask = common::reference::metrics::ascii_mask(&ids, &vis, w, h, 64, 18);
    let f = |m: &str| metric(report, &ex.variant, m).unwrap_or(f64::NAN);
    // Each figure's bound (` ±B`), when the run measured them (`--fragile`).
    let b = |m: &str, scale: f64| bound(report, &ex.variant, m, scale);
    let mut text = format!(
        "scene {label}: light 0 ('#' shadow, '.' lit, ' ' background)\n{mask}\n\
         misclassified {:.2} %{}  false shadow {:.2} %{}  false lit {:.2} %{}  mean |dV| {:.2} %{}\n",
        f("misclassified_pct"),
        b("misclassified_pct", 1.0),
        f("false_shadow_pct"),
        b("false_shadow_pct", 1.0),
        f("false_lit_pct"),
        b("false_lit_pct", 1.0),
        100.0 * f("mean_abs"),
        b("mean_abs", 100.0),
    );
    // An area light's soft shadow: its penumbra and its umbra.
    if metric(report, &ex.variant, "penumbra_mean_abs").is_some() {
        text += &format!(
            "penumbra |dV| {:.2} %{}  umbra misclassified {:.2} %{}  bleeding {:.2} %{}\n",
            100.0 * f("penumbra_mean_abs"),
            b("penumbra_mean_abs", 100.0),
            f("umbra_misclassified_pct"),
            b("umbra_misclassified_pct", 1.0),
            f("light_bleeding_pct"),
            b("light_bleeding_pct", 1.0),
        );
    }
    for c in &ex.snapshot_counters {
        let v = metric(report, &ex.variant, &format!("counters.{c}"));
        let moved = variant(report, &ex.variant)
            .and_then(|v| v["fragile"]["counters"][c.as_str()].as_u64())
            .map_or(String::new(), |n| format!(" ±{n}"));
        text += &format!("{c} {}{moved}\n", v.map_or("missing".into(), fmt));
    }
    Ok(text + "\n")
}

/// Grades one check on one run.
fn grade_check(
    ex: &Exercise,
    check: &Check,
    label: &str,
    hidden: bool,
    report: &Value,
    out: &Path,
) -> CheckResult {
    let measured = metric(report, &ex.variant, &check.metric);
    let target = resolve(&check.bound.target(), report, &check.metric);
    let passed = match (measured, &target) {
        (Some(m), Some((t, _))) => match check.bound.target().side {
            Side::AtMost => m <= *t,
            Side::AtLeast => m >= *t,
        },
        _ => false,
    };
    let diff = out.join(format!("{}_diff_l0.png", ex.variant));
    let cause = if passed {
        None
    } else {
        likely_cause(ex, report, &check.scene, &check.metric)
    };
    let hinted = cause.is_some();
    let feedback = (!passed).then(|| match (measured, &target) {
        (None, _) => format!(
            "the report has no {} for {}: does the exercise variant run?",
            check.metric, ex.variant
        ),
        (_, None) => format!("the report has no {} to compare with", check.metric),
        (Some(m), Some((_, t))) => cause.unwrap_or_else(|| {
            format!(
                "{} {} on {label}, target {t}",
                check.metric.trim_start_matches("counters."),
                fmt(m)
            )
        }),
    });
    CheckResult {
        scene: label.to_string(),
        hidden,
        metric: check.metric.clone(),
        measured,
        target: target.as_ref().map(|t| t.0),
        target_text: target.map_or("(no target)".into(), |t| t.1),
        passed,
        feedback,
        hinted,
        diff_image: diff.is_file().then(|| diff.display().to_string()),
        status: RunStatus::Finished,
    }
}

/// Grades one exercise of `lesson`.
pub fn grade_exercise(
    runner: &Runner,
    opts: &Options,
    lesson: &str,
    ex: &Exercise,
) -> Result<ExerciseResult> {
    let mut variants = vec![ex.variant.clone()];
    variants.extend(ex.compared_variants());
    let base = opts.out.join(lesson).join(&ex.variant);
    let mut checks = Vec::new();
    let mut adapter = (String::new(), String::new());
    let mut snapshot = format!(
        "{lesson} {}: {} (the reference solution's result)\n\n",
        ex.variant, ex.title
    );
    let own_scenes = if opts.hidden_only {
        vec![]
    } else {
        ex.scenes()
    };
    // After a run that did not finish, the exercise's other scenes are not
    // run: each would wait out the time limit again.
    let mut stuck: Option<String> = None;
    let not_again = |first: &str| format!("not run: {} did not finish on {first}", ex.variant);
    let mut skipped = Vec::new();
    // CI's checks: once the exercise has failed as the check needs, the
    // line that says why the rest is not run.
    let proven = |checks: &[CheckResult]| {
        let p = opts.stop_at?;
        let scene = p.failed_on(checks)?;
        Some(format!(
            "not run: {} already failed on {scene} ({}), all the --check flag needs",
            ex.variant,
            p.needs()
        ))
    };
    for scene in own_scenes {
        let (label, path) = scene_of(&opts.root, &scene);
        if let Some(why) = proven(&checks) {
            skipped.push(format!("{label}: {why}"));
            continue;
        }
        let out = base.join(label.trim_end_matches(".toml"));
        let on_scene: Vec<&Check> = ex.checks.iter().filter(|c| c.scene == scene).collect();
        if let Some(first) = &stuck {
            let why = not_again(first);
            checks.extend(failed_run(
                &on_scene,
                &label,
                false,
                &why,
                RunStatus::DidNotFinish,
            ));
            continue;
        }
        match run_scene(runner, opts, lesson, ex, path.as_deref(), &out, &variants) {
            Ok(report) => {
                let name = |k: &str| report["adapter"][k].as_str().unwrap_or("").to_string();
                adapter = (name("name"), name("backend"));
                snapshot += &snapshot_part(ex, &label, &report, &out)?;
                for c in on_scene {
                    checks.push(grade_check(ex, c, &label, false, &report, &out));
                }
            }
            Err(e) => {
                let (why, status) = why_not_run(&e, ex, lesson, &label);
                if status == RunStatus::DidNotFinish {
                    stuck = Some(label.clone());
                }
                checks.extend(failed_run(&on_scene, &label, false, &why, status));
            }
        }
    }
    if let Some(dir) = &opts.hidden {
        let hidden: Vec<&Check> = ex.checks.iter().filter(|c| c.hidden).collect();
        for scene in hidden_scenes(dir, lesson)? {
            let label = scene
                .file_name()
                .map_or("hidden".into(), |n| n.to_string_lossy().to_string());
            let out = base.join("hidden").join(label.trim_end_matches(".toml"));
            if let Some(why) = proven(&checks) {
                skipped.push(format!("{label} (hidden scene): {why}"));
                continue;
            }
            if let Some(first) = &stuck {
                let why = not_again(first);
                checks.extend(failed_run(
                    &hidden,
                    &label,
                    true,
                    &why,
                    RunStatus::DidNotFinish,
                ));
                continue;
            }
            match run_scene(runner, opts, lesson, ex, Some(&scene), &out, &variants) {
                Ok(report) => {
                    for c in &hidden {
                        checks.push(grade_check(ex, c, &label, true, &report, &out));
                    }
                }
                Err(e) => {
                    // Does the lesson itself refuse this scene (its own
                    // variants fail too), or only the student's variant?
                    let own = &variants[1..];
                    let refused = !own.is_empty()
                        && run_scene(runner, opts, lesson, ex, Some(&scene), &out, own).is_err();
                    if refused {
                        skipped.push(format!("{label}: {e:#}"));
                    } else {
                        let (why, status) = why_not_run(&e, ex, lesson, &label);
                        if status == RunStatus::DidNotFinish {
                            stuck = Some(label.clone());
                        }
                        checks.extend(failed_run(&hidden, &label, true, &why, status));
                    }
                }
            }
        }
    }
    let passed = !checks.is_empty() && checks.iter().all(|c| c.passed);
    let d = match checks.iter().find(|c| !c.passed).or(checks.first()) {
        Some(c) => c.clone(),
        None => CheckResult {
            scene: "(none)".into(),
            hidden: true,
            metric: "(none)".into(),
            measured: None,
            target: None,
            target_text: "(not run)".into(),
            passed: false,
            feedback: Some("the lesson refused every hidden scene, so nothing was graded".into()),
            hinted: false,
            diff_image: None,
            status: RunStatus::Finished,
        },
    };
    let status = [RunStatus::DidNotFinish, RunStatus::Crashed]
        .into_iter()
        .find(|s| checks.iter().any(|c| c.status == *s))
        .unwrap_or(RunStatus::Finished);
    let feedback = match &d.feedback {
        Some(f) => f.clone(),
        None => format!(
            "passed: {} {} on {}, target {}",
            d.metric,
            d.measured.map_or("?".into(), fmt),
            d.scene,
            d.target_text
        ),
    };
    Ok(ExerciseResult {
        lesson: lesson.to_string(),
        exercise: ex.variant.clone(),
        title: ex.title.clone(),
        passed,
        status,
        metric: d.metric.clone(),
        scene: d.scene.clone(),
        measured: d.measured,
        target: d.target,
        feedback,
        diff_image: d.diff_image.clone(),
        section: format!("book/src/{}", ex.section),
        task: ex.task.clone(),
        checks,
        skipped_scenes: skipped,
        // The adapter first: on the one it was recorded on, a snapshot
        // must match exactly (tests/support/tolerance.rs).
        snapshot: format!("adapter: {} ({})\n{snapshot}", adapter.0, adapter.1),
        adapter: adapter.0,
        backend: adapter.1,
    })
}

/// Grades every exercise of `lesson` (or only `only`).
pub fn grade_lesson(
    runner: &Runner,
    opts: &Options,
    lesson: &str,
    only: Option<&str>,
) -> Result<Vec<ExerciseResult>> {
    let spec = Spec::load(&Spec::path(&opts.root, lesson), &opts.root.join("scenes"))?;
    let mut results = Vec::new();
    for ex in spec
        .exercises
        .iter()
        .filter(|e| only.is_none_or(|o| o == e.variant))
    {
        results.push(grade_exercise(runner, opts, lesson, ex)?);
    }
    Ok(results)
}
