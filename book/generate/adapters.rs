//! How far another adapter's error figures are from the records': an
//! NVIDIA H100's reports of every lesson's default scene
//! (`tests/snapshot_replay/h100_reports/`, from
//! `lesson_NN --headless --adapter any --backend vulkan --width 640
//! --height 360 --frames 5` at commit `631f993`) against the records the
//! book's tables are made from (lavapipe). The coursework page shows it
//! beside the snapshots' tolerances.

use std::path::Path;

use anyhow::{Context, Result};
use common::measure::report::Report;
use common::reference::metrics::ErrorStats;

use crate::record::{Record, VariantRecord};
use crate::table::pct;

/// The H100's reports, beside the tests that replay them.
pub const REPORTS: &str = "tests/snapshot_replay/h100_reports";

/// The H100's report of each lesson that has one, in lesson order.
pub fn load_reports(root: &Path) -> Result<Vec<Report>> {
    let mut out = Vec::new();
    for n in 1..=9 {
        let path = root.join(REPORTS).join(format!("lesson_{n:02}.json"));
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let report: Report = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a report", path.display()))?;
        out.push(report);
    }
    Ok(out)
}

/// One error figure: its name, in a report and in a record.
struct Figure {
    name: &'static str,
    of_report: fn(&ErrorStats) -> f64,
    of_record: fn(&VariantRecord) -> f64,
}

const FIGURES: [Figure; 3] = [
    Figure {
        name: "misclassified",
        of_report: |e| e.misclassified_pct,
        of_record: |v| v.misclassified_pct,
    },
    Figure {
        name: "false shadow",
        of_report: |e| e.false_shadow_pct,
        of_record: |v| v.false_shadow_pct,
    },
    Figure {
        name: "false lit",
        of_report: |e| e.false_lit_pct,
        of_record: |v| v.false_lit_pct,
    },
];

/// The largest difference of one figure over a lesson's variants:
/// (|Δ|, variant, record's value, report's value).
type Largest = (f64, String, f64, f64);

fn largest(rec: &Record, report: &Report, f: &Figure) -> Option<Largest> {
    rec.variants
        .iter()
        .filter_map(|v| {
            let r = report.variants.iter().find(|w| w.name == v.name)?;
            let (a, b) = ((f.of_record)(v), (f.of_report)(&r.error));
            Some(((a - b).abs(), v.name.clone(), a, b))
        })
        .max_by(|x, y| x.0.total_cmp(&y.0))
}

fn cell(l: &Option<Largest>) -> String {
    match l {
        Some((d, name, a, b)) => format!("{} (`{name}`: {} → {})", pct(*d), pct(*a), pct(*b)),
        None => "—".into(),
    }
}

/// The table: per lesson, the largest difference of each error figure
/// and the variant it is on; then every lesson together.
pub fn h100_table(records: &[Record], reports: &[Report]) -> String {
    let mut rows = Vec::new();
    let mut all: Vec<Option<Largest>> = vec![None; FIGURES.len()];
    let (mut adapter, mut theirs, mut size) = (String::new(), String::new(), String::new());
    for report in reports {
        let Some(rec) = records
            .iter()
            .find(|r| r.lesson == report.lesson && r.run == "results")
        else {
            continue;
        };
        adapter = rec.adapter_label();
        theirs = crate::record::adapter_label(&report.adapter.name, &report.adapter.backend);
        size = format!("{}×{}", report.width, report.height);
        let mut cells = vec![
            report.lesson["lesson_".len()..].to_string(),
            report.variants.len().to_string(),
        ];
        for (k, f) in FIGURES.iter().enumerate() {
            let l = largest(rec, report, f);
            if l.as_ref().map(|x| x.0) > all[k].as_ref().map(|x| x.0) {
                all[k] = l.clone();
            }
            cells.push(cell(&l));
        }
        rows.push(format!("| {} |", cells.join(" | ")));
    }
    let n: usize = reports.iter().map(|r| r.variants.len()).sum();
    let mut last = vec!["every lesson".to_string(), n.to_string()];
    last.extend(all.iter().map(cell));
    rows.push(format!("| {} |", last.join(" | ")));
    let mut head = vec!["lesson".to_string(), "variants".into()];
    head.extend(
        FIGURES
            .iter()
            .map(|f| format!("{} %, largest difference", f.name)),
    );
    let own: Vec<(String, String)> = FIGURES
        .iter()
        .map(|f| {
            (
                format!("{} %, largest difference", f.name),
                format!(
                    "the largest |ours − H100| of the {} % over the lesson's variants, in percentage points of the receiver pixels, then the variant it is on and its two values (ours, from the records → the H100's); in the last row, the largest over every lesson; — where no variant is in both",
                    f.name
                ),
            )
        })
        .chain([
            ("lesson".into(), "the lesson whose default scene both adapters ran (the last row: every lesson together)".into()),
            ("variants".into(), "the variants in the H100's report of that lesson, every one compared with the record's".into()),
        ])
        .collect();
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    format!(
        "*{theirs} against the records ({adapter}) · {size} · each lesson's default scene, every variant · error figures in percentage points of receiver pixels*\n\n| {} |\n| {} |\n{}\n{}",
        head.join(" | "),
        vec!["---"; head.len()].join(" | "),
        rows.join("\n"),
        crate::legend::legend_own(&head, &own)
    )
}

/// Writes `generated/adapters/h100.md`.
pub fn write_all(root: &Path, generated: &Path, records: &[Record]) -> Result<()> {
    let dir = generated.join("adapters");
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("h100.md");
    let text = h100_table(records, &load_reports(root)?);
    std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))
}
