//! The closing chapter's tables ("Choosing a technique"), made from the
//! committed records of every run: each family's best variant and its worst
//! extreme case, the peers' defaults beside ours, and the three ways to
//! build shadow volumes. A soft shadow (lesson 10) is judged by the mean
//! |ΔV| over the reference's penumbra, a hard one by misclassified %.

use std::path::Path;

use anyhow::Result;

use crate::manifest::{Peer, FAMILIES, PEERS, VOLUME_BUILDS};
use crate::record::{Record, VariantRecord};
use crate::table::{count, header, pct, row, stat, time_cells};
use common::measure::counters::{EDGES_TESTED, VOLUME_FRAGMENTS};

/// Writes `generated/choosing/{families,peers,volumes_build}.md`.
/// `reference_error`: the soft reference's own sampling error, in % of V
/// (chapter 10's convergence), under which two soft errors do not differ.
pub fn write_all(
    generated: &Path,
    records: &[Record],
    reference_error: Option<&crate::lesson10::ReferenceErrors>,
) -> Result<()> {
    let dir = generated.join("choosing");
    std::fs::create_dir_all(&dir)?;
    let files = [
        ("families.md", families(records)),
        ("peers.md", peers(records, reference_error)),
        ("volumes_build.md", volumes_build(records)),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text)
            .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    }
    Ok(())
}

/// The record's most accurate variant, the families table's: the lowest
/// error (a hard shadow's misclassified %, a soft shadow's penumbra |ΔV|),
/// the first in the lesson's order on a tie.
pub fn most_accurate(r: &Record) -> Option<&VariantRecord> {
    r.variants
        .iter()
        .min_by(|a, b| a.error_pct().total_cmp(&b.error_pct()))
}

/// The lesson's default run (`lesson_04`).
pub fn default_of<'a>(records: &'a [Record], lesson: &str) -> Option<&'a Record> {
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
            "*{} · {}×{} · {what}*\n\n",
            r.adapter_label(),
            r.width,
            r.height
        ),
        None => String::new(),
    }
}

/// A soft shadow's error (lesson 10), in %: its penumbra's mean |ΔV|.
fn penumbra_pct(v: &VariantRecord) -> Option<f64> {
    v.soft.as_ref().map(|s| 100.0 * s.penumbra_mean_abs)
}

/// Per lesson: the variant with the lowest error on its default scene
/// (misclassified %, or for a soft shadow its penumbra's mean |ΔV|), its
/// frame time, and the worst of the lesson's extreme cases for it.
pub fn families(records: &[Record]) -> String {
    let mut s = caption(
        records,
        "each lesson's most accurate variant on its default scene (a soft shadow's: by the mean |ΔV| over the penumbra); frame cost: median [spread] of the default run",
    );
    let head = [
        "family".to_string(),
        "lesson".into(),
        "most accurate variant".into(),
        "misclassified %".into(),
        "penumbra \\|ΔV\\| %".into(),
        "frame ms".into(),
        "no shadows ms".into(),
        "its worst extreme case".into(),
        "misclassified % there".into(),
        "penumbra \\|ΔV\\| % there".into(),
    ];
    s += &header(&head);
    let opt = |x: Option<f64>| x.map_or("—".into(), pct);
    for (family, lessons) in FAMILIES {
        for lesson in *lessons {
            let Some(d) = default_of(records, lesson) else {
                continue;
            };
            let error = |v: &VariantRecord| v.error_pct();
            let Some(best) = most_accurate(d) else {
                continue;
            };
            let worst = cases_of(records, lesson)
                .filter_map(|c| variant(c, &best.name).map(|v| (c, v)))
                .max_by(|a, b| error(a.1).total_cmp(&error(b.1)));
            let (case, case_pct, case_penumbra) = match worst {
                Some((c, v)) => (
                    c.title.clone(),
                    pct(v.misclassified_pct),
                    opt(penumbra_pct(v)),
                ),
                None => ("—".into(), "—".into(), "—".into()),
            };
            s += &row(&[
                family.to_string(),
                format!("[{}]({}.md)", lesson.replace("lesson_", ""), lesson),
                format!("`{}`", best.name),
                pct(best.misclassified_pct),
                opt(penumbra_pct(best)),
                best.timing
                    .as_ref()
                    .map_or("—".into(), |t| time_cells(t)[0].clone()),
                d.baseline
                    .as_ref()
                    .map_or("—".into(), |b| time_cells(b)[0].clone()),
                case,
                case_pct,
                case_penumbra,
            ]);
        }
    }
    s += &crate::legend::legend_own(&head, FAMILIES_LEGEND);
    s
}

