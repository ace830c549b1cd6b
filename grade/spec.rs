//! The grading spec of a chapter: `lessons/lesson_NN/exercises.toml`.
//!
//! Each `[[exercise]]` names its variant (`exercise_<topic>`), the section
//! of the chapter to reread, its checks (a measured figure against a
//! target, on a scene) and its hints (the likely cause of a failure, in
//! words). The book includes these files, so the targets a student reads
//! are the targets the grader applies. What a hint says to change, where
//! that states the answer (a formula), is a `[[fix]]` at the end of the
//! file, outside the chapter's anchors: the grader prints it after the
//! hint's cause, and the chapter does not show it.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use common::measure::counters::Counter;
use serde::Deserialize;

/// One chapter's exercises.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    #[serde(rename = "exercise", default)]
    pub exercises: Vec<Exercise>,
    /// Moved into their hints' `fix` by [`Spec::load`].
    #[serde(rename = "fix", default)]
    fixes: Vec<Fix>,
}

/// The grader's half of a hint: what to change, printed after the hint's
/// cause. It states the answer, so it is kept out of the chapters.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Fix {
    /// The exercise (`exercise_<topic>`).
    variant: String,
    /// Its hint, counted from 1 in the file's order.
    hint: usize,
    say: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Exercise {
    /// The lesson variant that runs the student's code: `exercise_<topic>`.
    pub variant: String,
    pub title: String,
    /// `lesson_NN.md#heading-anchor`, under `book/src/`.
    pub section: String,
    /// One line: what to write, and where.
    pub task: String,
    /// Counters the snapshot records (exercises about work saved).
    #[serde(default)]
    pub snapshot_counters: Vec<String>,
    #[serde(default = "default_width")]
    pub width: u32,
    #[serde(default = "default_height")]
    pub height: u32,
    #[serde(rename = "check", default)]
    pub checks: Vec<Check>,
    #[serde(rename = "hint", default)]
    pub hints: Vec<Hint>,
}

fn default_width() -> u32 {
    320
}

fn default_height() -> u32 {
    180
}

fn one() -> f64 {
    1.0
}

/// A measured figure against its target, on one scene.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct Check {
    /// `"default"` (the lesson's own scene) or a file in `scenes/`.
    pub scene: String,
    /// `misclassified_pct`, `false_shadow_pct`, `false_lit_pct`, `mean_abs`,
    /// (an area light's) `penumbra_mean_abs`, `umbra_misclassified_pct`,
    /// `light_bleeding_pct`,
    /// `coverage_mismatch_pct` (an error figure of report.json),
    /// `counters.<name>` or `camera_path.<name>` (e.g. `camera_path.shimmer_pct`).
    pub metric: String,
    #[serde(flatten)]
    pub bound: Bound,
    /// Also checked on every scene of `grade --scenes DIR`.
    #[serde(default)]
    pub hidden: bool,
}

/// A target: a number, or a lesson variant's value on the same scene,
/// times `factor`, plus `slack`.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct Bound {
    pub at_most: Option<f64>,
    pub at_least: Option<f64>,
    pub at_most_variant: Option<String>,
    pub at_least_variant: Option<String>,
    #[serde(default = "one")]
    pub factor: f64,
    #[serde(default)]
    pub slack: f64,
}

/// The likely cause of a failure, printed when its condition holds.
#[derive(Debug, Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub struct Hint {
    pub metric: String,
    pub above: Option<f64>,
    pub below: Option<f64>,
    pub above_variant: Option<String>,
    pub below_variant: Option<String>,
    #[serde(default = "one")]
    pub factor: f64,
    #[serde(default)]
    pub slack: f64,
    /// Only on this scene (a check's `scene`): a cause that one of the
    /// exercise's scenes exists to catch. Every scene when unset.
    #[serde(default)]
    pub scene: Option<String>,
    /// The sentence; `{value}` is the hint metric's measured value.
    pub say: String,
    /// What to change (a `[[fix]]` of the file), printed after `say`.
    #[serde(skip)]
    pub fix: Option<String>,
}

/// Which way a target points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    AtMost,
    AtLeast,
}

