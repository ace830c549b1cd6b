//! `workbook`: the book generator's command line.
//!
//! ```text
//! cargo run --release --bin workbook -- book
//! ```
//!
//! What it makes, and from what, is the `generator` library's (`lib.rs`):
//! this file is each command's course.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use common::measure::report::Report;
use indicatif::{ProgressBar, ProgressStyle};

use generator::derive::{self, derive, write_run_tables};
use generator::manifest::{self, Run, RUNS};
use generator::record::load_records;
use generator::runs::{copy_outputs, to_record, Measure};
use generator::{
    bounds, claims, diagrams, grade_times, origins, runner_or_build, scaling, sets, soft_diagrams,
    stability, tap_floor, volume_diagrams, web, window_shots,
};

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
    /// Fill the measured figures (`<!--fig:...-->`) and the tables' views
    /// (`<!--view:...-->`) of the pages named, from the committed records
    /// and tables, and check their claims; nothing else is written.
    Fill {
        /// Pages under `book/src/` (`book/src/lesson_03.md`).
        #[arg(required = true)]
        pages: Vec<PathBuf>,
    },
    /// Draw the book's diagrams again (`book/src/figures/diagrams/`), from
    /// the geometry they show; nothing else is written.
    Diagrams,
    /// Compare the times of two generated folders (two runs of `book`):
    /// how many medians of B lie inside A's stated spread.
    Compare {
        /// A `book/src/generated` folder (or a copy of one).
        a: PathBuf,
        b: PathBuf,
        /// Also write the table of the comparison that "Using the workbook" includes
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
    /// Build the lessons for the web (WebAssembly, the browser's WebGPU)
    /// and place them in the book: `book/src/web/` and each chapter's
    /// live bar, `generated/web/` (needs `rustup target add
    /// wasm32-unknown-unknown` and wasm-bindgen-cli at the lock's version).
    Web,
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
    generator::repo_root()
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
        Command::Fill { pages } => {
            let root = root();
            let generated = root.join("book/src/generated");
            for page in &pages {
                if derive::fill_page(&generated, page)? {
                    println!("filled: {}", page.display());
                }
            }
            let errors = claims::false_claims_in(&root, &generated, &pages)?;
            if !errors.is_empty() {
                bail!(
                    "a sentence says what the records do not:\n{}",
                    errors.join("\n")
                );
            }
            return Ok(());
        }
        Command::Diagrams => {
            let root = root();
            let dir = root.join("book/src/figures/diagrams");
            diagrams::write_all(&root, &dir)?;
            volume_diagrams::write_all(&root, &dir)?;
            soft_diagrams::write_all(&root, &dir)?;
            println!("diagrams written to {}", dir.display());
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
        Command::Web => return web::build(&root()),
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
    // The web build first: it needs tools a machine may lack (the wasm
    // target, wasm-bindgen), and says so before the hour of runs, not after.
    if only.is_none() && main_set {
        web::build(&root)?;
    }
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
        false => work.join(origins::SETS_DIR),
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
        generator::write(
            &dir.join(format!("{}.json", run.name)),
            &serde_json::to_string_pretty(&record)?,
        )?;
        write_run_tables(&dir, run, &record)?;
    }
    if !main_set {
        bar.finish_with_message("runs done");
        let sets = origins::load_sets(&generated)?;
        sets::write_other_adapters(&generated, &sets)?;
        tap_floor::write_all(&generated, &load_records(&generated)?, &sets)?;
        println!(
            "another adapter's set written under {} in {:.0} s",
            generated.join(origins::SETS_DIR).display(),
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
