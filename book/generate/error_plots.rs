//! The error-vs-time plots: one a chapter (`figures/lesson_NN/error_vs_time.svg`)
//! and the workbook-wide one, from the default runs' records.

use std::path::Path;

use anyhow::{Context, Result};

use crate::record::Record;
use crate::{manifest, plots, summary};

/// Below this, an error is drawn on the plots' floor (log axis).
const ERROR_FLOOR_PCT: f64 = 1e-3;

/// One error-vs-time plot a chapter, and the workbook-wide one.
pub fn write_plots(figures: &Path, defaults: &[&Record]) -> Result<()> {
    let mut all = Vec::new();
    for r in defaults {
        let series = summary::series(r);
        let title = format!(
            "{}: error against time ({}, {}×{}, {} runs × {} frames)",
            r.lesson.replace('_', " "),
            r.adapter_label(),
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
        defaults
            .first()
            .map_or(String::new(), |r| r.adapter_label()),
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
