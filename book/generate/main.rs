//! `workbook`: regenerates every measured table, figure and plot of the book
//! and the README's results table, from real runs of the lessons.
//!
//! ```text
//! cargo run --release --bin workbook -- book
//! ```
//!
//! It runs every lesson headless on its default scene (timed, repeated) and
//! on every extreme-case scene a chapter cites ([`manifest::RUNS`]), then
//! writes `book/src/generated/` (tables, and the records the drift test
//! checks), `book/src/figures/` (figures, plots, diagrams) and the README's
//! table between its marker comments.
//!
//! The chapters' measured figures are markers it fills ([`prose`]); the
//! sentences comparing them carry claims it checks on the same records
//! ([`claims`]): it fails, naming the chapter's line, when one is false.

mod adapters;
mod bounds;
mod choosing;
mod claims;
mod diagrams;
mod figures;
mod gpu_costs;
mod grade_times;
mod legend;
mod lesson09;
mod lesson10;
mod manifest;
mod origins;
mod plots;
mod ports;
mod prose;
mod record;
mod runner;
mod scaling;
mod sets;
mod soft_diagrams;
mod stability;
mod summary;
mod table;
mod taps;
mod volume_diagrams;
mod volumes_gpu;
mod window_shots;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use common::measure::report::Report;
use indicatif::{ProgressBar, ProgressStyle};

use manifest::{Run, FIGURES, RUNS, TEXTS};
use record::{pool, Record, VariantRecord};
use runner::{RunArgs, Runner};

