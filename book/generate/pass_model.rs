//! What a shadow map's own passes should cost on an adapter: a model of
//! the passes that build the map, fitted on the adapter's own runs, that
//! each variant's measured passes are set against
//! (`generated/lesson_NN/tap_floor.md`, [`crate::taps`]).
//!
//! The work a map pass does is counted by the lessons: the texels of the
//! maps it clears and stores (`shadow_map_size`² times the cascades or the
//! cube faces drawn) and the fragments it rasterises (`shadow_fragments`).
//! The model is least squares on every variant of the set that counts
//! both, of every lesson the set holds:
//!
//! ```text
//! ms = a · Mtexels + b · Mfragments + c
//! ```
//!
//! fitted on the relative error (each point weighted by 1 / its time), since
//! what is read is the ratio measured / model, and a 0.03 ms pass must
//! count as much as a 300 ms one. Where the set's runs do not determine
//! both rates, the model keeps the texels alone, `ms = a · Mtexels + c`:
//! where the two counts move together over the points (their correlation
//! above [`COLLINEAR`]: of the H200's lessons 03 and 10, only lesson 03
//! counts its fragments, and its maps differ only in size; lesson 01's
//! map-size ladder alone would be the same),
//! or where the fit gives a negative rate (lavapipe: its runs of lessons 02
//! and 04 spread too widely for a cost per fragment to come out). Which
//! model a set got is printed with its table. A lesson that does not count
//! its fragments (lesson 10) is set against the texels-alone model only.
//!
//! A variant's map passes are its `shadow` pass plus, where it has them,
//! the passes that turn the map into what its lookup reads (a variance
//! map's `moments` and `blur`, the min/max chain's `min_max`): the model
//! counts only the depth map, so those extra passes show as the variant's
//! excess over the model.

use glam::{DMat2, DMat3, DVec2, DVec3};

use crate::origins::changed;
use crate::record::{Record, Timing, VariantRecord};
use common::measure::counters::{CASCADES, FACES_RENDERED, SHADOW_FRAGMENTS, SHADOW_MAP_SIZE};

/// The passes that build a variant's map.
pub const MAP_PASSES: &[&str] = &["shadow", "moments", "blur", "min_max"];

/// Why a model keeps the texels alone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Alone {
    /// The fragments move with the texels over the set's points.
    Together,
    /// With the fragments too, a rate came out negative.
    Negative,
}

/// Above this correlation of texels and fragments over a set's points,
/// the two rates are not told apart: the model keeps the texels alone.
pub const COLLINEAR: f64 = 0.99;

/// A fitted model of the map passes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassModel {
    /// Milliseconds per million map texels.
    pub per_mtexel: f64,
    /// Milliseconds per million rasterised fragments; `None`: the texels
    /// alone.
    pub per_mfragment: Option<f64>,
    /// Milliseconds a map pass costs before its first texel.
    pub fixed: f64,
    /// Why it keeps the texels alone, where it does.
    pub alone: Option<Alone>,
    /// The points it was fitted on.
    pub points: usize,
    /// The largest and smallest measured / model over those points.
    pub spread: (f64, f64),
}

impl PassModel {
    /// The model's time for a map of `texels` texels and `fragments`
    /// fragments; `None` when the model needs the fragments and the
    /// variant does not count them.
    pub fn predict(&self, texels: f64, fragments: Option<f64>) -> Option<f64> {
        let mut ms = self.fixed + self.per_mtexel * texels / 1e6;
        if let Some(b) = self.per_mfragment {
            ms += b * fragments? / 1e6;
        }
        Some(ms)
    }

    /// The model as the table's heading writes it.
    pub fn formula(&self) -> String {
        let frag = self
            .per_mfragment
            .map_or(String::new(), |b| format!(" + {} ms × Mfragments", fine(b)));
        format!(
            "ms = {} ms × Mtexels{frag} + {} ms",
            fine(self.per_mtexel),
            fine(self.fixed)
        )
    }
}

/// A rate to three significant figures.
fn fine(x: f64) -> String {
    if x.abs() >= 10.0 {
        format!("{x:.1}")
    } else if x.abs() >= 1.0 {
        format!("{x:.2}")
    } else {
        format!("{x:.3}")
    }
}

