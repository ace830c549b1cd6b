//! Chapter 10's own table: how far the exact reference of a soft shadow is
//! from converged. The reference estimates the visible fraction of the
//! emitter with stratified rays (`common::reference::area`); rendered again
//! with four times the rays, it moves by its own sampling error. The
//! chapter compares that with the smallest difference between variants it
//! draws a conclusion from.
//!
//! CPU only, and deterministic but for the times (the rays' jitter is a
//! hash of the pixel and the ray): `tests/generated.rs` renders it again
//! and compares every figure but the times.

use std::path::Path;

use anyhow::{Context, Result};
use common::reference::area::AreaSampling;
use common::reference::metrics::{LIT_THRESHOLD, RECEIVER_MIN_N_DOT_L};
use common::reference::{try_render_reference_with, Reference};
use common::scene::camera::camera_matrices;
use common::scene::Scene;
use serde::{Deserialize, Serialize};

use crate::record::Record;
use crate::table::{count, header, ms, pct, row};

/// The scenes the convergence is measured on: every scene chapter 10
/// runs, with their titles; each scene's ranking threshold is its own row.
pub const SCENES: &[(&str, &str)] = &[
    ("scenes/lesson_10.toml", "default scene"),
    (
        "scenes/lesson_10_contact.toml",
        "cube and sphere resting on the floor, a 2° sun",
    ),
    (
        "scenes/lesson_10_large_light.toml",
        "a spot light of 1 m radius",
    ),
    (
        "scenes/lesson_10_overlap.toml",
        "blockers at two heights side by side",
    ),
    (
        "scenes/lesson_10_thin.toml",
        "a thin sheet's edge over a box",
    ),
    (
        "scenes/lesson_10_grazing.toml",
        "a 1° sun 80° from the floor's normal",
    ),
];

/// The pairs of variants whose difference in penumbra |ΔV| on the default
/// scene the chapter draws a conclusion from (section "Error against
/// time"); the smallest difference among them is held against the
/// reference's own error.
pub const CONCLUSIONS: &[(&str, &str)] = &[
    ("pcss", "pcf_wide_32"),
    ("pcss", "pcf_wide_16"),
    ("pcss", "hard_pcf"),
    ("vsm", "vsm_bleed_cut"),
    ("godot_soft_low", "bevy_pcss_or_pcf"),
];

/// Two variants the chapter sets side by side without ranking them; the
/// sentence says whether their difference is inside the reference's error.
pub const UNRANKED: (&str, &str) = ("pcss", "filament_pcss");

/// The file names under `generated/lesson_10/`.
pub const RECORD: &str = "convergence.json";
pub const TABLE: &str = "convergence.md";

/// One scene's reference at N and at 4N rays.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Row {
    pub scene: String,
    pub title: String,
    /// Rays a penumbra pixel gets: the full strata.
    pub rays_per_penumbra_pixel_n: u64,
    pub rays_per_penumbra_pixel_4n: u64,
    /// Every shadow ray each reference cast.
    pub shadow_rays_n: u64,
    pub shadow_rays_4n: u64,
    /// Receiver pixels with 0 < V < 1 in either reference.
    pub penumbra_pixels: u64,
    /// |V_N − V_4N| over those: mean, 99th percentile, max (fractions).
    pub mean_abs: f64,
    pub p99_abs: f64,
    pub max_abs: f64,
    /// Receiver pixels lit (V ≥ ½) in one reference and not the other.
    pub classification_differs: u64,
    /// Wall-clock time of each reference, ms.
    pub ms_n: f64,
    pub ms_4n: f64,
}

/// The convergence record: where it was measured, and one row a scene.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct Convergence {
    /// The CPU, in words, and the threads the reference ran on.
    pub cpu: String,
    pub threads: usize,
    pub width: u32,
    pub height: u32,
    pub rows: Vec<Row>,
}

impl Convergence {
    /// The reference's own sampling error, in % of V: the largest mean
    /// |V_N − V_4N| over the scenes measured.
    pub fn reference_error(&self) -> f64 {
        self.rows
            .iter()
            .map(|r| 100.0 * r.mean_abs)
            .fold(0.0, f64::max)
    }

    /// Each scene's own sampling error, in % of V, by the scene as a
    /// record names it (`default` for the lesson's default scene, at any
    /// size): the threshold a ranking on that scene uses.
    pub fn errors_by_scene(&self) -> ReferenceErrors {
        let mut by_scene: std::collections::BTreeMap<String, f64> = (self.rows.iter())
            .map(|r| (r.scene.clone(), 100.0 * r.mean_abs))
            .collect();
        if let Some(own) = self.rows.iter().find(|r| r.scene == SCENES[0].0) {
            by_scene.insert("default".into(), 100.0 * own.mean_abs);
        }
        ReferenceErrors {
            by_scene,
            largest: self.reference_error(),
        }
    }
}

/// The soft reference's own sampling error per scene (% of V), and the
/// largest, for a scene the convergence table has no row of.
#[derive(Clone, Debug)]
pub struct ReferenceErrors {
    pub by_scene: std::collections::BTreeMap<String, f64>,
    pub largest: f64,
}

