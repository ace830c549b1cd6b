//! Scaling sweeps (issue 9): time and deterministic counters of one
//! shadow-map lesson and one shadow-volume lesson against the size of the
//! problem: caster triangles, shadow-map (or screen) resolution, and the
//! number of lights.
//!
//! Every point is one process of the lesson (`--frames 5`) on a scene this
//! module writes into a scratch folder (a torus at rising tessellation, or
//! the default casters under N lights), or on the lesson's default scene.
//! The records go to `book/src/generated/scaling/<sweep>.json`, the tables
//! to `<sweep>.md`, and two log-log plots a sweep (times, and counters on
//! their own axes) to `book/src/figures/scaling/<sweep>_{time,counters}.svg`.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use common::measure::report::Report;
use common::measure::timing::{CPU_TOTAL, FRAME};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};

use crate::manifest;
use crate::plots::{self, Curve};
use crate::record::Stat;
use crate::runner::{RunArgs, Runner};
use crate::table::{count, pct, row, stat};

/// The frame size of every sweep but the screen-size one.
const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;
/// Timed frames a point (one process a point).
const FRAMES: u32 = 5;

/// Torus tessellations (minor segments; major = 2 × minor), 4·v² triangles:
/// 1k, 4k, 16k, 64k, 256k and 1M.
const TORUS_MINOR: [u32; 6] = [16, 32, 64, 128, 256, 512];
/// The volume routes' sweep goes on to the 4.2 M-triangle torus (v = 1024),
/// where a route whose buffers pass the adapter's limits is left out.
const TORUS_MINOR_ROUTES: [u32; 7] = [16, 32, 64, 128, 256, 512, 1024];
/// The three volume routes of lesson 05, each run in a process of its own,
/// so that one left out (a limit) does not stop the others.
const ROUTES: [&str; 3] = ["zpass_cpu", "zpass_quads", "zpass_compute"];
/// lesson_01's resolution variants, in order, and their side in texels.
const SHADOW_RES: [(&str, u32); 5] = [
    ("res_256", 256),
    ("res_512", 512),
    ("res_1024", 1024),
    ("res_2048", 2048),
    ("res_4096", 4096),
];
/// Screen sizes of the volume lesson's resolution sweep.
const SCREENS: [(u32, u32); 4] = [(320, 180), (640, 360), (1280, 720), (2560, 1440)];
/// Light counts of the lights sweeps.
const LIGHTS: [u32; 5] = [1, 2, 4, 8, 16];

/// One point of a sweep: one variant at one size.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct SweepPoint {
    /// The size (triangles, texels on a side, pixels, lights).
    pub x: f64,
    /// The size as the table prints it (`1 048 576`, `1280×720`).
    pub label: String,
    pub variant: String,
    /// GPU time of the frame: median [interquartile range] of the point's
    /// frames (the frame cost, `frame`, is among the passes where recorded).
    pub total: Stat,
    /// The passes the sweep shows, by their report key.
    pub passes: BTreeMap<String, Stat>,
    /// The counters the sweep shows.
    pub counters: BTreeMap<String, u64>,
    pub misclassified_pct: f64,
}

/// Milliseconds or a count.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Unit {
    Ms,
    Count,
}

/// One curve of a sweep: a variant's time or counter against the size, its
/// expected order and the measured log-log slope.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct SweepCurve {
    pub variant: String,
    /// `total`, a pass key (`shadow`, `volume`, `cpu_silhouette`) or a
    /// counter name.
    pub key: String,
    pub unit: Unit,
    /// The expected order, e.g. `O(√n)`.
    pub expected: String,
    /// The log-log slope that order means once constant costs are small.
    pub expected_slope: f64,
    /// Least-squares log-log slope over every point (`None`: not defined,
    /// e.g. a counter that is zero).
    pub slope_all: Option<f64>,
    /// The same over the largest three sizes, where fixed costs weigh least.
    pub slope_top: Option<f64>,
}

/// One sweep: one lesson, one or more variants, one size axis.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Sweep {
    /// File stem: `triangles_lesson_05`.
    pub name: String,
    pub lesson: String,
    pub title: String,
    /// The x column's header (`triangles`).
    pub axis: String,
    /// What the points ran on.
    pub scene: String,
    pub adapter: String,
    pub backend: String,
    /// The frame size; 0 when the sweep varies it.
    pub width: u32,
    pub height: u32,
    pub frames: u32,
    pub timing_source: String,
    pub passes: Vec<String>,
    pub counters: Vec<String>,
    pub points: Vec<SweepPoint>,
    pub curves: Vec<SweepCurve>,
    /// Variants the lesson left out at some size: their buffers would pass
    /// one of the adapter's limits (the lesson's own note says which).
    #[serde(default)]
    pub stops: Vec<SweepStop>,
}

/// A variant left out at one size of a sweep, and why.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct SweepStop {
    pub x: f64,
    pub label: String,
    pub variant: String,
    /// The lesson's line: the buffer, its size and the limit.
    pub why: String,
}

/// The .md file name of a sweep's table (in `book/src/generated/scaling/`).
pub fn table_file(sweep: &Sweep) -> String {
    format!("{}.md", sweep.name)
}

/// The folder of the records and tables, under the repository root.
fn generated_dir(root: &Path) -> PathBuf {
    root.join("book/src/generated/scaling")
}