/// The families table's own columns.
const FAMILIES_LEGEND: &[(&str, &str)] = &[
    ("family", "the family of techniques the lesson belongs to: shadow maps (lessons 01–04), shadow volumes (05–08), cascaded shadow maps (09), soft shadows from area lights (10)"),
    ("lesson", "the lesson, linked to its chapter"),
    ("most accurate variant", "the lesson's variant with the lowest error on the lesson's default scene: misclassified %, or for a soft shadow the mean |ΔV| over the penumbra (the first in the lesson's order on a tie)"),
    ("misclassified %", "that variant's misclassified % on the default scene: receiver pixels classified differently from the exact reference, in % of the receiver pixels of every light"),
    ("penumbra \\|ΔV\\| %", "a soft shadow's (a light with a size): that variant's mean |V − V_ref| over the receiver pixels in the exact reference's penumbra (0 < V_ref < 1) on the default scene, in %; — for a hard shadow"),
    ("frame ms", "that variant's frame cost in the default run, wall clock from the start of recording to the GPU's completion: median [spread], ms; `unstable` where the protocol's check failed; — where the run is untimed"),
    ("no shadows ms", "the frame cost of the same run's no-shadow baseline (the scene drawn without shadows): median [spread], ms; — where the run has none"),
    ("its worst extreme case", "of the lesson's other runs (its extreme cases: other scenes, sizes), the one where that variant's error (as for the most accurate variant) is highest; — where the lesson has none"),
    ("misclassified % there", "that variant's misclassified % in that extreme case"),
    ("penumbra \\|ΔV\\| % there", "a soft shadow's: that variant's mean |ΔV| over the penumbra in that extreme case, in %; — for a hard shadow"),
];

/// Each peer's default beside ours, on every scene of its lesson. A soft
/// shadow's difference below `reference_error` (the exact reference's own
/// sampling error, % of V) names no better one.
pub fn peers(
    records: &[Record],
    reference_error: Option<&crate::lesson10::ReferenceErrors>,
) -> String {
    let mut s = caption(
        records,
        "each scene of the lesson, in the row's measure: misclassified % of receiver pixels, or for a soft shadow the mean |ΔV| over the reference's penumbra, in %; difference in percentage points (peer − ours)",
    );
    let head = [
        "peer (variant)".to_string(),
        "ours".into(),
        "scene".into(),
        "measure".into(),
        "peer %".into(),
        "ours %".into(),
        "peer − ours".into(),
        "better".into(),
    ];
    s += &header(&head);
    for p in PEERS {
        let runs = default_of(records, p.lesson)
            .into_iter()
            .chain(cases_of(records, p.lesson));
        for r in runs {
            let (Some(theirs), Some(ours)) = (variant(r, p.variant), variant(r, p.ours)) else {
                continue;
            };
            s += &row(&peer_cells(p, r, theirs, ours, reference_error));
        }
    }
    let better = match reference_error {
        Some(_) => format!(
            "{}; for a soft shadow, `within the reference's error` where the two differ by less than the exact reference's own sampling error on that row's scene, in % of V (its mean \\|V_N − V_4N\\| in chapter 10's convergence table; the largest of them for the default scene's other sizes)",
            BETTER,
        ),
        None => BETTER.to_string(),
    };
    let own: Vec<(&str, &str)> = PEERS_LEGEND
        .iter()
        .copied()
        .chain([("better", better.as_str())])
        .collect();
    s += &crate::legend::legend_own(&head, &own);
    s
}

/// The peers table's "better" column.
const BETTER: &str = "which has the smaller error, and how many times smaller (the larger % over the smaller; ∞ where ours is 0); `equal` where the two differ by less than 0.0005 points, under the tables' three decimals";

