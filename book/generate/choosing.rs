//! The closing chapter's tables ("Choosing a technique"), made from the
//! committed records of every run: each family's best variant and its worst
//! extreme case, the peers' defaults beside ours, and the three ways to
//! build shadow volumes.

use std::path::Path;

use anyhow::Result;

use crate::manifest::{Peer, FAMILIES, PEERS, VOLUME_BUILDS};
use crate::record::{Record, VariantRecord};
use crate::table::{count, pct, row, stat, time_cells};

/// Writes `generated/choosing/{families,peers,volumes_build}.md`.
pub fn write_all(generated: &Path, records: &[Record]) -> Result<()> {
    let dir = generated.join("choosing");
    std::fs::create_dir_all(&dir)?;
    let files = [
        ("families.md", families(records)),
        ("peers.md", peers(records)),
        ("volumes_build.md", volumes_build(records)),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text)
            .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    }
    Ok(())
}

fn default_of<'a>(records: &'a [Record], lesson: &str) -> Option<&'a Record> {
    records
        .iter()
        .find(|r| r.lesson == lesson && r.run == "results")
}

fn cases_of<'a>(records: &'a [Record], lesson: &str) -> impl Iterator<Item = &'a Record> + 'a {
    let lesson = lesson.to_string();
    records
        .iter()
        .filter(move |r| r.lesson == lesson && r.run != "results")
}

fn variant<'a>(r: &'a Record, name: &str) -> Option<&'a VariantRecord> {
    r.variants.iter().find(|v| v.name == name)
}

fn caption(records: &[Record], what: &str) -> String {
    match records.first() {
        Some(r) => format!(
            "*{}, {} · {}×{} · {what}*\n\n",
            r.adapter, r.backend, r.width, r.height
        ),
        None => String::new(),
    }
}

/// Per lesson: the variant with the lowest error on its default scene, its
/// frame time, and the worst of the lesson's extreme cases for it.
pub fn families(records: &[Record]) -> String {
    let mut s = caption(
        records,
        "each lesson's most accurate variant on its default scene; frame cost: median [spread] of the default run",
    );
    s += &row(&[
        "family".into(),
        "lesson".into(),
        "most accurate variant".into(),
        "misclassified %".into(),
        "frame ms".into(),
        "no shadows ms".into(),
        "its worst extreme case".into(),
        "misclassified % there".into(),
    ]);
    s += &row(&vec!["---".to_string(); 8]);
    for (family, lessons) in FAMILIES {
        for lesson in *lessons {
            let Some(d) = default_of(records, lesson) else {
                continue;
            };
            let Some(best) = d
                .variants
                .iter()
                .min_by(|a, b| a.misclassified_pct.total_cmp(&b.misclassified_pct))
            else {
                continue;
            };
            let worst = cases_of(records, lesson)
                .filter_map(|c| variant(c, &best.name).map(|v| (c, v)))
                .max_by(|a, b| a.1.misclassified_pct.total_cmp(&b.1.misclassified_pct));
            let (case, case_pct) = match worst {
                Some((c, v)) => (c.title.clone(), pct(v.misclassified_pct)),
                None => ("—".into(), "—".into()),
            };
            s += &row(&[
                family.to_string(),
                format!("[{}]({}.md)", lesson.replace("lesson_", ""), lesson),
                format!("`{}`", best.name),
                pct(best.misclassified_pct),
                best.timing
                    .as_ref()
                    .map_or("—".into(), |t| time_cells(t)[0].clone()),
                d.baseline
                    .as_ref()
                    .map_or("—".into(), |b| time_cells(b)[0].clone()),
                case,
                case_pct,
            ]);
        }
    }
    s
}

/// Each peer's default beside ours, on every scene of its lesson.
pub fn peers(records: &[Record]) -> String {
    let mut s = caption(
        records,
        "misclassified % of receiver pixels on each scene of the lesson; difference in percentage points (peer − ours)",
    );
    s += &row(&[
        "peer default (variant)".into(),
        "ours".into(),
        "scene".into(),
        "peer %".into(),
        "ours %".into(),
        "peer − ours".into(),
        "better".into(),
    ]);
    s += &row(&vec!["---".to_string(); 7]);
    for p in PEERS {
        let runs = default_of(records, p.lesson)
            .into_iter()
            .chain(cases_of(records, p.lesson));
        for r in runs {
            let (Some(theirs), Some(ours)) = (variant(r, p.variant), variant(r, p.ours)) else {
                continue;
            };
            s += &row(&peer_cells(p, r, theirs, ours));
        }
    }
    s
}

fn peer_cells(p: &Peer, r: &Record, theirs: &VariantRecord, ours: &VariantRecord) -> Vec<String> {
    let d = theirs.misclassified_pct - ours.misclassified_pct;
    // The tables print three decimals: a smaller difference is no difference.
    let better = if d.abs() < 0.0005 {
        "equal".to_string()
    } else if d > 0.0 {
        format!(
            "ours, ×{}",
            ratio(theirs.misclassified_pct, ours.misclassified_pct)
        )
    } else {
        format!(
            "peer, ×{}",
            ratio(ours.misclassified_pct, theirs.misclassified_pct)
        )
    };
    vec![
        format!("{} (`{}`)", p.who, p.variant),
        format!("`{}`", p.ours),
        if r.run == "results" {
            format!("{} default", r.lesson.replace('_', " "))
        } else {
            r.title.clone()
        },
        pct(theirs.misclassified_pct),
        pct(ours.misclassified_pct),
        format!("{d:+.3}"),
        better,
    ]
}

/// `a / b` as the tables print it; "∞" when b is 0.
fn ratio(a: f64, b: f64) -> String {
    if b <= 0.0 {
        "∞ (ours 0)".into()
    } else {
        format!("{:.1}", a / b)
    }
}

/// The three ways to build volumes, per timed run of lesson 05: frame time,
/// the build's own pass, edges per second, volume fragments.
pub fn volumes_build(records: &[Record]) -> String {
    let mut s = caption(
        records,
        "frame cost: median [spread]; edges per second = edges tested per frame / the pass that tests them",
    );
    s += &row(&[
        "scene".into(),
        "variant".into(),
        "misclassified %".into(),
        "frame ms".into(),
        "edge pass".into(),
        "edge pass ms".into(),
        "edges tested".into(),
        "M edges/s".into(),
        "volume fragments".into(),
    ]);
    s += &row(&vec!["---".to_string(); 9]);
    for (run, variants) in VOLUME_BUILDS {
        let Some(r) = records.iter().find(|r| r.id() == *run) else {
            continue;
        };
        for (name, pass) in *variants {
            let Some(v) = variant(r, name) else {
                continue;
            };
            let t = v.timing.as_ref();
            let pass_ms = t.and_then(|t| t.passes.get(*pass));
            let edges = v.counters.get("edges_tested").copied();
            let rate = match (edges, pass_ms) {
                (Some(e), Some(p)) if p.median > 0.0 => {
                    format!("{:.1}", e as f64 / (p.median * 1e-3) / 1e6)
                }
                _ => "—".into(),
            };
            s += &row(&[
                if r.run == "results" {
                    "default".into()
                } else {
                    r.title.clone()
                },
                format!("`{name}`"),
                pct(v.misclassified_pct),
                t.map_or("—".into(), |t| time_cells(t)[0].clone()),
                format!("`{pass}`"),
                pass_ms.map_or("—".into(), stat),
                edges.map_or("—".into(), count),
                rate,
                v.counters
                    .get("volume_fragments")
                    .map_or("—".into(), |&n| count(n)),
            ]);
        }
    }
    s
}