/// Rewrites every sweep's table from its committed record.
pub fn write_tables(root: &Path) -> Result<()> {
    let generated = generated_dir(root);
    for sweep in load_sweeps(root)? {
        write(&generated.join(table_file(&sweep)), &table(&sweep))?;
    }
    Ok(())
}

/// Every committed sweep record, by file name.
pub fn load_sweeps(root: &Path) -> Result<Vec<Sweep>> {
    let dir = generated_dir(root);
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .with_context(|| format!("{} is missing: run `workbook book`", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p)
                .with_context(|| format!("cannot read {}", p.display()))?;
            serde_json::from_str(&text).with_context(|| format!("{}: not a sweep", p.display()))
        })
        .collect()
}

fn slope_cell(s: Option<f64>) -> String {
    s.map_or("—".into(), |s| format!("{s:.2}"))
}

fn curve_name(sweep: &Sweep, c: &SweepCurve) -> String {
    let what = match c.unit {
        Unit::Ms if c.key == "total" => "GPU ms".to_string(),
        Unit::Ms => format!("`{}` ms", c.key),
        Unit::Count => format!("`{}`", c.key),
    };
    if distinct_variants(sweep).len() > 1 && !c.variant.contains(", ") {
        format!("`{}` {what}", c.variant)
    } else {
        what
    }
}

fn distinct_variants(sweep: &Sweep) -> Vec<String> {
    let mut v: Vec<String> = Vec::new();
    for p in &sweep.points {
        if !v.contains(&p.variant) {
            v.push(p.variant.clone());
        }
    }
    v
}

/// The markdown of one sweep: the header line, one row a point, then the
/// slope table.
pub fn table(sweep: &Sweep) -> String {
    let size = if sweep.width > 0 {
        format!("{}×{}", sweep.width, sweep.height)
    } else {
        "frame size: see the rows".to_string()
    };
    let mut s = format!(
        "*{}, {} · {} · {} · median of {} frames, warmed up until they settle (the introduction's protocol), one process a point, [interquartile range], {}*\n\n",
        sweep.adapter,
        sweep.backend,
        size,
        sweep.scene,
        sweep.frames,
        sweep.timing_source.replace('_', " ")
    );
    let multi = distinct_variants(sweep).len() > 1;
    let mut head = vec![sweep.axis.clone()];
    if multi {
        head.push("variant".into());
    }
    // The frame cost where the records have it (older ones: GPU time only).
    let has_frame = sweep.points.iter().any(|p| p.passes.contains_key(FRAME));
    if has_frame {
        head.push("frame ms".into());
    }
    head.push("GPU ms".into());
    // Passes in the frame's order, counters in the tables' order
    // (`legend.rs`), whatever order the record lists them in.
    let mut passes = sweep.passes.clone();
    passes.sort_by_key(|k| crate::legend::pass_rank(k));
    let mut counters = sweep.counters.clone();
    counters.sort_by_key(|k| crate::legend::counter_rank(k));
    head.extend(passes.iter().map(|p| format!("`{p}` ms")));
    head.extend(counters.iter().map(|c| format!("`{c}`")));
    head.push("misclassified %".into());
    s += &row(&head);
    s += &row(&vec!["---".to_string(); head.len()]);
    for p in &sweep.points {
        let mut cells = vec![p.label.clone()];
        if multi {
            cells.push(format!("`{}`", p.variant));
        }
        if has_frame {
            cells.push(p.passes.get(FRAME).map_or("—".into(), stat));
        }
        cells.push(stat(&p.total));
        for k in &passes {
            cells.push(p.passes.get(k).map_or("—".into(), stat));
        }
        for k in &counters {
            cells.push(p.counters.get(k).map_or("—".into(), |&n| count(n)));
        }
        cells.push(pct(p.misclassified_pct));
        s += &row(&cells);
    }
    s += &points_legend(sweep, &head, &passes, &counters);
    s += &stops_table(sweep);
    let mut xs: Vec<f64> = sweep.points.iter().map(|p| p.x).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let top = SIZES_TOP.min(xs.len());
    let _ = write!(
        s,
        "\n*Log-log slopes against {}: least squares over every point, and over the largest {top}.*\n\n",
        sweep.axis
    );
    s += &row(&[
        "curve".into(),
        "expected order".into(),
        "expected slope".into(),
        "measured slope (all points)".into(),
        format!("measured slope (largest {top})"),
    ]);
    s += &row(&vec!["---".to_string(); 5]);
    for c in &sweep.curves {
        s += &row(&[
            curve_name(sweep, c),
            c.expected.clone(),
            format!("{:.1}", c.expected_slope),
            slope_cell(c.slope_all),
            slope_cell(c.slope_top),
        ]);
    }
    s += &slopes_legend(sweep, top);
    s
}

/// The size axis's column: what the size is, and its symbol in the
/// expected orders.
fn axis_definition(sweep: &Sweep) -> (String, &'static str) {
    match sweep.axis.as_str() {
        "triangles" => (
            "the caster's triangles n, the size the row ran at: a torus of v minor × 2v major segments, two triangles a quad (4·v²), on a floor".into(),
            "n",
        ),
        "shadow map" => (
            "the shadow map's size in texels, s² for a side of s texels: lesson 01's variant `res_<s>`, all sizes in one process".into(),
            "s",
        ),
        "screen" => (
            "the frame's size, width×height in pixels (P = width · height): the default scene rendered at each size".into(),
            "P",
        ),
        "lights" => (
            format!(
                "the number of lights N in the scene, on a circle above lesson 01's floor and casters ({}: see the caption)",
                if sweep.lesson == "lesson_02" {
                    "spot lights, one 1024² shadow map each"
                } else {
                    "point lights"
                }
            ),
            "N",
        ),
        _ => ("the size of the problem the row ran at".into(), "x"),
    }
}