#[derive(Parser)]
#[command(about = "The shadow workbook's book generator")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run every lesson and rewrite every generated table, figure and plot.
    Book {
        /// Only this lesson's runs (`lesson_04`); the README table and the
        /// workbook plot are then made from the committed records of the others.
        #[arg(long, value_name = "LESSON")]
        only: Option<String>,
        /// vulkan | gl | ... (the committed tables were made on Vulkan).
        #[arg(long, default_value = manifest::BACKEND)]
        backend: String,
        /// software (the book's own set: lavapipe) | any (your GPU) | part of
        /// an adapter's name. Any adapter or backend other than the book's
        /// writes a set of its own under `book/src/generated/sets/`.
        #[arg(long, default_value = manifest::ADAPTER)]
        adapter: String,
    },
    /// Measure each committed record's bounds again (an untimed run of its
    /// entry with `--fragile`) and write them into the record, its times
    /// and tables untouched: how far each figure may move on another
    /// adapter. `book` measures them with every run.
    Bounds {
        /// Only this lesson's records (`lesson_04`).
        #[arg(long, value_name = "LESSON")]
        only: Option<String>,
    },
    /// Rewrite the tables, plots and README block that are made from the
    /// committed records, without running a lesson.
    Tables,
    /// Compare the times of two generated folders (two runs of `book`):
    /// how many medians of B lie inside A's stated spread.
    Compare {
        /// A `book/src/generated` folder (or a copy of one).
        a: PathBuf,
        b: PathBuf,
        /// Also write the introduction's table of the comparison
        /// (`book/src/generated/protocol/repeatability.md`).
        #[arg(long)]
        write: bool,
    },
    /// Capture each lesson's window (on a private Xvfb on Linux) for its
    /// chapter: `figures/window/` and `generated/window/`.
    WindowShots {
        /// Only this lesson's shot (`lesson_10`).
        #[arg(long, value_name = "LESSON")]
        only: Option<String>,
        #[arg(long, default_value = manifest::BACKEND)]
        backend: String,
        #[arg(long, default_value = manifest::ADAPTER)]
        adapter: String,
    },
    /// Time `grade --adapter software` once per chapter and write the
    /// coursework page's table (`generated/coursework/grade_times.md`).
    GradeTimes,
    /// Run one scaling sweep again (`triangles_lesson_05`) and rewrite its
    /// record, table and plot; the other sweeps' records stay as committed.
    Sweep {
        /// The sweep's name, as its record's file is named.
        name: String,
        #[arg(long, default_value = manifest::BACKEND)]
        backend: String,
    },
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn main() {
    if let Err(e) = run(Cli::parse()) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn run(cli: Cli) -> Result<()> {
    let (only, backend, adapter) = match cli.command {
        Command::Book {
            only,
            backend,
            adapter,
        } => (only, backend, adapter),
        Command::Bounds { only } => return bounds::write(&root(), only.as_deref()),
        Command::Tables => {
            let root = root();
            derive(
                &root,
                &root.join("book/src/generated"),
                &root.join("book/src/figures"),
            )?;
            println!("tables, plots and the README block rewritten from the records");
            return Ok(());
        }
        Command::Compare { a, b, write } => {
            let out = root()
                .join("book/src/generated")
                .join(stability::REPEATABILITY);
            return stability::compare(&a, &b, write.then_some(out.as_path()));
        }
        Command::WindowShots {
            only,
            backend,
            adapter,
        } => {
            let root = root();
            window_shots::write_all(
                &runner_or_build()?,
                &root.join("book/src/figures"),
                &root.join("book/src/generated"),
                &backend,
                &adapter,
                only.as_deref(),
            )?;
            println!("window screenshots written");
            return Ok(());
        }
        Command::GradeTimes => {
            return grade_times::run(&root(), &root().join("book/src/generated"));
        }
        Command::Sweep { name, backend } => {
            let root = root();
            let bar = ProgressBar::new(0);
            let work = root.join("target/book-runs");
            let runner = runner_or_build()?;
            scaling::run(&runner, &root, &work, &backend, &bar, Some(&name))?;
            bar.finish_with_message("sweep done");
            println!("sweep {name} run again: its record, table and plot rewritten");
            return Ok(());
        }
    };
    if let Some(l) = &only {
        if !RUNS.iter().any(|r| r.lesson == l) {
            let last = RUNS.last().map_or("", |r| r.lesson);
            bail!("--only: no lesson {l:?} in the manifest (lesson_01 to {last})");
        }
    }
    let start = std::time::Instant::now();
    let runner = runner_or_build()?;
    let root = root();
    let main_set = sets::is_main(&adapter, &backend);
    let generated = root.join("book/src/generated");
    let figures = root.join("book/src/figures");
    let work = root.join("target/book-runs");
    let runs: Vec<&Run> = RUNS
        .iter()
        .filter(|r| only.as_ref().is_none_or(|l| l == r.lesson))
        .collect();
    let steps: u64 = runs
        .iter()
        .map(|r| if r.timed { manifest::REPEATS } else { 1 } as u64)
        .sum();
    let bar = ProgressBar::new(steps);
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} runs {msg}")
            .context("progress bar template")?,
    );
    let work = match main_set {
        true => work,
        false => work.join(sets::SETS_DIR),
    };
    // The repeats of a timed run go in rounds over the whole manifest, not
    // back to back: a machine whose speed drifts over minutes (this one
    // does) then shows the drift in the run's spread instead of moving the
    // whole run.
    let mut reports: Vec<Vec<Report>> = vec![Vec::new(); runs.len()];
    for round in 0..manifest::REPEATS {
        for (run, done) in runs.iter().zip(reports.iter_mut()) {
            if run.timed || round == 0 {
                let a = Measure {
                    runner: &runner,
                    backend: &backend,
                    adapter: &adapter,
                    work: &work,
                    bar: &bar,
                };
                done.push(a.once(run, round)?);
            }
        }
    }
    for (run, reports) in runs.iter().zip(&reports) {
        let record = to_record(run, reports)?;
        let dir = match main_set {
            true => generated.join(run.lesson),
            // Another adapter's set: its records and tables, nothing else.
            false => sets::set_dir(&generated, &record.adapter, &record.backend).join(run.lesson),
        };
        std::fs::create_dir_all(&dir)?;
        write(
            &dir.join(format!("{}.json", run.name)),
            &serde_json::to_string_pretty(&record)?,
        )?;
        write_run_tables(&dir, run, &record)?;
    }
    if !main_set {
        bar.finish_with_message("runs done");
        let sets = sets::load_sets(&generated)?;
        sets::write_other_adapters(&generated, &sets)?;
        taps::write_all(&generated, &load_records(&generated)?, &sets)?;
        println!(
            "another adapter's set written under {} in {:.0} s",
            generated.join(sets::SETS_DIR).display(),
            start.elapsed().as_secs_f64()
        );
        return Ok(());
    }
    if only.is_none() {
        scaling::run(&runner, &root, &work, &backend, &bar, None)?;
        window_shots::write_all(&runner, &figures, &generated, &backend, &adapter, None)?;
    }
    bar.finish_with_message("runs done");
    copy_outputs(&work, &figures, &generated, only.as_deref())?;
    derive(&root, &generated, &figures)?;
    println!("regenerated in {:.0} s", start.elapsed().as_secs_f64());
    Ok(())
}

