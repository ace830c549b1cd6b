//! Chapter 09's own tables and plots, from the record of its default run:
//! shimmer over the camera path, the error per cascade, and shadow-map
//! texels per 100 m against view depth (perspective aliasing).

use std::path::Path;

use anyhow::{Context, Result};

use crate::plots::{self, Curve};
use crate::record::Record;
use crate::table::{count, header, pct, row};

/// The counters `texels_per_100m_at_<D>m`, by distance D.
const ALIASING_PREFIX: &str = "texels_per_100m_at_";

/// Writes `generated/lesson_09/{shimmer,cascades,aliasing}.md` and
/// `figures/lesson_09/{shimmer,aliasing}.svg` from lesson 09's default run.
pub fn write_all(generated: &Path, figures: &Path, records: &[Record]) -> Result<()> {
    let Some(r) = records
        .iter()
        .find(|r| r.lesson == "lesson_09" && r.run == "results")
    else {
        return Ok(());
    };
    let dir = generated.join("lesson_09");
    std::fs::create_dir_all(&dir)?;
    for (name, text) in [
        ("shimmer.md", shimmer_table(r)),
        ("cascades.md", cascades_table(r)),
        ("aliasing.md", aliasing_table(r)),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    let fig = figures.join("lesson_09");
    std::fs::create_dir_all(&fig)?;
    shimmer_plot(&fig.join("shimmer.svg"), r)?;
    aliasing_plot(&fig.join("aliasing.svg"), r)
}

/// Lesson 09's variants (`lessons/lesson_09/main.rs`), as the legends
/// define them. Every one spends about 2048² texels: K maps of 2048 / √K.
const VARIANTS: &str = "lesson 09's variant, each spending about 2048² shadow-map texels (K cascades of 2048 / √K a side): `single_2048`: lesson 01's one 2048² map fitted to the scene's bounds, the baseline; `k1` … `k4`: K cascades, practical splits (λ = 0.9), each fitted with a bounding sphere, snapped to its texel grid and reaching back towards the light; `k4_uniform`, `k4_log`: `k4` with uniform or logarithmic splits; `k4_aabb`: `k4` with a tight box instead of the sphere, snapped to its own, changing, texel size; `k4_nosnap`: `k4` not snapped; `k4_aabb_nosnap`: the tight box, not snapped (the naive fit); `k4_noextend`: `k4` with boxes only as deep as the sphere, so casters outside it are lost; `k4_blend`: `k4` fading into the next cascade over the last 10 % of each; `k4_nocull`: `k4` drawing every caster into every cascade, over the whole map (no caster culling: the same image, drawn at full cost)";

fn caption(r: &Record, what: &str) -> String {
    format!(
        "*{} · {}×{} · the default scene (`scenes/{}.toml`) · {what}*\n\n",
        r.adapter_label(),
        r.width,
        r.height,
        r.lesson
    )
}

/// One row a variant with a camera path: shimmer, the flips, and the
/// spread of the per-frame error.
pub fn shimmer_table(r: &Record) -> String {
    let frames = r
        .variants
        .iter()
        .find_map(|v| v.camera_path.as_ref().map(|p| p.frames))
        .unwrap_or(0);
    let mut s = caption(
        r,
        &format!(
            "camera path of {frames} frames (a pan, then a dolly); % of the receivers per pair of consecutive frames, pooled over the pairs. Shimmer: frame i's view with frame i + 1's fit against frame i's own (world-locked). Screen-space: consecutive frames, flips the reference does not make"
        ),
    );
    let head = [
        "variant".to_string(),
        "shimmer % (world-locked)".into(),
        "screen-space mismatch %".into(),
        "technique flips %".into(),
        "reference flips %".into(),
        "misclassified % per frame (min–max)".into(),
    ];
    s += &header(&head);
    for v in &r.variants {
        let Some(p) = &v.camera_path else {
            continue;
        };
        let min = p
            .misclassified_pct_per_frame
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let max = p
            .misclassified_pct_per_frame
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        s += &row(&[
            format!("`{}`", v.name),
            pct(p.shimmer_pct),
            pct(p.screen_mismatch_pct),
            pct(p.technique_flip_pct),
            pct(p.reference_flip_pct),
            if min.is_finite() {
                format!("{}–{}", pct(min), pct(max))
            } else {
                "—".into()
            },
        ]);
    }
    s += &crate::legend::legend_own(&head, SHIMMER_LEGEND);
    s
}

/// The shimmer table's own columns.
const SHIMMER_LEGEND: &[(&str, &str)] = &[
        ("variant", VARIANTS),
        ("shimmer % (world-locked)", "of the receiver pixels (every light) whose surface frame i + 1 sees too, those whose shadow state changes when frame i's view is rendered with frame i + 1's cascade fit instead of its own: the view and the reference stay put, so every change is the fit moving; pooled over the path's pairs of consecutive frames, in %"),
        ("screen-space mismatch %", "of the pixels that are receivers in both of two consecutive frames (every light), those whose shadow state the technique changes while the exact reference's stays the same; pooled over the pairs, in %"),
        ("technique flips %", "of those pixels, the ones whose shadow state the technique changes from one frame to the next (the view moves, so edges sweep across the screen), in %"),
        ("reference flips %", "the same for the exact reference: the changes the moving view makes by itself, the same for every variant, in %"),
        ("misclassified % per frame (min–max)", "the lowest and the highest of the path's per-frame misclassified %: in each frame, the receiver pixels (every light) classified differently from the exact reference, in % of them; — where the variant has no frame"),
];

/// One row a variant with classes; per cascade: its share of the receiver
/// pixels and its misclassified %.
pub fn cascades_table(r: &Record) -> String {
    let k = r
        .variants
        .iter()
        .map(|v| v.classes.len())
        .max()
        .unwrap_or(0);
    let mut s = caption(
        r,
        "per cascade: misclassified % of that cascade's pixels (its pixels)",
    );
    let mut head = vec!["variant".to_string(), "overall %".into()];
    head.extend((0..k).map(|i| format!("cascade {i}")));
    let mut own: Vec<(String, String)> = vec![
        ("variant".into(), VARIANTS.into()),
        ("overall %".into(), "the variant's misclassified % over all its receiver pixels: those classified differently from the exact reference, in % of the receiver pixels of every light (the run's main figure)".into()),
    ];
    own.extend((0..k).map(|i| {
        let which = match i {
            0 => "the cascade nearest the camera (a single map's only one)".to_string(),
            _ => format!("the next cascade out from the camera, after cascade {}", i - 1),
        };
        (
            format!("cascade {i}"),
            format!("{which}: the misclassified % of the receiver pixels whose view depth selects it (as the lit pass picks the cascade), in % of those pixels, and in parentheses how many they are; — where the variant has fewer cascades"),
        )
    }));
    s += &header(&head);
    for v in r.variants.iter().filter(|v| !v.classes.is_empty()) {
        let mut cells = vec![format!("`{}`", v.name), pct(v.misclassified_pct)];
        for i in 0..k {
            cells.push(v.classes.get(i).map_or("—".into(), |c| {
                format!("{} ({})", pct(c.misclassified_pct), count(c.pixels))
            }));
        }
        s += &row(&cells);
    }
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    s += &crate::legend::legend_own(&head, &own);
    s
}

/// The distances (m) of the `texels_per_100m_at_<D>m` counters, ascending.
fn distances(r: &Record) -> Vec<(u64, String)> {
    let mut d: Vec<(u64, String)> = r
        .variants
        .iter()
        .flat_map(|v| v.counters.keys())
        .filter_map(|k| {
            let m = k.strip_prefix(ALIASING_PREFIX)?.strip_suffix('m')?;
            Some((m.parse().ok()?, k.clone()))
        })
        .collect();
    d.sort();
    d.dedup();
    d
}

/// Shadow-map texels per 100 m at each view depth, per variant (by
/// depth, nearest first).
pub fn aliasing_table(r: &Record) -> String {
    let d = distances(r);
    let mut s = caption(
        r,
        "shadow-map texels per 100 m of scene, in the cascade that holds each view depth",
    );
    let mut head = vec!["variant".to_string()];
    head.extend(d.iter().map(|(m, _)| format!("{m} m")));
    let mut own: Vec<(String, String)> = vec![("variant".into(), VARIANTS.into())];
    own.extend(d.iter().map(|(m, k)| {
        (
            format!("{m} m"),
            format!("shadow-map texels per 100 m of scene in the cascade that holds view depth {m} m (the counter `{k}`): 100 × the map's side in texels ÷ that cascade's width in metres, rounded; more is finer; — where the variant does not report it"),
        )
    }));
    s += &header(&head);
    for v in &r.variants {
        if !d.iter().any(|(_, k)| v.counters.contains_key(k)) {
            continue;
        }
        let mut cells = vec![format!("`{}`", v.name)];
        cells.extend(
            d.iter()
                .map(|(_, k)| v.counters.get(k).map_or("—".into(), |&n| count(n))),
        );
        s += &row(&cells);
    }
    let own: Vec<(&str, &str)> = own.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    s += &crate::legend::legend_own(&head, &own);
    s
}

fn shimmer_plot(path: &Path, r: &Record) -> Result<()> {
    let bars: Vec<(String, f64, f64)> = r
        .variants
        .iter()
        .filter_map(|v| {
            let p = v.camera_path.as_ref()?;
            Some((v.name.clone(), p.shimmer_pct, p.screen_mismatch_pct))
        })
        .collect();
    if bars.is_empty() {
        return Ok(());
    }
    let title = format!(
        "Lesson 09: shimmer over the camera path ({}, {}×{})",
        r.adapter_label(),
        r.width,
        r.height
    );
    plots::bars(
        path,
        &title,
        "% of the receivers, per pair of consecutive frames",
        (
            "shimmer (world-locked): the fit moves, the view stays",
            "screen-space: flips the reference does not make",
        ),
        &bars,
    )
}

fn aliasing_plot(path: &Path, r: &Record) -> Result<()> {
    let d = distances(r);
    // Variants with the same density at every distance (the fit's options
    // that do not change the texel: snapping, the blend) share one line,
    // named after all of them, so that no line hides under another.
    let mut curves: Vec<Curve> = Vec::new();
    for v in &r.variants {
        if !d.iter().any(|(_, k)| v.counters.contains_key(k)) {
            continue;
        }
        let (xs, ys): (Vec<f64>, Vec<f64>) = d
            .iter()
            .filter_map(|(m, k)| Some((*m as f64, *v.counters.get(k)? as f64)))
            .unzip();
        match curves.iter_mut().find(|c| c.xs == xs && c.ys == ys) {
            Some(c) => c.name = format!("{}, {}", c.name, v.name),
            None => curves.push(Curve {
                name: v.name.clone(),
                xs,
                ys,
                expected: String::new(),
            }),
        }
    }
    if curves.is_empty() {
        return Ok(());
    }
    let title = format!(
        "Lesson 09: texels per 100 m on the ground against view distance ({}, {}×{})",
        r.adapter_label(),
        r.width,
        r.height
    );
    plots::scaling_plot(
        path,
        &title,
        "view distance, m (log)",
        "shadow-map texels per 100 m (log)",
        &curves,
    )
}