/// The legend of a sweep's points table.
fn points_legend(sweep: &Sweep, head: &[String], passes: &[String], counters: &[String]) -> String {
    let frames = sweep.frames;
    let spread = format!("median [interquartile range] of the point's {frames} timed frames, ms");
    let gpu = if sweep.timing_source == "cpu_wall" {
        "the frame's passes, each submitted and timed on its own by the CPU's wall clock, summed"
    } else {
        "the GPU's time for the whole frame, from its first pass's start timestamp to its last pass's end"
    };
    let mut own: Vec<(String, String)> = vec![
        (sweep.axis.clone(), axis_definition(sweep).0),
        (
            "variant".into(),
            format!("{}'s variant the row ran (its `--variant` name)", sweep.lesson.replace('_', " ")),
        ),
        (
            "frame ms".into(),
            format!("the frame's wall-clock cost, from the start of recording to the GPU's completion: {spread}"),
        ),
        ("GPU ms".into(), format!("{gpu}: {spread}")),
        (
            "misclassified %".into(),
            "the receiver pixels classified differently from the exact reference (lit where V ≥ ½), in % of the receiver pixels of every light".into(),
        ),
    ];
    for p in passes {
        let d = crate::legend::PASSES
            .iter()
            .find(|(n, _)| *n == p.as_str())
            .map_or("the pass of that name", |(_, d)| d);
        own.push((
            format!("`{p}` ms"),
            format!("{d}: {spread}; — where the variant has no such pass"),
        ));
    }
    for c in counters {
        let Some((_, d)) = crate::legend::COUNTERS
            .iter()
            .find(|(n, _)| *n == c.as_str())
        else {
            continue;
        };
        own.push((
            format!("`{c}`"),
            format!(
                "{}; in one frame; — where the variant does not report it",
                d.replace(
                    "of those, ",
                    "of the volume fragments that reach the stencil, "
                )
            ),
        ));
    }
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    crate::legend::legend_own(head, &own)
}

/// The legend of a sweep's slopes table.
fn slopes_legend(sweep: &Sweep, top: usize) -> String {
    let axis = &sweep.axis;
    let x = axis_definition(sweep).1;
    let multi = distinct_variants(sweep).len() > 1;
    let curve = format!(
        "what is fitted against the {axis} {x}: {}a time's median (GPU ms: the GPU's time for the frame; `` `pass` ms ``: that pass's time), or a counter (`` `name` ``) in one frame",
        if multi {
            "the variant, where the curve is one variant's (none named: every variant's points together); "
        } else {
            ""
        }
    );
    let head = [
        "curve".to_string(),
        "expected order".into(),
        "expected slope".into(),
        "measured slope (all points)".into(),
        format!("measured slope (largest {top})"),
    ];
    let own = [
        ("curve", curve),
        (
            "expected order",
            format!("how the curve should grow with {x}, from what the algorithm does (O(1): not at all)"),
        ),
        (
            "expected slope",
            "the log-log slope that order means once fixed costs are small: O(1) → 0, O(√n) → 0.5, O(n) → 1, O(s²) → 2".into(),
        ),
        (
            "measured slope (all points)",
            format!("the least-squares slope of log(value) against log({x}) over every point of the curve; — where it is not defined (a value of 0, or a single point)"),
        ),
        (
            head[4].as_str(),
            format!("the same over the curve's largest {top} sizes, where fixed costs weigh least"),
        ),
    ];
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (*a, b.as_str())).collect();
    crate::legend::legend_own(&head, &own)
}

/// Where each variant of a sweep with stops stops: the largest size it ran
/// and the first it was left out at, with the lesson's reason.
fn stops_table(sweep: &Sweep) -> String {
    if sweep.stops.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "\n*Where each variant stops on {} ({}): the largest {} it ran, and the lesson's line where it left the variant out.*\n\n",
        sweep.adapter, sweep.backend, sweep.axis
    );
    s += &row(&[
        "variant".into(),
        format!("largest {} run", sweep.axis),
        "left out at".into(),
        "why".into(),
    ]);
    s += &row(&vec!["---".to_string(); 4]);
    let mut variants = distinct_variants(sweep);
    for t in &sweep.stops {
        if !variants.contains(&t.variant) {
            variants.push(t.variant.clone());
        }
    }
    for v in variants {
        let largest = (sweep.points.iter())
            .filter(|p| p.variant == v)
            .max_by(|a, b| a.x.total_cmp(&b.x))
            .map_or("—".to_string(), |p| p.label.clone());
        let stop = (sweep.stops.iter())
            .filter(|t| t.variant == v)
            .min_by(|a, b| a.x.total_cmp(&b.x));
        let (at, why) = stop.map_or(("—".into(), "ran every size".into()), |t| {
            (t.label.clone(), t.why.clone())
        });
        s += &row(&[format!("`{v}`"), largest, at, why]);
    }
    let axis = &sweep.axis;
    let head = [
        "variant".to_string(),
        format!("largest {axis} run"),
        "left out at".into(),
        "why".into(),
    ];
    let own = [
        (
            "variant".to_string(),
            format!("{}'s variant (its `--variant` name)", sweep.lesson.replace('_', " ")),
        ),
        (
            head[1].clone(),
            format!("the largest size (the {axis} column's) at which the variant ran (— where it ran at none)"),
        ),
        (
            "left out at".into(),
            format!("the smallest size (the {axis} column's) at which the lesson refused to run the variant (— where it ran every size)"),
        ),
        (
            "why".into(),
            "the lesson's own line: the buffer the variant would need there, its size, and the adapter's limit it passes".into(),
        ),
    ];
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    s += &crate::legend::legend_own(&head, &own);
    s
}