/// A target resolved to one side and a number or a variant.
pub struct Target<'a> {
    pub side: Side,
    pub value: Option<f64>,
    pub variant: Option<&'a str>,
    pub factor: f64,
    pub slack: f64,
}

impl Target<'_> {
    /// A comparison with NaN or infinity passes or fails whatever is measured.
    fn is_finite(&self) -> bool {
        let value = self.value.is_none_or(f64::is_finite);
        value && self.factor.is_finite() && self.slack.is_finite()
    }
}

/// One side of a target: a number or a variant, and which way it points.
type Limit<'a> = (Option<f64>, &'a Option<String>, Side);

/// The one limit given (validated by [`Spec::load`]) as a target.
fn target_of<'a>(limits: [Limit<'a>; 2], factor: f64, slack: f64) -> Target<'a> {
    let (value, variant, side) = limits
        .into_iter()
        .find(|(v, n, _)| v.is_some() || n.is_some())
        .expect("validated by Spec::load");
    Target {
        side,
        value,
        variant: variant.as_deref(),
        factor,
        slack,
    }
}

/// How many of the four ways to give a limit are used (one is right).
fn given(limits: &[Limit; 2]) -> usize {
    let count = |(v, n, _): &Limit| usize::from(v.is_some()) + usize::from(n.is_some());
    limits.iter().map(count).sum()
}

impl Bound {
    fn limits(&self) -> [Limit<'_>; 2] {
        [
            (self.at_most, &self.at_most_variant, Side::AtMost),
            (self.at_least, &self.at_least_variant, Side::AtLeast),
        ]
    }

    pub fn target(&self) -> Target<'_> {
        target_of(self.limits(), self.factor, self.slack)
    }
}

impl Hint {
    /// The hint's condition: the measured value lies beyond this target
    /// (`above`: greater than it; `below`: less).
    fn limits(&self) -> [Limit<'_>; 2] {
        [
            (self.below, &self.below_variant, Side::AtMost),
            (self.above, &self.above_variant, Side::AtLeast),
        ]
    }

    pub fn target(&self) -> Target<'_> {
        target_of(self.limits(), self.factor, self.slack)
    }
}

/// The error figures a metric may name, besides `counters.<name>`.
const ERROR_METRICS: [&str; 8] = [
    "misclassified_pct",
    "false_shadow_pct",
    "false_lit_pct",
    "mean_abs",
    "coverage_mismatch_pct",
    // Soft shadows (lesson 10): an area light's.
    "penumbra_mean_abs",
    "umbra_misclassified_pct",
    "light_bleeding_pct",
];

/// Whether `metric` is an error figure, `counters.<name>` or
/// `camera_path.<name>` (measured on a scene with a `[camera_path]`).
fn check_metric(metric: &str, at: &str) -> Result<()> {
    if let Some(name) = metric.strip_prefix("counters.") {
        return check_counter(name, &format!("{at}: metric"));
    }
    let ok = ERROR_METRICS.contains(&metric)
        || metric
            .strip_prefix("camera_path.")
            .is_some_and(|c| !c.is_empty());
    if !ok {
        bail!(
            "{at}: metric {metric:?} is not one of {}, counters.<name> or camera_path.<name>",
            ERROR_METRICS.join(", ")
        );
    }
    Ok(())
}

/// Whether `name` is a counter a lesson reports (`common::measure::counters`).
fn check_counter(name: &str, at: &str) -> Result<()> {
    if Counter::named(name).is_none() {
        bail!("{at}: {name:?} is not a counter (common/src/measure/counters.rs lists them)");
    }
    Ok(())
}

/// 1-based line of a byte offset, for error messages.
fn line_of(text: &str, offset: usize) -> usize {
    let before = &text.as_bytes()[..offset.min(text.len())];
    before.iter().filter(|&&b| b == b'\n').count() + 1
}

impl Spec {
    /// The spec file of `lesson` under the workbook's `root`.
    pub fn path(root: &Path, lesson: &str) -> PathBuf {
        root.join("lessons").join(lesson).join("exercises.toml")
    }