/// Everything made from the committed records: the scenes' tables, the
/// closing chapter's, chapter 09's, the adapters' comparison, the plots
/// and the README's results block; and chapter 10's convergence of the
/// reference, rendered again on the CPU (seconds).
fn derive(root: &Path, generated: &Path, figures: &Path) -> Result<()> {
    let records = load_records(generated)?;
    for (run, record) in RUNS.iter().zip(&records) {
        write_run_tables(&generated.join(run.lesson), run, record)?;
    }
    write_scenes_tables(generated, &records)?;
    ports::write_all(generated)?;
    // Chapter 10's convergence first: the peers table reads its figure.
    let convergence =
        lesson10::write_all(root, generated, &records, manifest::WIDTH, manifest::HEIGHT)?;
    choosing::write_all(generated, &records, Some(&convergence.errors_by_scene()))?;
    volumes_gpu::write(root, generated)?;
    gpu_costs::write(root, generated, &records)?;
    scaling::write_tables(root)?;
    lesson09::write_all(generated, figures, &records)?;
    adapters::write_all(root, generated, &records)?;
    let sets = sets::load_sets(generated)?;
    sets::write_other_adapters(generated, &sets)?;
    taps::write_all(generated, &records, &sets)?;
    let defaults: Vec<&Record> = records.iter().filter(|r| r.run == "results").collect();
    write_plots(figures, &defaults)?;
    for chapter in prose::write_chapters(&root.join("book/src"), generated)? {
        println!("figures in prose rewritten: {chapter}");
    }
    claims::check_book(root, generated)?;
    diagrams::write_all(root, &figures.join("diagrams"))?;
    volume_diagrams::write_all(root, &figures.join("diagrams"))?;
    soft_diagrams::write_all(root, &figures.join("diagrams"))?;
    let readme = root.join("README.md");
    let text = std::fs::read_to_string(&readme).context("cannot read README.md")?;
    let text = summary::splice(&text, &summary::readme_block(&defaults))
        .with_context(|| format!("README.md has no line {}", summary::BEGIN))?;
    write(&readme, &text)
}

/// A run's results table and, for a timed run, its passes table.
fn write_run_tables(dir: &Path, run: &Run, record: &Record) -> Result<()> {
    let mean_abs = manifest::MEAN_ABS_LESSONS.contains(&run.lesson);
    write(
        &dir.join(format!("{}.md", run.name)),
        &record.table(mean_abs)?,
    )?;
    if run.timed {
        write(
            &dir.join(format!("{}_passes.md", run.name)),
            &record.passes_table()?,
        )?;
    }
    if let Some(classes) = record.soft_classes_table()? {
        write(&dir.join(format!("{}_classes.md", run.name)), &classes)?;
    }
    Ok(())
}

/// The runner, building the lesson binaries first when one is missing.
pub fn runner_or_build() -> Result<Runner> {
    let exe = std::env::current_exe().context("cannot find the generator's own path")?;
    if Runner::beside(&exe).is_err() {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        eprintln!("building the lessons: {cargo} build --release --bins");
        let ok = std::process::Command::new(&cargo)
            .args(["build", "--release", "--bins"])
            .current_dir(root())
            .status()
            .with_context(|| format!("cannot run {cargo}"))?
            .success();
        if !ok {
            bail!("`cargo build --release --bins` failed");
        }
    }
    Runner::beside(&exe)
}

/// What one run of a lesson needs.
struct Measure<'a> {
    runner: &'a Runner,
    backend: &'a str,
    adapter: &'a str,
    work: &'a Path,
    bar: &'a ProgressBar,
}

impl Measure<'_> {
    /// Runs repeat `i` of one manifest entry and returns its report.
    fn once(&self, run: &Run, i: u32) -> Result<Report> {
        let repeats = if run.timed { manifest::REPEATS } else { 1 };
        let scene = run.scene.map(|s| root().join(s));
        let args = RunArgs {
            lesson: run.lesson,
            scene: scene.as_deref(),
            width: run.size.0,
            height: run.size.1,
            frames: if run.timed { run.frames } else { 1 },
            variants: run.variants,
            backend: Some(self.backend),
            adapter: Some(self.adapter),
            // Untimed runs keep errors and counters only: no warm-up needed.
            warm_up_ms: (!run.timed).then_some(0.0),
            // The bounds once (they are deterministic), after the timed
            // frames of the same process.
            fragile: i == 0,
        };
        let bar = self.bar;
        bar.set_message(format!("{} ({}/{repeats})", run.id(), i + 1));
        let out = self
            .work
            .join(run.lesson)
            .join(run.name)
            .join(format!("r{i}"));
        let t = std::time::Instant::now();
        let report = self.runner.run(&args, &out)?;
        bar.inc(1);
        if bar.is_hidden() {
            // Not a terminal (a log): one line a run instead of the bar.
            eprintln!(
                "[{}/{}] {} run {}: {:.1} s",
                bar.position(),
                bar.length().unwrap_or(0),
                run.id(),
                i + 1,
                t.elapsed().as_secs_f64()
            );
        }
        Ok(report)
    }
}