/// The points the "largest sizes" slope uses.
const SIZES_TOP: usize = 3;

// ---------------------------------------------------------------------------
// Running the sweeps.

/// What a sweep shows and expects, before it runs.
struct Plan {
    name: &'static str,
    lesson: &'static str,
    title: &'static str,
    axis: &'static str,
    /// The plots' x-axis label.
    x_label: &'static str,
    scene: String,
    variants: &'static [&'static str],
    passes: &'static [&'static str],
    counters: &'static [&'static str],
    /// (variant, key, unit, expected order, expected slope)
    curves: Vec<(&'static str, &'static str, Unit, &'static str, f64)>,
}

/// One run of a sweep: a scene (or the default), a frame size, the x of
/// each variant.
struct Step {
    scene: Option<PathBuf>,
    width: u32,
    height: u32,
    variants: Vec<&'static str>,
    /// x and label, for every variant of the run (lesson_01 runs all its
    /// resolutions at once: one x each).
    xs: Vec<(&'static str, f64, String)>,
}

/// Runs the scaling sweeps (all, or the one named `only`) and writes
/// book/src/generated/scaling/*.json and *.md and
/// book/src/figures/scaling/*.svg. `work` is a scratch folder (meshes,
/// scenes, run outputs).
pub fn run(
    runner: &Runner,
    root: &Path,
    work: &Path,
    backend: &str,
    bar: &ProgressBar,
    only: Option<&str>,
) -> Result<()> {
    let work = work.join("scaling");
    std::fs::create_dir_all(&work)?;
    let generated = generated_dir(root);
    let figures = root.join("book/src/figures/scaling");
    std::fs::create_dir_all(&generated)?;
    std::fs::create_dir_all(&figures)?;

    let mut sweeps = plans(&work)?;
    if let Some(name) = only {
        let names: Vec<&str> = sweeps.iter().map(|(p, _)| p.name).collect();
        if !names.contains(&name) {
            bail!("sweep: no sweep {name:?} (one of {})", names.join(", "));
        }
        sweeps.retain(|(p, _)| p.name == name);
    }
    let total: usize = sweeps.iter().map(|(_, steps)| steps.len()).sum();
    bar.inc_length(total as u64);
    for (plan, steps) in &sweeps {
        let sweep = measure(runner, plan, steps, &work, backend, bar)?;
        write(
            &generated.join(format!("{}.json", sweep.name)),
            &(serde_json::to_string_pretty(&sweep)? + "\n"),
        )?;
        write(&generated.join(table_file(&sweep)), &table(&sweep))?;
        plot(&sweep, plan.x_label, &figures)?;
    }
    // The records read back to the same tables (what the drift test checks).
    for sweep in load_sweeps(root)? {
        let path = generated.join(table_file(&sweep));
        let md = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        if md != table(&sweep) {
            bail!(
                "{}: the record does not read back to its table",
                path.display()
            );
        }
    }
    Ok(())
}

/// The six sweeps and their runs; writes the meshes and scenes they need.
fn plans(work: &Path) -> Result<Vec<(Plan, Vec<Step>)>> {
    let mut out = Vec::new();

    // 1. Triangles: a torus at rising tessellation.
    let mut l02 = Vec::new();
    let mut l05 = Vec::new();
    for v in TORUS_MINOR_ROUTES {
        let dir = work.join(format!("torus_{v}"));
        std::fs::create_dir_all(&dir)?;
        let tris = write_torus(&dir.join("torus.obj"), 2 * v, v)?;
        let s02 = dir.join("lesson_02.toml");
        write(&s02, &torus_scene(Light::Directional))?;
        let s05 = dir.join("lesson_05.toml");
        write(&s05, &torus_scene(Light::Point))?;
        let x = tris as f64;
        if TORUS_MINOR.contains(&v) {
            l02.push(Step {
                scene: Some(s02),
                width: WIDTH,
                height: HEIGHT,
                variants: vec!["slope_hw"],
                xs: vec![("slope_hw", x, count(tris))],
            });
        }
        for route in ROUTES {
            l05.push(Step {
                scene: Some(s05.clone()),
                width: WIDTH,
                height: HEIGHT,
                variants: vec![route],
                xs: vec![(route, x, count(tris))],
            });
        }
    }
    let torus = "a floor and one torus of n triangles (4·v² for v = 16 … 512), generated";
    let torus_routes =
        "a floor and one torus of n triangles (4·v² for v = 16 … 1024), generated, one process per route and size";
    out.push((
        Plan {
            name: "triangles_lesson_02",
            lesson: "lesson_02",
            title: "Shadow map (lesson 02, slope_hw) against caster triangles",
            axis: "triangles",
            x_label: "caster triangles n (log)",
            scene: format!("{torus}, one directional light"),
            variants: &["slope_hw"],
            passes: &["shadow", "base", "lighting"],
            counters: &["shadow_texels_written", "shadow_fragments", "draws"],
            curves: vec![
                ("slope_hw", "total", Unit::Ms, "O(n)", 1.0),
                ("slope_hw", "shadow", Unit::Ms, "O(n)", 1.0),
                (
                    "slope_hw",
                    "shadow_texels_written",
                    Unit::Count,
                    "O(1)",
                    0.0,
                ),
                ("slope_hw", "shadow_fragments", Unit::Count, "O(1)", 0.0),
            ],
        },
        l02,
    ));
    out.push((
        Plan {
            name: "triangles_lesson_05",
            lesson: "lesson_05",
            title: "Shadow volumes (lesson 05) against caster triangles",
            axis: "triangles",
            x_label: "caster triangles n (log)",
            scene: format!("{torus_routes}, one point light"),
            variants: &ROUTES,
            passes: &[
                "cpu_total",
                "cpu_silhouette",
                "extrude",
                "volume",
                "base",
                "lighting",
            ],
            counters: &["volume_triangles", "volume_fragments", "stencil_updates"],
            curves: vec![
                ("zpass_cpu", "total", Unit::Ms, "O(n)", 1.0),
                ("zpass_compute", "cpu_total", Unit::Ms, "O(1)", 0.0),
                ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(n)", 1.0),
                ("zpass_cpu", "volume", Unit::Ms, "O(√n)", 0.5),
                ("zpass_quads", "total", Unit::Ms, "O(n)", 1.0),
                ("zpass_quads", "volume", Unit::Ms, "O(n)", 1.0),
                ("zpass_compute", "total", Unit::Ms, "O(n)", 1.0),
                ("zpass_compute", "extrude", Unit::Ms, "O(n)", 1.0),
                ("zpass_cpu", "volume_triangles", Unit::Count, "O(√n)", 0.5),
                ("zpass_quads", "volume_triangles", Unit::Count, "O(n)", 1.0),
                ("zpass_cpu", "volume_fragments", Unit::Count, "O(1)", 0.0),
                ("zpass_quads", "volume_fragments", Unit::Count, "O(1)", 0.0),
            ],
        },
        l05,
    ));

    // 2. Resolution: lesson_01's shadow-map sizes in one run; the volume
    // lesson's screen size.
    out.push((
        Plan {
            name: "resolution_lesson_01",
            lesson: "lesson_01",
            title: "Shadow map (lesson 01) against shadow-map resolution",
            axis: "shadow map",
            x_label: "shadow-map side s, texels (log)",
            scene: "the default scene (`scenes/lesson_01.toml`), all resolutions in one process"
                .into(),
            variants: &["res_256", "res_512", "res_1024", "res_2048", "res_4096"],
            passes: &["shadow", "base", "lighting"],
            counters: &["shadow_texels_written", "shadow_fragments"],
            curves: vec![
                ("*", "total", Unit::Ms, "O(s²)", 2.0),
                ("*", "shadow", Unit::Ms, "O(s²)", 2.0),
                ("*", "lighting", Unit::Ms, "O(1)", 0.0),
                ("*", "shadow_texels_written", Unit::Count, "O(s²)", 2.0),
            ],
        },
        vec![Step {
            scene: None,
            width: WIDTH,
            height: HEIGHT,
            variants: SHADOW_RES.iter().map(|r| r.0).collect(),
            xs: SHADOW_RES
                .iter()
                .map(|&(v, s)| (v, s as f64, format!("{s}²")))
                .collect(),
        }],
    ));
    out.push((
        Plan {
            name: "screen_lesson_05",
            lesson: "lesson_05",
            title: "Shadow volumes (lesson 05, zpass_cpu) against screen size",
            axis: "screen",
            x_label: "screen pixels P = width × height (log)",
            scene: "the default scene (`scenes/lesson_05.toml`: a point and a directional light)"
                .into(),
            variants: &["zpass_cpu"],
            passes: &["cpu_silhouette", "volume", "base", "lighting"],
            counters: &["volume_fragments", "stencil_updates", "volume_triangles"],
            curves: vec![
                ("zpass_cpu", "total", Unit::Ms, "O(P)", 1.0),
                ("zpass_cpu", "volume", Unit::Ms, "O(P)", 1.0),
                ("zpass_cpu", "lighting", Unit::Ms, "O(P)", 1.0),
                ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(1)", 0.0),
                ("zpass_cpu", "volume_fragments", Unit::Count, "O(P)", 1.0),
                ("zpass_cpu", "stencil_updates", Unit::Count, "O(P)", 1.0),
                ("zpass_cpu", "volume_triangles", Unit::Count, "O(1)", 0.0),
            ],
        },
        SCREENS
            .iter()
            .map(|&(w, h)| Step {
                scene: None,
                width: w,
                height: h,
                variants: vec!["zpass_cpu"],
                xs: vec![("zpass_cpu", (w * h) as f64, format!("{w}×{h}"))],
            })
            .collect(),
    ));

    // 3. Lights: the default casters under N lights.
    let mut l02 = Vec::new();
    let mut l05 = Vec::new();
    for n in LIGHTS {
        let dir = work.join(format!("lights_{n}"));
        std::fs::create_dir_all(&dir)?;
        let s02 = dir.join("lesson_02.toml");
        write(&s02, &lights_scene(n, Light::Spot))?;
        let s05 = dir.join("lesson_05.toml");
        write(&s05, &lights_scene(n, Light::Point))?;
        l02.push(Step {
            scene: Some(s02),
            width: WIDTH,
            height: HEIGHT,
            variants: vec!["slope_hw"],
            xs: vec![("slope_hw", n as f64, n.to_string())],
        });
        l05.push(Step {
            scene: Some(s05),
            width: WIDTH,
            height: HEIGHT,
            variants: vec!["zpass_cpu"],
            xs: vec![("zpass_cpu", n as f64, n.to_string())],
        });
    }
    let casters = "lesson 01's floor and four casters under N lights on a circle, generated";
    out.push((
        Plan {
            name: "lights_lesson_02",
            lesson: "lesson_02",
            title: "Shadow map (lesson 02, slope_hw) against the number of spot lights",
            axis: "lights",
            x_label: "spot lights N (log)",
            scene: format!("{casters} (spot lights, one 1024² map each)"),
            variants: &["slope_hw"],
            passes: &["shadow", "base", "lighting"],
            counters: &["shadow_texels_written", "draws"],
            curves: vec![
                ("slope_hw", "total", Unit::Ms, "O(N)", 1.0),
                ("slope_hw", "shadow", Unit::Ms, "O(N)", 1.0),
                ("slope_hw", "lighting", Unit::Ms, "O(N)", 1.0),
                (
                    "slope_hw",
                    "shadow_texels_written",
                    Unit::Count,
                    "O(N)",
                    1.0,
                ),
                ("slope_hw", "draws", Unit::Count, "O(N)", 1.0),
            ],
        },
        l02,
    ));
    out.push((
        Plan {
            name: "lights_lesson_05",
            lesson: "lesson_05",
            title: "Shadow volumes (lesson 05, zpass_cpu) against the number of point lights",
            axis: "lights",
            x_label: "point lights N (log)",
            scene: format!("{casters} (point lights)"),
            variants: &["zpass_cpu"],
            passes: &["cpu_silhouette", "volume", "base", "lighting"],
            counters: &["volume_triangles", "volume_fragments", "draws"],
            curves: vec![
                ("zpass_cpu", "total", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "volume", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "lighting", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "volume_triangles", Unit::Count, "O(N)", 1.0),
                ("zpass_cpu", "volume_fragments", Unit::Count, "O(N)", 1.0),
                ("zpass_cpu", "draws", Unit::Count, "O(N)", 1.0),
            ],
        },
        l05,
    ));
    Ok(out)
}

/// Runs a sweep's steps and makes its record.
fn measure(
    runner: &Runner,
    plan: &Plan,
    steps: &[Step],
    work: &Path,
    backend: &str,
    bar: &ProgressBar,
) -> Result<Sweep> {
    let mut points: Vec<SweepPoint> = Vec::new();
    let mut stops: Vec<SweepStop> = Vec::new();
    let mut first: Option<Report> = None;
    for (i, step) in steps.iter().enumerate() {
        bar.set_message(format!("scaling {} ({}/{})", plan.name, i + 1, steps.len()));
        let args = RunArgs {
            lesson: plan.lesson,
            scene: step.scene.as_deref(),
            width: step.width,
            height: step.height,
            frames: FRAMES,
            variants: &step.variants,
            backend: Some(backend),
            adapter: Some(manifest::ADAPTER),
            warm_up_ms: None,
            fragile: false,
        };
        let out = work.join("runs").join(plan.name).join(format!("p{i}"));
        let report = match runner.run(&args, &out) {
            Ok(r) => r,
            // A variant whose buffers pass the adapter's limits: the lesson
            // refuses it by name in one line; where it stops is a result.
            Err(e) if step.variants.len() == 1 && limit_line(&e.to_string()).is_some() => {
                let (variant, x, label) = &step.xs[0];
                let why = limit_line(&e.to_string()).unwrap_or_default();
                let own = format!("{}: ", plan.lesson);
                stops.push(SweepStop {
                    x: *x,
                    label: label.clone(),
                    variant: variant.to_string(),
                    why: why.strip_prefix(&own).unwrap_or(&why).to_string(),
                });
                bar.inc(1);
                continue;
            }
            Err(e) => {
                return Err(e)
                    .with_context(|| format!("scaling sweep {}, point {}", plan.name, i + 1))
            }
        };
        for (variant, x, label) in &step.xs {
            let v = report
                .variants
                .iter()
                .find(|v| v.name == *variant)
                .with_context(|| format!("{}: no variant {variant} in the report", plan.lesson))?;
            let total = v
                .timing_samples_ms
                .get("total")
                .with_context(|| format!("{}: {variant} has no total time", plan.lesson))?;
            points.push(SweepPoint {
                x: *x,
                label: label.clone(),
                variant: variant.to_string(),
                total: Stat::of(total),
                // The sweep's passes, and the frame cost and CPU time.
                passes: plan
                    .passes
                    .iter()
                    .chain(&[FRAME, CPU_TOTAL])
                    .filter_map(|&k| v.timing_samples_ms.get(k).map(|s| (k.into(), Stat::of(s))))
                    .collect(),
                counters: plan
                    .counters
                    .iter()
                    .filter_map(|&k| v.counters.get(k).map(|&n| (k.into(), n)))
                    .collect(),
                misclassified_pct: v.error.misclassified_pct,
            });
        }
        first.get_or_insert(report);
        bar.inc(1);
    }
    let Some(first) = first else {
        bail!("scaling sweep {} has no points", plan.name);
    };
    let present = |k: &str, counter: bool| {
        points.iter().any(|p| {
            if counter {
                p.counters.contains_key(k)
            } else {
                p.passes.contains_key(k)
            }
        })
    };
    let passes: Vec<String> = plan
        .passes
        .iter()
        .filter(|k| present(k, false))
        .map(|k| k.to_string())
        .collect();
    let counters: Vec<String> = plan
        .counters
        .iter()
        .filter(|k| present(k, true))
        .map(|k| k.to_string())
        .collect();
    let variants: Vec<String> = plan.variants.iter().map(|v| v.to_string()).collect();
    let mut curves = Vec::new();
    for &(variant, key, unit, expected, expected_slope) in &plan.curves {
        let mine: Vec<&str> = if variant == "*" {
            variants.iter().map(|v| v.as_str()).collect()
        } else {
            vec![variant]
        };
        let pts: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| mine.contains(&p.variant.as_str()))
            .filter_map(|p| value(p, key, unit).map(|y| (p.x, y)))
            .collect();
        if pts.is_empty() {
            continue; // the lesson does not report this key
        }
        let slope = |pts: &[(f64, f64)]| {
            let xs: Vec<f64> = pts.iter().map(|p| p.0).collect();
            let ys: Vec<f64> = pts.iter().map(|p| p.1).collect();
            Some(plots::loglog_slope(&xs, &ys)).filter(|s| s.is_finite())
        };
        let top = &pts[pts.len().saturating_sub(SIZES_TOP)..];
        curves.push(SweepCurve {
            variant: if variant == "*" {
                variants.join(", ")
            } else {
                variant.into()
            },
            key: key.into(),
            unit,
            expected: expected.into(),
            expected_slope,
            slope_all: slope(&pts),
            slope_top: slope(top),
        });
    }
    let single_size = steps.iter().all(|s| (s.width, s.height) == (WIDTH, HEIGHT));
    Ok(Sweep {
        name: plan.name.into(),
        lesson: plan.lesson.into(),
        title: plan.title.into(),
        axis: plan.axis.into(),
        scene: plan.scene.clone(),
        adapter: first.adapter.name.clone(),
        backend: first.adapter.backend.clone(),
        width: if single_size { WIDTH } else { 0 },
        height: if single_size { HEIGHT } else { 0 },
        frames: first.frames,
        timing_source: crate::record::timing_source(&first),
        passes,
        counters,
        points,
        curves,
        stops,
    })
}