impl ReferenceErrors {
    /// The threshold for a ranking on `scene`.
    pub fn of(&self, scene: &str) -> f64 {
        self.by_scene.get(scene).copied().unwrap_or(self.largest)
    }
}

/// The rays a penumbra pixel gets with `s`: `side²`.
fn rays_per_penumbra_pixel(s: AreaSampling) -> u64 {
    s.rays()
}

/// Renders one scene's reference at N and 4N and compares them.
pub fn measure(root: &Path, scene: &str, title: &str, width: u32, height: u32) -> Result<Row> {
    let path = root.join(scene);
    let s = Scene::load(&path).with_context(|| format!("convergence: {}", path.display()))?;
    let view_proj = camera_matrices(&s, width, height).view_proj;
    let n = AreaSampling::DEFAULT;
    let a = try_render_reference_with(&s, view_proj, width, height, n)?;
    let b = try_render_reference_with(&s, view_proj, width, height, n.times_four())?;
    let (mut diffs, mut differs) = (Vec::new(), 0u64);
    for k in (0..s.lights.len()).filter(|&k| a.area_light[k]) {
        for p in 0..a.hits.len() {
            if !receiver(&a, k, p) {
                continue;
            }
            let (va, vb) = (a.visibility[k][p], b.visibility[k][p]);
            differs += u64::from((va >= LIT_THRESHOLD) != (vb >= LIT_THRESHOLD));
            let soft = |v: f32| v > 0.0 && v < 1.0;
            if soft(va) || soft(vb) {
                diffs.push((va - vb).abs() as f64);
            }
        }
    }
    let mean = diffs.iter().sum::<f64>() / diffs.len().max(1) as f64;
    Ok(Row {
        scene: scene.to_string(),
        title: title.to_string(),
        rays_per_penumbra_pixel_n: rays_per_penumbra_pixel(n),
        rays_per_penumbra_pixel_4n: rays_per_penumbra_pixel(n.times_four()),
        shadow_rays_n: a.shadow_rays,
        shadow_rays_4n: b.shadow_rays,
        penumbra_pixels: diffs.len() as u64,
        mean_abs: mean,
        p99_abs: if diffs.is_empty() {
            0.0
        } else {
            common::measure::timing::quantile(&diffs, 0.99)
        },
        max_abs: diffs.iter().copied().fold(0.0, f64::max),
        classification_differs: differs,
        ms_n: a.ms,
        ms_4n: b.ms,
    })
}

/// A receiver of light `k` (as the error figures count them): geometry
/// hit, facing the light inside its reach.
fn receiver(r: &Reference, k: usize, p: usize) -> bool {
    r.hits[p].is_some() && r.lit_by[k][p] > RECEIVER_MIN_N_DOT_L
}

/// Every scene of [`SCENES`] at `width × height`.
pub fn measure_all(root: &Path, width: u32, height: u32) -> Result<Convergence> {
    let rows = SCENES
        .iter()
        .map(|(scene, title)| measure(root, scene, title, width, height))
        .collect::<Result<Vec<_>>>()?;
    Ok(Convergence {
        cpu: cpu_name(),
        threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
        width,
        height,
        rows,
    })
}

/// The CPU's model name (Linux), else "this machine's CPU".
fn cpu_name() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.split_whitespace().collect::<Vec<_>>().join(" "))
        })
        .unwrap_or_else(|| "this machine's CPU".into())
}

/// A visibility difference as the tables print it: in % of V (as the
/// penumbra |ΔV| % of the results table).
fn dv(x: f64) -> String {
    pct(100.0 * x)
}

/// The table, and the sentence comparing the default scene's mean
/// difference with the closest pair of variants in `results` (lesson 10's
/// default run).
pub fn table(c: &Convergence, results: Option<&Record>) -> String {
    let (n, n4) = (AreaSampling::DEFAULT, AreaSampling::DEFAULT.times_four());
    let mut s = format!(
        "*the exact reference on the CPU ({}, {} threads) · {}×{} · one image of each scene at N and at 4N rays: N = {}×{} strata wherever a conservative query of the BVH finds a caster in the cone from the point to the emitter or the emitter is partly below the point's horizon, no ray (V = 1) elsewhere; 4N = {}×{} · times: one run each, wall clock*\n\n",
        c.cpu,
        c.threads,
        c.width,
        c.height,
        n.side,
        n.side,
        n4.side,
        n4.side,
    );
    let head = [
        "scene".to_string(),
        "rays per penumbra pixel, N".into(),
        "rays per penumbra pixel, 4N".into(),
        "shadow rays, N".into(),
        "shadow rays, 4N".into(),
        "penumbra pixels".into(),
        "mean \\|V_N − V_4N\\| %".into(),
        "99th percentile %".into(),
        "max %".into(),
        "classification differs".into(),
        "N ms".into(),
        "4N ms".into(),
    ];
    s += &header(&head);
    for r in &c.rows {
        s += &row(&[
            format!("{} (`{}`)", r.title, r.scene),
            count(r.rays_per_penumbra_pixel_n),
            count(r.rays_per_penumbra_pixel_4n),
            count(r.shadow_rays_n),
            count(r.shadow_rays_4n),
            count(r.penumbra_pixels),
            dv(r.mean_abs),
            dv(r.p99_abs),
            dv(r.max_abs),
            count(r.classification_differs),
            ms(r.ms_n),
            ms(r.ms_4n),
        ]);
    }
    s += &crate::legend::legend_own(&head, LEGEND);
    s += &format!("\n{}\n", verdict(c, results));
    s
}

