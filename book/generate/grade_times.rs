//! `workbook grade-times`: how long `grade` takes per chapter on the
//! software adapter, for the coursework page
//! (`book/src/generated/coursework/grade_times.md`).
//!
//! It runs the grade binary beside the generator (`target/release/grade`,
//! built by `cargo build --release --bins`) [`REPEATS`] times per chapter,
//! as a student would, and times each run by the wall clock: the table
//! gives the median and the spread (fastest to slowest run). The grader's own rebuild
//! of the lessons is left out (it runs only under `cargo run`), so the
//! figures are the grading alone.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};

/// Where the table is written, under `book/src/generated/`.
pub const OUT: &str = "coursework/grade_times.md";

/// Runs of the grader per chapter: times on a shared machine are noisy.
pub const REPEATS: usize = 3;

/// One chapter's runs of the grader.
struct Timed {
    lesson: String,
    exercises: usize,
    /// Each run's wall-clock seconds, sorted.
    seconds: Vec<f64>,
}

impl Timed {
    fn median(&self) -> f64 {
        common::measure::timing::quantile(&self.seconds, 0.5)
    }
}

/// The chapters with exercises: `lessons/lesson_NN/exercises.toml`.
fn chapters(root: &Path) -> Result<Vec<String>> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(root.join("lessons")).context("cannot read lessons/")? {
        let name = e?.file_name().to_string_lossy().to_string();
        if root
            .join("lessons")
            .join(&name)
            .join("exercises.toml")
            .is_file()
        {
            out.push(name);
        }
    }
    out.sort();
    Ok(out)
}

/// Runs `grade --adapter software` once per chapter and writes the table.
pub fn run(root: &Path, generated: &Path) -> Result<()> {
    let exe = std::env::current_exe().context("cannot find the generator's own path")?;
    let grade: PathBuf = exe.with_file_name(format!("grade{}", std::env::consts::EXE_SUFFIX));
    if !grade.is_file() {
        bail!(
            "{} is missing: build it with `cargo build --release --bins`",
            grade.display()
        );
    }
    let work = root.join("target/grade-times");
    std::fs::create_dir_all(&work).with_context(|| format!("cannot create {}", work.display()))?;
    let mut rows = Vec::new();
    let mut adapter = String::new();
    for lesson in chapters(root)? {
        let json = work.join(format!("{lesson}.json"));
        let mut seconds = Vec::new();
        for run in 1..=REPEATS {
            eprintln!("grading {lesson} on the software adapter ({run} of {REPEATS}) ...");
            let start = Instant::now();
            let status = std::process::Command::new(&grade)
                .args(["--adapter", "software", &lesson, "--json"])
                .arg(&json)
                .arg("--out")
                .arg(work.join(&lesson))
                // Not under cargo: the grader then does not rebuild the lessons.
                .env_remove("CARGO")
                .current_dir(root)
                .stdout(std::process::Stdio::null())
                .status()
                .with_context(|| format!("cannot run {}", grade.display()))?;
            seconds.push(start.elapsed().as_secs_f64());
            // 0: every exercise passed, 1: some failed (the starters do); 2: an error.
            if !matches!(status.code(), Some(0) | Some(1)) {
                bail!("grade {lesson} failed ({status}); see its message above");
            }
        }
        seconds.sort_by(f64::total_cmp);
        let text = std::fs::read_to_string(&json)
            .with_context(|| format!("cannot read {}", json.display()))?;
        let entries: Vec<serde_json::Value> =
            serde_json::from_str(&text).with_context(|| format!("{}", json.display()))?;
        if adapter.is_empty() {
            if let Some(e) = entries.first() {
                let name = e["adapter"].as_str().unwrap_or("");
                let backend = e["backend"].as_str().unwrap_or("");
                adapter = format!("{name} ({backend})");
            }
        }
        rows.push(Timed {
            lesson,
            exercises: entries.len(),
            seconds,
        });
    }
    let out = generated.join(OUT);
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    std::fs::write(&out, table(&rows, &adapter))
        .with_context(|| format!("cannot write {}", out.display()))?;
    println!("wrote {}", out.display());
    Ok(())
}

fn table(rows: &[Timed], adapter: &str) -> String {
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let mut s = format!(
        "Wall-clock time of `grade --adapter software lesson_NN`, {REPEATS} runs per \
         chapter, on {adapter}, with {cores} CPU cores, on {} (written by \
         `cargo run --release --bin workbook -- grade-times`):\n\n",
        today()
    );
    let head = ["chapter", "exercises", "seconds", "spread"].map(String::from);
    s += "| chapter | exercises | seconds | spread |\n| --- | ---: | ---: | ---: |\n";
    let spread = |v: &[f64]| {
        format!(
            "{:.1}–{:.1}",
            v.first().copied().unwrap_or(0.0),
            v.last().copied().unwrap_or(0.0)
        )
    };
    for r in rows {
        s += &format!(
            "| {} | {} | {:.1} | {} |\n",
            r.lesson,
            r.exercises,
            r.median(),
            spread(&r.seconds)
        );
    }
    let n: usize = rows.iter().map(|r| r.exercises).sum();
    let mut totals: Vec<f64> = (0..REPEATS)
        .map(|i| {
            rows.iter()
                .map(|r| r.seconds.get(i).copied().unwrap_or(0.0))
                .sum()
        })
        .collect();
    totals.sort_by(f64::total_cmp);
    let all: f64 = rows.iter().map(Timed::median).sum();
    s += &format!(
        "| all {} chapters | {n} | {all:.1} | {} |\n",
        rows.len(),
        spread(&totals)
    );
    s += &crate::legend::legend_own(
        &head,
        &[
            ("chapter", "the chapter graded: `grade --adapter software lesson_NN`, every exercise of it"),
            ("exercises", "how many exercises the chapter has"),
            ("seconds", "the median wall-clock time of its runs, from start to the grader's last line (the lessons already built)"),
            ("spread", "the fastest to the slowest run; for all chapters, the sums of the fastest and of the slowest runs"),
        ],
    );
    s
}

/// Today's date (UTC), as YYYY-MM-DD.
fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    // Days since 1970-01-01 to a civil date (Howard Hinnant's algorithm).
    let z = (secs / 86_400) as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}")
}