/// The texels a variant's map passes cover: `shadow_map_size`² times the
/// cascades (lesson 09) or the cube faces drawn (lesson 04, an empty face
/// is cleared once and then skipped). Lessons that do not count the size
/// name it: lesson 01's `res_N` and lesson 04's `*_N` variants by their
/// last number, lesson 04's ports by their cards
/// (`workbook::lesson_04::peers`). `None` where none says.
pub fn map_texels(lesson: &str, v: &VariantRecord) -> Option<f64> {
    let c = &v.counters;
    let size = match c.get(SHADOW_MAP_SIZE.name) {
        Some(&n) => n,
        None => named_size(lesson, &v.name)?,
    };
    let layers = c.get(CASCADES.name).copied().unwrap_or(1)
        * c.get(FACES_RENDERED.name).copied().unwrap_or(1);
    Some((size * size * layers) as f64)
}

/// A map size that a variant's name or card gives, where its lesson does
/// not count it.
fn named_size(lesson: &str, name: &str) -> Option<u64> {
    use workbook::lesson_04::peers::{BEVY_POINT, LEARNOPENGL_1TAP, LEARNOPENGL_PCF20};
    match (lesson, name) {
        ("lesson_04", "learnopengl_1tap") => return Some(LEARNOPENGL_1TAP.size.into()),
        ("lesson_04", "learnopengl_pcf20") => return Some(LEARNOPENGL_PCF20.size.into()),
        ("lesson_04", "bevy_point") => return Some(BEVY_POINT.size.into()),
        ("lesson_01" | "lesson_04", _) => {}
        _ => return None,
    }
    let n: u64 = name.rsplit('_').next()?.parse().ok()?;
    n.is_power_of_two().then_some(n)
}

/// The median of a variant's map passes, when its times are quotable and
/// it has a `shadow` pass.
pub fn map_ms(t: Option<&Timing>) -> Option<f64> {
    let t = t.filter(|t| t.stable())?;
    t.passes.get("shadow")?;
    Some(
        MAP_PASSES
            .iter()
            .filter_map(|p| t.passes.get(*p))
            .map(|s| s.median)
            .sum(),
    )
}

/// One point of the fit: texels, fragments, milliseconds.
type Point = (f64, f64, f64);

/// The set's points: every variant of its default runs that counts its
/// map's texels and fragments and has quotable times, less those changed
/// since the set's `commit` (their code is no longer the lesson's).
pub fn points(records: &[Record], commit: Option<&str>) -> Vec<Point> {
    lesson_points(records, commit)
        .into_iter()
        .map(|(_, p)| p)
        .collect()
}

/// The lessons the set's [`points`] come from, `01, 03`.
pub fn point_lessons(records: &[Record], commit: Option<&str>) -> String {
    let mut lessons: Vec<&str> = lesson_points(records, commit)
        .into_iter()
        .map(|(l, _)| l.strip_prefix("lesson_").unwrap_or(l))
        .collect();
    lessons.dedup();
    lessons.join(", ")
}

/// [`points`], each with its lesson.
fn lesson_points<'a>(records: &'a [Record], commit: Option<&str>) -> Vec<(&'a str, Point)> {
    let mut out = Vec::new();
    for r in records.iter().filter(|r| r.run == "results") {
        for v in &r.variants {
            if commit.is_some_and(|c| changed(c, &r.lesson, &v.name).is_some()) {
                continue;
            }
            let (Some(t), Some(&f), Some(ms)) = (
                map_texels(&r.lesson, v),
                v.counters.get(SHADOW_FRAGMENTS.name),
                map_ms(v.timing.as_ref()),
            ) else {
                continue;
            };
            out.push((r.lesson.as_str(), (t, f as f64, ms)));
        }
    }
    out
}