/// The sentence under the table, from the numbers.
pub fn verdict(c: &Convergence, results: Option<&Record>) -> String {
    let Some(own) = c.rows.iter().find(|r| r.scene == SCENES[0].0) else {
        return "*The default scene's convergence was not measured.*".into();
    };
    let penumbra = |name: &str| {
        let v = results?.variants.iter().find(|v| v.name == name)?;
        Some(100.0 * v.soft.as_ref()?.penumbra_mean_abs)
    };
    let gap_of =
        |(a, b): (&'static str, &'static str)| Some(((penumbra(a)? - penumbra(b)?).abs(), a, b));
    let Some((gap, a, b)) = CONCLUSIONS
        .iter()
        .filter_map(|&pair| gap_of(pair))
        .min_by(|x, y| x.0.total_cmp(&y.0))
    else {
        return "*No soft-shadow figures in `lesson_10/results.json`: run `workbook book --only lesson_10`.*".into();
    };
    let (pa, pb) = (penumbra(a).unwrap_or(0.0), penumbra(b).unwrap_or(0.0));
    let mean = 100.0 * own.mean_abs;
    let so = if mean < gap {
        format!(
            "below that difference ({:.1} times smaller): the difference is the variants', not the reference's sampling",
            gap / mean.max(f64::MIN_POSITIVE)
        )
    } else {
        format!(
            "not below that difference ({:.1} times as large): the reference's sampling alone could make a difference that size, so the two figures cannot be read as one variant being nearer the exact soft shadow than the other",
            mean / gap.max(f64::MIN_POSITIVE)
        )
    };
    let mut text = format!(
        "On the default scene the reference moves by {} % of V on average over its penumbra when its rays are quadrupled. The smallest difference between variants the chapter draws a conclusion from is `{a}` against `{b}`: penumbra \\|ΔV\\| {} % and {} %, {} points apart (`lesson_10/results`). The reference's own error is {so}.",
        pct(mean),
        pct(pa),
        pct(pb),
        pct(gap),
    );
    if let Some((gap, a, b)) = gap_of(UNRANKED) {
        let inside = match gap < mean {
            true => "inside the reference's own error: the chapter does not rank them",
            false => "outside the reference's own error",
        };
        text += &format!(" `{a}` and `{b}` are {} points apart, {inside}.", pct(gap));
    }
    text
}

/// The convergence table's columns.
const LEGEND: &[(&str, &str)] = &[
    ("scene", "the scene both references were rendered from, at the book's resolution, with the lesson's camera"),
    ("rays per penumbra pixel, N", "the shadow rays a pixel in the penumbra gets with the reference's default sampling: the full strata, since in the penumbra a caster is in the cone toward the emitter"),
    ("rays per penumbra pixel, 4N", "the same with four times the rays (`AreaSampling::times_four`: the strata's side doubled)"),
    ("shadow rays, N", "every shadow ray the reference with the default sampling cast, all pixels (`Reference::shadow_rays`): a pixel with no caster in its cone toward the emitter and the emitter wholly above its horizon casts none"),
    ("shadow rays, 4N", "the same for the reference with four times the rays"),
    ("penumbra pixels", "receiver pixels (geometry facing the light inside its reach, as the error figures count them) whose visibility is strictly between 0 and 1 in either reference"),
    ("mean \\|V_N − V_4N\\| %", "the mean of |V_N − V_4N| over those pixels, in % of V: how far the default reference, the one every results table is measured against, moves with four times the rays; an estimate of its own sampling error (the 4N reference has one too, about half as large)"),
    ("99th percentile %", "the 99th percentile of |V_N − V_4N| over those pixels, in % of V"),
    ("max %", "the largest |V_N − V_4N| over those pixels, in % of V"),
    ("classification differs", "receiver pixels lit (V ≥ ½) in one reference and shadowed in the other: the pixels whose misclassified % the reference's sampling could change"),
    ("N ms", "wall-clock time of the reference with the default sampling, BVH build and primary rays included, one run, ms"),
    ("4N ms", "the same with four times the rays"),
];

/// Measures the convergence, writes `generated/lesson_10/convergence.{json,md}`
/// and returns it.
pub fn write_all(
    root: &Path,
    generated: &Path,
    records: &[Record],
    width: u32,
    height: u32,
) -> Result<Convergence> {
    let c = measure_all(root, width, height)?;
    let results = records
        .iter()
        .find(|r| r.lesson == "lesson_10" && r.run == "results");
    let dir = generated.join("lesson_10");
    std::fs::create_dir_all(&dir)?;
    for (name, text) in [
        (RECORD, serde_json::to_string_pretty(&c)?),
        (TABLE, table(&c, results)),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(c)
}