/// What the book keeps of a run. Errors and counters must agree between
/// the repeats (they are deterministic); times are pooled.
pub fn to_record(run: &Run, reports: &[Report]) -> Result<Record> {
    let first = &reports[0];
    let variants = first
        .variants
        .iter()
        .map(|v| {
            let same: Vec<&common::measure::report::VariantReport> = reports
                .iter()
                .filter_map(|r| r.variants.iter().find(|w| w.name == v.name))
                .collect();
            if same.iter().any(|w| {
                w.error != v.error
                    || w.counters != v.counters
                    || w.camera_path != v.camera_path
                    || w.classes != v.classes
            }) {
                bail!(
                    "{}: variant {} gave different errors, counters or shimmer in repeated runs",
                    run.id(),
                    v.name
                );
            }
            let runs: Vec<RunTimes> = same
                .iter()
                .zip(1..)
                .map(|(w, i)| {
                    let base = w.timing_check.as_ref().and_then(|c| c.base_ms);
                    let why = format!(
                        "base pass {} ms in run {i}",
                        base.map_or("—".into(), |b| format!("{b:.3}"))
                    );
                    (&w.timing_samples_ms, w.timing_stable(), why)
                })
                .collect();
            let timing = pool_stable(&runs);
            Ok(VariantRecord {
                name: v.name.clone(),
                receiver_pixels: v.error.receiver_pixels,
                misclassified_pct: v.error.misclassified_pct,
                false_shadow_pct: v.error.false_shadow_pct,
                false_lit_pct: v.error.false_lit_pct,
                mean_abs: v.error.mean_abs,
                coverage_mismatch_pct: v.error.coverage_mismatch_pct,
                counters: v.counters.clone(),
                timing: if run.timed { timing } else { None },
                camera_path: v.camera_path.clone(),
                classes: record::ClassRecord::of(v),
                soft: v.error.soft.clone(),
                fragile: v.fragile.clone(),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let baselines: Vec<RunTimes> = reports
        .iter()
        .zip(1..)
        .filter_map(|(r, i)| {
            let b = r.baseline.as_ref()?;
            Some((
                &b.timing_samples_ms,
                b.stable(),
                format!("every baseline block of run {i}"),
            ))
        })
        .collect();
    let baseline = pool_stable(&baselines);
    Ok(Record {
        lesson: run.lesson.to_string(),
        run: run.name.to_string(),
        scene: run.scene.unwrap_or("default").to_string(),
        title: run.title.to_string(),
        adapter: first.adapter.name.clone(),
        backend: first.adapter.backend.clone(),
        width: first.width,
        height: first.height,
        repeats: reports.len() as u32,
        frames: if run.timed { first.frames } else { 0 },
        timing_source: record::timing_source(first),
        variants,
        warm_up_ms: first
            .timing_protocol
            .as_ref()
            .filter(|_| run.timed)
            .map(|p| p.warm_up_min_ms),
        baseline: if run.timed { baseline } else { None },
    })
}

/// One run's samples of a timed cell, whether its block was stable, and
/// why not.
type RunTimes<'a> = (&'a BTreeMap<String, Vec<f64>>, bool, String);

/// Pools the runs whose times were stable; a run that was not is left out
/// and named (`left_out`). When no run was stable, every run is pooled and
/// the timing is `unstable`, with the reasons.
fn pool_stable(runs: &[RunTimes]) -> Option<record::Timing> {
    let stable: Vec<&BTreeMap<String, Vec<f64>>> =
        runs.iter().filter(|r| r.1).map(|r| r.0).collect();
    let why: Vec<&str> = runs.iter().filter(|r| !r.1).map(|r| r.2.as_str()).collect();
    let why = (!why.is_empty()).then(|| why.join(", "));
    if stable.is_empty() {
        let all: Vec<&BTreeMap<String, Vec<f64>>> = runs.iter().map(|r| r.0).collect();
        return pool(&all).map(|t| record::Timing { unstable: why, ..t });
    }
    pool(&stable).map(|t| record::Timing { left_out: why, ..t })
}

/// Copies the figures and lesson-written tables of the manifest; a PNG
/// figure is made ready for the page on the way ([`figures::prepare`]),
/// and its count goes to `generated/figures.json`.
fn copy_outputs(work: &Path, figures: &Path, generated: &Path, only: Option<&str>) -> Result<()> {
    let mut counts = figures::load_counts(generated)?;
    for (list, dest_root, is_figure) in [(FIGURES, figures, true), (TEXTS, generated, false)] {
        for f in list
            .iter()
            .filter(|f| only.is_none_or(|l| f.run.starts_with(l)))
        {
            let src = work.join(f.run).join("r0").join(f.file);
            let dest = dest_root.join(f.dest);
            std::fs::create_dir_all(dest.parent().context("figure path")?)?;
            if is_figure && f.dest.ends_with(".png") {
                figures::prepare_file(&src, f.dest, &dest, &mut counts)
                    .with_context(|| format!("figure {}", f.dest))?;
                continue;
            }
            std::fs::copy(&src, &dest)
                .with_context(|| format!("figure {}: cannot copy {}", f.dest, src.display()))?;
        }
    }
    figures::write_counts(generated, &counts)
}

/// Every committed record, by lesson then manifest order.
pub fn load_records(generated: &Path) -> Result<Vec<Record>> {
    RUNS.iter()
        .map(|r| {
            let path = generated.join(r.lesson).join(format!("{}.json", r.name));
            let text = std::fs::read_to_string(&path)
                .with_context(|| format!("{} is missing: run `workbook book`", path.display()))?;
            serde_json::from_str(&text).with_context(|| format!("{}: not a record", path.display()))
        })
        .collect()
}

/// Below this, an error is drawn on the plots' floor (log axis).
const ERROR_FLOOR_PCT: f64 = 1e-3;

/// One error-vs-time plot a chapter, and the workbook-wide one.
fn write_plots(figures: &Path, defaults: &[&Record]) -> Result<()> {
    let mut all = Vec::new();
    for r in defaults {
        let series = summary::series(r);
        let title = format!(
            "{}: error against time ({}, {}×{}, {} runs × {} frames)",
            r.lesson.replace('_', " "),
            r.adapter,
            r.width,
            r.height,
            r.repeats,
            r.frames
        );
        let path = figures.join(&r.lesson).join("error_vs_time.svg");
        std::fs::create_dir_all(path.parent().context("plot path")?)?;
        let base = r
            .baseline
            .as_ref()
            .filter(|b| b.stable())
            .map(|b| b.frame().median);
        plots::error_vs_time(&path, &title, &series, base, ERROR_FLOOR_PCT)?;
        all.push(series);
    }
    let dir = figures.join("workbook");
    std::fs::create_dir_all(&dir)?;
    let title = format!(
        "Every lesson's variants: error against time ({}, {}×{}, {} runs × {} frames)",
        defaults.first().map_or("", |r| r.adapter.as_str()),
        manifest::WIDTH,
        manifest::HEIGHT,
        manifest::REPEATS,
        manifest::FRAMES
    );
    plots::workbook_plot(
        &dir.join("error_vs_time.svg"),
        &title,
        &all,
        ERROR_FLOOR_PCT,
    )
}

/// Each lesson's extreme cases side by side (`scenes.md`).
fn write_scenes_tables(generated: &Path, records: &[Record]) -> Result<()> {
    let mut lessons: Vec<&str> = records.iter().map(|r| r.lesson.as_str()).collect();
    lessons.dedup();
    for l in lessons {
        let cases: Vec<&Record> = records
            .iter()
            // The extreme cases: not the default scene, at either size.
            .filter(|r| r.lesson == l && r.run != "results" && r.run != manifest::HD)
            .collect();
        if cases.is_empty() {
            continue;
        }
        let error = table::Cell::error_of(&cases);
        write(
            &generated.join(l).join("scenes.md"),
            &table::scenes_table(&cases, error)?,
        )?;
        // A soft shadow's other failure: light in the umbra.
        if error == table::Cell::Penumbra {
            write(
                &generated.join(l).join("scenes_bleeding.md"),
                &table::scenes_table(&cases, table::Cell::Bleeding)?,
            )?;
        }
    }
    Ok(())
}

fn write(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}