    /// Reads and checks a spec: every error names the file and the field.
    pub fn load(path: &Path, scenes_dir: &Path) -> Result<Spec> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read the exercise spec", path.display()))?;
        let mut spec: Spec = toml::from_str(&text).map_err(|e| {
            let msg = e.message().replace(['\n', '\r'], " ");
            // The line: toml's message alone may name no key ("duplicate key").
            let at = match e.span() {
                Some(s) => format!("{}:{}", path.display(), line_of(&text, s.start)),
                None => path.display().to_string(),
            };
            anyhow::anyhow!("{at}: not a valid exercise spec: {msg}")
        })?;
        if spec.exercises.is_empty() {
            bail!("{}: no [[exercise]] in the spec", path.display());
        }
        for f in std::mem::take(&mut spec.fixes) {
            let at = format!(
                "{}: [[fix]] of {:?}, hint {}",
                path.display(),
                f.variant,
                f.hint
            );
            let Some(ex) = spec.exercises.iter_mut().find(|e| e.variant == f.variant) else {
                bail!("{at}: no such exercise");
            };
            let Some(h) = f.hint.checked_sub(1).and_then(|i| ex.hints.get_mut(i)) else {
                bail!("{at}: the exercise has {} hints", ex.hints.len());
            };
            if h.fix.replace(f.say).is_some() {
                bail!("{at}: a second fix for the same hint");
            }
        }
        for ex in &spec.exercises {
            let at = format!("{}: exercise {:?}", path.display(), ex.variant);
            if !ex.variant.starts_with(common::run::lesson::EXERCISE_PREFIX) {
                bail!("{at}: variant must start with \"exercise_\"");
            }
            if ex.checks.is_empty() {
                bail!("{at}: no [[exercise.check]]");
            }
            for c in &ex.snapshot_counters {
                check_counter(c, &format!("{at}: snapshot_counters"))?;
            }
            if !ex.checks.iter().any(|c| c.hidden) {
                bail!("{at}: no check has hidden = true, so hidden scenes would grade nothing");
            }
            for c in &ex.checks {
                let at = format!("{at}, check on {:?}", c.scene);
                check_metric(&c.metric, &at)?;
                if given(&c.bound.limits()) != 1 {
                    bail!("{at}: give exactly one of at_most, at_least, at_most_variant, at_least_variant");
                }
                if c.scene != "default" && !scenes_dir.join(&c.scene).is_file() {
                    let file = c.scene.escape_debug();
                    bail!("{at}: scene file scenes/{file} does not exist");
                }
                if !c.bound.target().is_finite() {
                    bail!("{at}: at_most, at_least, factor and slack must be finite numbers");
                }
            }
            for h in &ex.hints {
                let at = format!("{at}, hint {:?}", h.say);
                check_metric(&h.metric, &at)?;
                if given(&h.limits()) != 1 {
                    bail!("{at}: give exactly one of above, below, above_variant, below_variant");
                }
                if !h.target().is_finite() {
                    bail!("{at}: above, below, factor and slack must be finite numbers");
                }
                if let Some(scene) = &h.scene {
                    if !ex.checks.iter().any(|c| &c.scene == scene) {
                        bail!("{at}: scene {scene:?} is not one of the exercise's check scenes");
                    }
                }
            }
        }
        Ok(spec)
    }
}

impl Exercise {
    /// The lesson variants the checks and hints compare with.
    pub fn compared_variants(&self) -> Vec<String> {
        let mut v: Vec<String> = Vec::new();
        let names = self
            .checks
            .iter()
            .flat_map(|c| [&c.bound.at_most_variant, &c.bound.at_least_variant])
            .chain(
                self.hints
                    .iter()
                    .flat_map(|h| [&h.above_variant, &h.below_variant]),
            );
        for n in names.flatten() {
            if !v.contains(n) {
                v.push(n.clone());
            }
        }
        v
    }