/// The model of a set's map passes ([`points`]); `None` when the points
/// determine not even the cost per texel.
pub fn fit(points: &[Point]) -> Option<PassModel> {
    let apart = correlation(points).abs() < COLLINEAR && distinct(points) >= 4;
    let both = apart.then(|| two_rates(points)).flatten();
    let model = match both {
        Some(m) if m.per_mtexel >= 0.0 && m.per_mfragment.is_some_and(|b| b >= 0.0) => m,
        _ => {
            let why = if apart {
                Alone::Negative
            } else {
                Alone::Together
            };
            let m = texels_alone(points).filter(|m| m.per_mtexel >= 0.0)?;
            PassModel {
                alone: Some(why),
                ..m
            }
        }
    };
    Some(with_spread(model, points))
}

/// The model's worst ratios over its own points.
fn with_spread(mut m: PassModel, points: &[Point]) -> PassModel {
    let ratios: Vec<f64> = points
        .iter()
        .filter_map(|&(t, f, ms)| Some(ms / m.predict(t, Some(f))?))
        .collect();
    let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    m.points = points.len();
    m.spread = (lo, hi);
    m
}

/// How many distinct (texels, fragments) the points have.
fn distinct(points: &[Point]) -> usize {
    let mut seen: Vec<(u64, u64)> = points.iter().map(|p| (p.0 as u64, p.1 as u64)).collect();
    seen.sort_unstable();
    seen.dedup();
    seen.len()
}

/// Pearson's correlation of the texels and the fragments over the points
/// (1 when either does not vary: nothing tells them apart).
pub fn correlation(points: &[Point]) -> f64 {
    let n = points.len() as f64;
    if n < 2.0 {
        return 1.0;
    }
    let mt = points.iter().map(|p| p.0).sum::<f64>() / n;
    let mf = points.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut stt, mut sff, mut stf) = (0.0, 0.0, 0.0);
    for p in points {
        stt += (p.0 - mt).powi(2);
        sff += (p.1 - mf).powi(2);
        stf += (p.0 - mt) * (p.1 - mf);
    }
    if stt <= 0.0 || sff <= 0.0 {
        return 1.0;
    }
    stf / (stt * sff).sqrt()
}

/// Weighted least squares of ms on (Mtexels, Mfragments, 1), weights
/// 1 / ms² on the squared residuals (the relative error).
fn two_rates(points: &[Point]) -> Option<PassModel> {
    let mut ata = DMat3::ZERO;
    let mut atb = DVec3::ZERO;
    for &(t, f, ms) in points {
        let w = 1.0 / ms;
        let x = DVec3::new(t / 1e6, f / 1e6, 1.0) * w;
        ata += DMat3::from_cols(x * x.x, x * x.y, x * x.z);
        atb += x * (ms * w);
    }
    if ata.determinant().abs() < 1e-12 {
        return None;
    }
    let s = ata.inverse() * atb;
    Some(PassModel {
        per_mtexel: s.x,
        per_mfragment: Some(s.y),
        fixed: s.z,
        alone: None,
        points: 0,
        spread: (0.0, 0.0),
    })
}