/// The peers table's own columns.
const PEERS_LEGEND: &[(&str, &str)] = &[
    ("peer (variant)", "a published renderer's or tutorial's default, or an option it documents (the label says which, and the port's card gives the setting), and the lesson's variant that reproduces it"),
    ("ours", "the lesson's variant the book recommends in its place"),
    ("scene", "the run: the lesson's default scene, or the title of one of its extreme cases"),
    ("measure", "the error compared: `misclassified %` (receiver pixels classified differently from the exact reference, in % of the receiver pixels) for a hard shadow; `penumbra |ΔV| %` (the mean |V − V_ref| over the receivers in the exact reference's penumbra, 0 < V_ref < 1, in %) for a soft shadow"),
    ("peer %", "the peer's variant's error on that scene, in the row's measure"),
    ("ours %", "our variant's error on that scene, in the row's measure"),
    ("peer − ours", "peer % − ours %, in percentage points: positive where ours is nearer the exact reference"),
];

fn peer_cells(
    p: &Peer,
    r: &Record,
    theirs: &VariantRecord,
    ours: &VariantRecord,
    reference_error: Option<&crate::lesson10::ReferenceErrors>,
) -> Vec<String> {
    let (a, b) = (theirs.error_pct(), ours.error_pct());
    let d = a - b;
    let soft = ours.soft.is_some();
    // The tables print three decimals: a smaller difference is no difference.
    let better = if d.abs() < 0.0005 {
        "equal".to_string()
    } else if soft && reference_error.is_some_and(|e| d.abs() < e.of(&r.scene)) {
        // The soft reference's own sampling could make a difference this size.
        "within the reference's error".to_string()
    } else if d > 0.0 {
        format!("ours, ×{}", ratio(a, b))
    } else {
        format!("peer, ×{}", ratio(b, a))
    };
    let measure = match soft {
        true => "penumbra \\|ΔV\\| %",
        false => "misclassified %",
    };
    vec![
        format!("{} (`{}`)", p.who, p.variant),
        format!("`{}`", p.ours),
        if r.run == "results" {
            format!("{} default", r.lesson.replace('_', " "))
        } else {
            r.title.clone()
        },
        measure.into(),
        pct(a),
        pct(b),
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
    let head = [
        "scene".to_string(),
        "variant".into(),
        "misclassified %".into(),
        "frame ms".into(),
        "edge pass".into(),
        "edge pass ms".into(),
        "edges tested".into(),
        "M edges/s".into(),
        "volume fragments".into(),
    ];
    s += &header(&head);
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
            let edges = v.counters.get(EDGES_TESTED.name).copied();
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
                    .get(VOLUME_FRAGMENTS.name)
                    .map_or("—".into(), |&n| count(n)),
            ]);
        }
    }
    s += &crate::legend::legend_own(&head, VOLUMES_BUILD_LEGEND);
    s
}

/// The volume builds table's own columns.
const VOLUMES_BUILD_LEGEND: &[(&str, &str)] = &[
    ("scene", "the run of lesson 05: `default` is its default scene, else the extreme case's title"),
    ("variant", "the route that builds the volumes: `zpass_cpu` finds the silhouettes on the CPU every frame; `zpass_quads` sends a degenerate quad for every edge, built once, and extrudes it in the vertex shader; `zpass_compute` finds silhouettes and writes the sides in a compute pass, drawn indirectly"),
    ("misclassified %", "the route's misclassified % on that scene: receiver pixels classified differently from the exact reference, in % of the receiver pixels of every light"),
    ("frame ms", "the route's frame cost, wall clock from the start of recording to the GPU's completion: median [spread], ms; `unstable` where the protocol's check failed"),
    ("edge pass", "the pass in which the route tests the caster edges for the silhouette: `cpu_silhouette` (on the CPU), `volume` (the vertex shader of the volume pass, which also rasterises the volumes), `extrude` (the compute pass)"),
    ("edge pass ms", "that pass's time, CPU time for `cpu_silhouette` and GPU time for the others: median [spread], ms; — where not recorded"),
    ("edges tested", "caster edges tested for the silhouette in one frame, over all lights (the counter `edges_tested`)"),
    ("M edges/s", "edges tested over the edge pass's median time, in millions of edges per second; for `volume` the pass also rasterises, so this understates its testing rate; — where either is missing"),
    ("volume fragments", "shadow-volume fragments rasterised in one frame (the counter `volume_fragments`: an exact, untimed tally)"),
];