    /// The distinct scenes its checks use, in order.
    pub fn scenes(&self) -> Vec<String> {
        let mut v: Vec<String> = Vec::new();
        for c in &self.checks {
            if !v.contains(&c.scene) {
                v.push(c.scene.clone());
            }
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
[[exercise]]
variant = "exercise_x"
title = "X"
section = "lesson_02.md#exercise-1-x"
task = "write x()"

[[exercise.check]]
scene = "default"
metric = "misclassified_pct"
at_most_variant = "slope_hw"
slack = 0.1
hidden = true

[[exercise.hint]]
metric = "false_shadow_pct"
above = 1.0
say = "acne {value}"
"#;

    fn load(text: &str) -> Result<Spec> {
        let dir = std::env::temp_dir().join(format!("grade-spec-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(format!(
            "{:x}.toml",
            text.len() * 31 + text.bytes().map(u64::from).sum::<u64>() as usize
        ));
        std::fs::write(&p, text).unwrap();
        Spec::load(&p, &dir)
    }

    #[test]
    fn a_good_spec_loads_and_names_its_compared_variants() {
        let s = load(GOOD).unwrap();
        assert_eq!(s.exercises[0].compared_variants(), vec!["slope_hw"]);
        assert_eq!(s.exercises[0].scenes(), vec!["default"]);
        let t = s.exercises[0].checks[0].bound.target();
        assert_eq!(
            (t.side, t.variant, t.slack),
            (Side::AtMost, Some("slope_hw"), 0.1)
        );
    }

    #[test]
    fn camera_path_metrics_load() {
        let path = GOOD.replace("\"misclassified_pct\"", "\"camera_path.shimmer_pct\"");
        let s = load(&path).unwrap();
        assert_eq!(s.exercises[0].checks[0].metric, "camera_path.shimmer_pct");
        let e = format!(
            "{:#}",
            load(&GOOD.replace("\"misclassified_pct\"", "\"camera_path.\"")).unwrap_err()
        );
        assert!(e.contains("camera_path.<name>"), "{e}");
    }

    #[test]
    fn fixes_join_their_hints() {
        let with =
            format!("{GOOD}\n[[fix]]\nvariant = \"exercise_x\"\nhint = 1\nsay = \"lower it\"\n");
        let s = load(&with).unwrap();
        assert_eq!(s.exercises[0].hints[0].fix.as_deref(), Some("lower it"));
        for bad in [
            with.replace("hint = 1", "hint = 2"),
            with.replace("\"exercise_x\"\nhint", "\"exercise_y\"\nhint"),
        ] {
            let e = format!("{:#}", load(&bad).unwrap_err());
            assert!(e.contains("[[fix]]"), "{e}");
        }
    }

    #[test]
    fn a_hint_for_one_scene_names_a_check_scene() {
        let on = |scene: &str| {
            GOOD.replace(
                "metric = \"false_shadow_pct\"\nabove",
                &format!("scene = \"{scene}\"\nmetric = \"false_shadow_pct\"\nabove"),
            )
        };
        let s = load(&on("default")).unwrap();
        assert_eq!(s.exercises[0].hints[0].scene.as_deref(), Some("default"));
        let e = format!("{:#}", load(&on("other.toml")).unwrap_err());
        assert!(e.contains("not one of the exercise's check scenes"), "{e}");
    }

    #[test]
    fn bad_specs_are_one_line_naming_the_field() {
        for (bad, want) in [
            (
                GOOD.replace("at_most_variant", "at_mast_variant"),
                "unknown field",
            ),
            (GOOD.replace("exercise_x", "x"), "must start with"),
            (GOOD.replace("misclassified_pct", "misclasified"), "metric"),
            (GOOD.replace("hidden = true", "hidden = false"), "hidden"),
            (
                GOOD.replace("scene = \"default\"", "scene = \"nowhere.toml\""),
                "does not exist",
            ),
            (
                GOOD.replace("slack = 0.1", "slack = 0.1\nat_most = 2.0"),
                "exactly one",
            ),
            (GOOD.replace("above = 1.0", ""), "exactly one"),
            ("title = 3".to_string(), "not a valid exercise spec"),
        ] {
            let e = format!("{:#}", load(&bad).unwrap_err());
            assert!(e.contains(want), "want {want:?} in: {e}");
            assert!(!e.contains('\n'), "one line: {e}");
        }
    }
}