/// The same with the texels alone.
fn texels_alone(points: &[Point]) -> Option<PassModel> {
    let mut ata = DMat2::ZERO;
    let mut atb = DVec2::ZERO;
    for &(t, _, ms) in points {
        let w = 1.0 / ms;
        let x = DVec2::new(t / 1e6, 1.0) * w;
        ata += DMat2::from_cols(x * x.x, x * x.y);
        atb += x * (ms * w);
    }
    if ata.determinant().abs() < 1e-12 {
        return None;
    }
    let s = ata.inverse() * atb;
    Some(PassModel {
        per_mtexel: s.x,
        per_mfragment: None,
        fixed: s.y,
        alone: None,
        points: 0,
        spread: (0.0, 0.0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_known_rates_are_recovered_where_the_counts_differ() {
        // 0.1 ms a million texels, 0.05 a million fragments, 0.02 fixed:
        // maps of several sizes, with few and with many fragments per texel.
        let model = |t: f64, f: f64| 0.02 + 0.1 * t / 1e6 + 0.05 * f / 1e6;
        let pts: Vec<Point> = [
            (1.0e6, 0.5e6),
            (4.0e6, 2.0e6),
            (5.0e6, 1.0e6),
            (4.0e6, 3.5e6),
        ]
        .iter()
        .map(|&(t, f)| (t, f, model(t, f)))
        .collect();
        let m = fit(&pts).expect("a model");
        assert!((m.per_mtexel - 0.1).abs() < 1e-9, "{m:?}");
        assert!(
            (m.per_mfragment.expect("two rates") - 0.05).abs() < 1e-9,
            "{m:?}"
        );
        assert!((m.fixed - 0.02).abs() < 1e-9, "{m:?}");
        assert!((m.spread.0 - 1.0).abs() < 1e-9 && (m.spread.1 - 1.0).abs() < 1e-9);
    }

    #[test]
    fn counts_that_move_together_keep_the_texels_alone() {
        // Fragments a share of the texels, within a rasteriser's few at the
        // edges (one scene, maps of five sizes: the H200's lesson 03): no
        // cost per fragment is told apart, though a fit would give one.
        let pts: Vec<Point> = [0.25e6, 0.5e6, 1.0e6, 2.0e6, 4.0e6]
            .iter()
            .enumerate()
            .map(|(i, &t)| {
                let wobble = if i % 2 == 0 { 1.004 } else { 0.996 };
                (t, 0.53 * t * wobble, 0.003 + 0.12 * t / 1e6)
            })
            .collect();
        assert!(correlation(&pts) > COLLINEAR);
        assert!(
            two_rates(&pts).is_some(),
            "the fit alone would give a cost per fragment"
        );
        let m = fit(&pts).expect("a model");
        assert_eq!(m.per_mfragment, None);
        assert_eq!(m.alone, Some(Alone::Together));
        assert!((m.per_mtexel - 0.12).abs() < 1e-9, "{m:?}");
        // A variant that does not count fragments is still predicted.
        assert!(m.predict(1.0e6, None).is_some());
    }

    #[test]
    fn a_negative_rate_is_no_model() {
        // More fragments, less time: a fit would give a negative cost per
        // fragment; the texels alone are kept.
        let pts: Vec<Point> = vec![
            (1.0e6, 0.5e6, 1.0),
            (1.0e6, 3.0e6, 0.5),
            (4.0e6, 1.0e6, 3.0),
            (4.0e6, 4.0e6, 2.0),
            (2.0e6, 2.0e6, 1.5),
        ];
        let m = fit(&pts).expect("a model");
        assert_eq!(m.per_mfragment, None, "{m:?}");
        assert_eq!(m.alone, Some(Alone::Negative));
        assert!(m.per_mtexel > 0.0);
    }

    #[test]
    fn map_sizes_come_from_the_counters_or_the_names() {
        let v = |name: &str, counters: &[(&str, u64)]| VariantRecord {
            name: name.into(),
            receiver_pixels: 1,
            misclassified_pct: 0.0,
            false_shadow_pct: 0.0,
            false_lit_pct: 0.0,
            mean_abs: 0.0,
            coverage_mismatch_pct: 0.0,
            counters: counters.iter().map(|(k, n)| (k.to_string(), *n)).collect(),
            timing: None,
            camera_path: None,
            classes: Vec::new(),
            soft: None,
            fragile: None,
        };
        let k4 = v("k4", &[(SHADOW_MAP_SIZE.name, 1024), (CASCADES.name, 4)]);
        assert_eq!(map_texels("lesson_09", &k4), Some(4.0 * 1024.0 * 1024.0));
        let cube = v("linear_256", &[(FACES_RENDERED.name, 5)]);
        assert_eq!(map_texels("lesson_04", &cube), Some(5.0 * 256.0 * 256.0));
        let port = v("bevy_point", &[(FACES_RENDERED.name, 6)]);
        assert_eq!(map_texels("lesson_04", &port), Some(6.0 * 1024.0 * 1024.0));
        assert_eq!(
            map_texels("lesson_01", &v("res_512", &[])),
            Some(512.0 * 512.0)
        );
        // A name with no size, in a lesson that counts none: no guess.
        assert_eq!(map_texels("lesson_01", &v("res_x", &[])), None);
        assert_eq!(map_texels("lesson_02", &v("bias_1tx", &[])), None);
    }
}