/// The lesson's line about a buffer that passes one of the adapter's
/// limits (lesson 05's `fit`), from a failed run's message, or `None`.
fn limit_line(message: &str) -> Option<String> {
    let line = message.lines().last()?;
    let limits = ["(max_buffer_size = ", "(max_storage_buffer_binding_size = "];
    if !limits.iter().any(|l| line.contains(l)) {
        return None;
    }
    let why = line.rsplit_once("failed: ").map_or(line, |(_, w)| w);
    Some(why.trim_start_matches("error: ").to_string())
}

/// A point's value of `key` (a time's median, or a counter).
fn value(p: &SweepPoint, key: &str, unit: Unit) -> Option<f64> {
    match unit {
        Unit::Ms if key == "total" => Some(p.total.median),
        Unit::Ms => p.passes.get(key).map(|s| s.median),
        Unit::Count => p.counters.get(key).map(|&n| n as f64),
    }
}

/// The sweep's two log-log plots: times, and counters.
fn plot(sweep: &Sweep, x_label: &str, figures: &Path) -> Result<()> {
    for (unit, suffix, y_label) in [
        (Unit::Ms, "time", "median ms (log)"),
        (Unit::Count, "counters", "count per frame (log)"),
    ] {
        let curves: Vec<Curve> = sweep
            .curves
            .iter()
            .filter(|c| c.unit == unit)
            .filter_map(|c| {
                let mine: Vec<&str> = c.variant.split(", ").collect();
                let (xs, ys): (Vec<f64>, Vec<f64>) = sweep
                    .points
                    .iter()
                    .filter(|p| mine.contains(&p.variant.as_str()))
                    .filter_map(|p| value(p, &c.key, unit).map(|y| (p.x, y)))
                    .filter(|&(_, y)| y > 0.0)
                    .unzip();
                (!xs.is_empty()).then(|| Curve {
                    name: curve_name(sweep, c).replace('`', ""),
                    xs,
                    ys,
                    expected: c.expected.clone(),
                })
            })
            .collect();
        if curves.is_empty() {
            continue;
        }
        let what = if unit == Unit::Ms { "time" } else { "counters" };
        let title = format!("{}: {what}", sweep.title);
        let path = figures.join(format!("{}_{suffix}.svg", sweep.name));
        plots::scaling_plot(&path, &title, x_label, y_label, &curves)?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Generated meshes and scenes.

#[derive(Clone, Copy, PartialEq)]
enum Light {
    Directional,
    Point,
    Spot,
}

/// A closed torus (major radius 1, minor 0.35) of `major × minor` quads,
/// two triangles each, with shared vertices: every edge has two faces.
/// Returns the triangle count.
fn write_torus(path: &Path, major: u32, minor: u32) -> Result<u64> {
    let (big, small) = (1.0f64, 0.35f64);
    let mut s = String::with_capacity((major * minor) as usize * 80);
    s += &format!("# torus {major}×{minor}, written by the book generator's scaling sweep\n");
    for i in 0..major {
        let u = std::f64::consts::TAU * i as f64 / major as f64;
        for j in 0..minor {
            let v = std::f64::consts::TAU * j as f64 / minor as f64;
            let r = big + small * v.cos();
            let _ = writeln!(
                s,
                "v {:.6} {:.6} {:.6}",
                r * u.cos(),
                small * v.sin(),
                r * u.sin()
            );
        }
    }
    let id = |i: u32, j: u32| (i % major) * minor + (j % minor) + 1;
    for i in 0..major {
        for j in 0..minor {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            // Outward normals, counter-clockwise seen from outside.
            let _ = writeln!(s, "f {a} {d} {c}\nf {a} {c} {b}");
        }
    }
    write(path, &s)?;
    Ok(2 * major as u64 * minor as u64)
}

const CAMERA_02: &str = "[camera]\neye = [0.8, 3.4, 6.6]\ntarget = [0.0, 0.6, 0.2]\nup = [0.0, 1.0, 0.0]\nfov_y_deg = 45.0\nnear = 0.1\nfar = 50.0\n";
const CAMERA_05: &str = "[camera]\neye = [3.6, 3.4, 5.2]\ntarget = [0.0, 0.6, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_deg = 45.0\nnear = 0.1\nfar = \"infinite\"\n";
const AMBIENT: &str = "\n[ambient]\ncolor = [0.12, 0.12, 0.15]\n";

/// A floor and the torus (`torus.obj` beside the scene), tilted, one light.
fn torus_scene(light: Light) -> String {
    let (camera, light) = match light {
        Light::Directional => (
            CAMERA_02,
            "type = \"directional\"\ndirection = [0.55, -0.75, 0.45]",
        ),
        _ => (
            CAMERA_05,
            "type = \"point\"\nposition = [1.5, 4.0, 1.0]\nrange = 14.0",
        ),
    };
    format!(
        "# Generated by the book's scaling sweep: a floor and one torus.\n{camera}{AMBIENT}
[[lights]]
{light}
color = [1.0, 0.97, 0.9]

[[objects]]
mesh = \"plane\"
scale = [8.0, 1.0, 8.0]
color = [0.75, 0.75, 0.72]

[[objects]]
mesh = \"torus.obj\"
translate = [0.0, 1.2, 0.0]
rotate_deg = [55.0, 20.0, 0.0]
scale = 1.2
color = [0.85, 0.7, 0.3]
"
    )
}

/// lesson_01's floor and casters under `n` lights on a circle above them.
fn lights_scene(n: u32, light: Light) -> String {
    let camera = if light == Light::Spot {
        CAMERA_02
    } else {
        CAMERA_05
    };
    let mut s = format!(
        "# Generated by the book's scaling sweep: the default casters under {n} lights.\n{camera}{AMBIENT}"
    );
    let target = [0.0f64, 0.4, 0.0];
    let c = 1.0 / n as f64;
    for k in 0..n {
        let a = std::f64::consts::TAU * (k as f64 + 0.25) / n as f64;
        let p = [3.5 * a.cos(), 4.5, 3.5 * a.sin()];
        let _ = write!(s, "\n[[lights]]\n");
        match light {
            Light::Spot => {
                let d = [target[0] - p[0], target[1] - p[1], target[2] - p[2]];
                let _ = write!(
                    s,
                    "type = \"spot\"\nposition = [{:.4}, {:.4}, {:.4}]\ndirection = [{:.4}, {:.4}, {:.4}]\nrange = 20.0\nspot_angle_deg = 80.0\n",
                    p[0], p[1], p[2], d[0], d[1], d[2]
                );
            }
            _ => {
                let _ = write!(
                    s,
                    "type = \"point\"\nposition = [{:.4}, {:.4}, {:.4}]\nrange = 14.0\n",
                    p[0], p[1], p[2]
                );
            }
        }
        let _ = writeln!(s, "color = [{c:.4}, {c:.4}, {c:.4}]");
    }
    s += "
[[objects]]
mesh = \"plane\"
scale = [7.0, 1.0, 7.0]
color = [0.75, 0.75, 0.72]

[[objects]]
mesh = \"cube\"
translate = [-1.4, 0.5, 0.3]
rotate_deg = [0.0, 25.0, 0.0]
color = [0.8, 0.35, 0.3]

[[objects]]
mesh = \"sphere\"
translate = [0.9, 0.6, 1.0]
scale = 1.2
color = [0.3, 0.55, 0.8]

[[objects]]
mesh = \"torus\"
translate = [0.6, 0.3, -1.4]
scale = 1.8
rotate_deg = [20.0, 0.0, 0.0]
color = [0.85, 0.7, 0.3]

[[objects]]
mesh = \"knot\"
translate = [-1.2, 0.8, -1.6]
scale = 1.3
color = [0.45, 0.75, 0.45]
";
    s
}

fn write(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}
