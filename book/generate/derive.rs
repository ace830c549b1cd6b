//! Everything made from the committed records, without running a lesson
//! (`workbook tables`, and `workbook book` after its runs): every table,
//! plot, diagram and figure in prose, and the README's results block.

use std::path::Path;

use anyhow::{Context, Result};

use crate::error_plots::write_plots;
use crate::manifest::{Run, RUNS};
use crate::record::{load_records, Record};
use crate::{
    adapters, choosing, claims, diagrams, gpu_costs, lesson09, lesson10, manifest, origins, ports,
    prose, scaling, sets, soft_diagrams, summary, table, tap_floor, views, volume_diagrams,
    volumes_gpu, write,
};

/// Everything made from the committed records: the scenes' tables, the
/// closing chapter's, chapter 09's, the adapters' comparison, the plots
/// and the README's results block; and chapter 10's convergence of the
/// reference, rendered again on the CPU (seconds).
pub fn derive(root: &Path, generated: &Path, figures: &Path) -> Result<()> {
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
    write(
        &generated.join("choosing/volumes_build_sets.md"),
        &sets::volumes_build_sets(generated)?,
    )?;
    scaling::write_tables(root)?;
    lesson09::write_all(generated, figures, &records)?;
    adapters::write_all(root, generated, &records)?;
    let sets = origins::load_sets(generated)?;
    sets::write_other_adapters(generated, &sets)?;
    tap_floor::write_all(generated, &records, &sets)?;
    let defaults: Vec<&Record> = records.iter().filter(|r| r.run == "results").collect();
    write_plots(figures, &defaults)?;
    for chapter in prose::write_chapters(&root.join("book/src"), generated)? {
        println!("figures in prose rewritten: {chapter}");
    }
    for page in prose::chapters(&root.join("book/src"))? {
        if fill_views(generated, &page)? {
            println!("tables' views rewritten: {}", page.display());
        }
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

/// Writes the views of one page from the generated tables; whether it
/// changed.
fn fill_views(generated: &Path, page: &Path) -> Result<bool> {
    let text = std::fs::read_to_string(page).with_context(|| format!("{}", page.display()))?;
    if !text.contains(views::OPEN) {
        return Ok(false);
    }
    let new = views::fill(&text, &mut |s| views::read_generated(generated, s))
        .with_context(|| format!("{}", page.display()))?;
    let changed = new != text;
    if changed {
        write(page, &new)?;
    }
    Ok(changed)
}

/// Fills one page's figures in prose and its tables' views (`workbook
/// fill`); whether it changed.
pub fn fill_page(generated: &Path, page: &Path) -> Result<bool> {
    let text = std::fs::read_to_string(page).with_context(|| format!("{}", page.display()))?;
    let new = prose::fill(&text, &mut |k| prose::lookup(generated, k))
        .with_context(|| format!("{}", page.display()))?;
    let figures = new != text;
    if figures {
        write(page, &new)?;
    }
    Ok(fill_views(generated, page)? || figures)
}

/// A run's results table and, for a timed run, its passes table.
pub fn write_run_tables(dir: &Path, run: &Run, record: &Record) -> Result<()> {
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
