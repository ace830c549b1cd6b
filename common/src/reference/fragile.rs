//! The receivers a rasteriser could flip, measured by the run itself.
//!
//! Two conformant GPUs draw the same frame a little differently: where a
//! triangle's edge crosses a pixel's centre, which pixel it covers is decided
//! by how finely each snaps vertices (Vulkan asks for at least 1/16 of a
//! pixel, [`JITTER_PX`]); where a receiver's depth and a shadow map's texel
//! are within a few ulps, which side of the compare it lands on is decided by
//! each one's rounding. Neither is the technique's doing, so the error
//! figures of one technique on two adapters differ by those pixels, and only
//! those.
//!
//! The runner counts them: it draws the variant again with the camera moved
//! by ± [`JITTER_PX`] of a pixel ([`JITTERS`]), which moves every receiver by
//! less than any two rasterisers disagree on, and asks which receivers then
//! change surface or change side of the lit threshold. A figure that counts
//! pixels can move by at most that many of them; a figure that averages
//! |ΔV| by at most the mean change. [`Fragile::bounds`] gives each figure's
//! bound in the figure's own units, and the snapshots and the book's drift
//! test allow a figure to move between adapters by its bound
//! (`tests/support/tolerance.rs`).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::reference::metrics::RECEIVER_MIN_N_DOT_L;
use crate::reference::soft_metrics::{BLEEDING_THRESHOLD, LIT_THRESHOLD};
use crate::reference::Reference;

/// How far the camera moves (pixels, in x and in y): the coarsest sub-pixel
/// grid a conformant rasteriser may snap vertices to (Vulkan's
/// `subPixelPrecisionBits` >= 4).
pub const JITTER_PX: f64 = 1.0 / 16.0;

/// The offsets tried, in units of [`JITTER_PX`]: three directions 120°
/// apart. Their components along any direction sum to zero, so every edge,
/// whatever its direction, is crossed from both sides.
pub const JITTERS: [[f64; 2]; 3] = [[0.0, 1.0], [-0.866_025, -0.5], [0.866_025, -0.5]];

/// What a run's sub-pixel jitter showed, over every light.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Default)]
pub struct Fragile {
    /// The jitter, pixels ([`JITTER_PX`]), and how many offsets were drawn.
    pub jitter_px: f64,
    pub offsets: u32,
    /// Receivers (summed over lights) that changed surface or side of the
    /// lit threshold under some offset.
    pub flipped_pixels: u64,
    /// Per error figure (its `ErrorStats` / `SoftError` field name), how far
    /// it can move if only what moved under the jitter moves: in the
    /// figure's own units.
    pub bounds: BTreeMap<String, f64>,
    /// Per counter, how far it moved under the offsets, summed over them:
    /// fragments that tie in a depth test, or cover a pixel's centre by a
    /// hair. Each offset moves other fragments, and another rasteriser may
    /// move any of them, so the moves add (as the flipped pixels do).
    #[serde(default)]
    pub counters: BTreeMap<String, u64>,
}

/// One frame's images: object id (0 = nothing) and one light's visibility.
#[derive(Clone, Copy)]
pub struct Images<'a> {
    pub id: &'a [u32],
    pub visibility: &'a [f32],
}

/// Numerators and denominators of the bounds of one or more lights.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    receivers: u64,
    flipped: u64,
    dv_sum: f64,
    penumbra: u64,
    penumbra_dv_sum: f64,
    umbra: u64,
    umbra_flipped: u64,
    umbra_bleed_flipped: u64,
    umbra_dv_sum: f64,
    soft: bool,
    /// Per pixel class (lesson 09's cascades): its name, receivers and
    /// flipped receivers.
    classes: Vec<(String, u64, u64)>,
}

impl Tally {
    /// Per-class bounds too: `names` and one class index per pixel (the
    /// lesson's `pixel_classes`).
    pub fn with_classes(names: &[String]) -> Tally {
        Tally {
            classes: names.iter().map(|n| (n.clone(), 0, 0)).collect(),
            ..Tally::default()
        }
    }

    /// Adds light `light`'s receivers: `base` is the frame measured,
    /// `moved` the same variant drawn at each jitter, `class_of` each
    /// pixel's class (see [`Tally::with_classes`]).
    pub fn add(
        &mut self,
        reference: &Reference,
        light: usize,
        base: Images,
        moved: &[Images],
        class_of: Option<&[u8]>,
    ) {
        let (ref_vis, lit_by) = (&reference.visibility[light], &reference.lit_by[light]);
        let soft = reference.area_light[light];
        self.soft |= soft;
        for p in 0..reference.hits.len() {
            let Some(hit) = reference.hits[p] else {
                continue;
            };
            // The receivers of `metrics::compare`: the GPU sees the
            // reference's surface, which faces the light.
            if base.id[p] != hit.object + 1 || lit_by[p] <= RECEIVER_MIN_N_DOT_L {
                continue;
            }
            let v = base.visibility[p];
            let (mut flip, mut bleed_flip, mut dv) = (false, false, 0.0f32);
            for m in moved {
                if m.id[p] != base.id[p] {
                    (flip, bleed_flip, dv) = (true, true, 1.0);
                    continue;
                }
                let w = m.visibility[p];
                flip |= (w >= LIT_THRESHOLD) != (v >= LIT_THRESHOLD);
                bleed_flip |= (w > BLEEDING_THRESHOLD) != (v > BLEEDING_THRESHOLD);
                dv = dv.max((w - v).abs());
            }
            self.receivers += 1;
            self.flipped += u64::from(flip);
            if let Some(c) = class_of.and_then(|c| self.classes.get_mut(c[p] as usize)) {
                c.1 += 1;
                c.2 += u64::from(flip);
            }
            self.dv_sum += f64::from(dv);
            if soft {
                let exact = ref_vis[p];
                if exact <= 0.0 {
                    self.umbra += 1;
                    self.umbra_flipped += u64::from(flip);
                    self.umbra_bleed_flipped += u64::from(bleed_flip);
                    self.umbra_dv_sum += f64::from(dv);
                } else if exact < 1.0 {
                    self.penumbra += 1;
                    self.penumbra_dv_sum += f64::from(dv);
                }
            }
        }
    }

    /// The bounds, pooled over the lights added.
    pub fn finish(&self, offsets: usize) -> Fragile {
        let share = |n: f64, of: u64| if of == 0 { 0.0 } else { n / of as f64 };
        let pct = |n: u64, of: u64| 100.0 * share(n as f64, of);
        let mut bounds = BTreeMap::new();
        let flipped = pct(self.flipped, self.receivers);
        for key in [
            "misclassified_pct",
            "false_shadow_pct",
            "false_lit_pct",
            "interior_misclassified_pct",
        ] {
            bounds.insert(key.to_string(), flipped);
        }
        bounds.insert("mean_abs".into(), share(self.dv_sum, self.receivers));
        for (name, receivers, flipped) in &self.classes {
            for key in ["misclassified_pct", "false_shadow_pct", "false_lit_pct"] {
                bounds.insert(format!("class {name} {key}"), pct(*flipped, *receivers));
            }
        }
        if self.soft {
            bounds.insert(
                "penumbra_mean_abs".into(),
                share(self.penumbra_dv_sum, self.penumbra),
            );
            bounds.insert(
                "umbra_misclassified_pct".into(),
                pct(self.umbra_flipped, self.umbra),
            );
            bounds.insert(
                "light_bleeding_pct".into(),
                pct(self.umbra_bleed_flipped, self.umbra),
            );
            bounds.insert(
                "umbra_mean_abs".into(),
                share(self.umbra_dv_sum, self.umbra),
            );
        }
        Fragile {
            jitter_px: JITTER_PX,
            offsets: offsets as u32,
            flipped_pixels: self.flipped,
            bounds,
            counters: BTreeMap::new(),
        }
    }
}

impl Fragile {
    /// The bounds of two runs together (two adapters, each measured): how
    /// far a figure may move between them. Each rasteriser flips only
    /// pixels its own run found fragile, so the images differ by at most
    /// both sets: every bound and counter move is the sum of the two (a key
    /// one run lacks counts as 0 there).
    pub fn plus(&self, other: &Fragile) -> Fragile {
        let mut bounds = self.bounds.clone();
        for (k, b) in &other.bounds {
            *bounds.entry(k.clone()).or_insert(0.0) += b;
        }
        let mut counters = self.counters.clone();
        for (k, n) in &other.counters {
            *counters.entry(k.clone()).or_insert(0) += n;
        }
        Fragile {
            jitter_px: self.jitter_px.max(other.jitter_px),
            offsets: self.offsets + other.offsets,
            flipped_pixels: self.flipped_pixels + other.flipped_pixels,
            bounds,
            counters,
        }
    }
}

/// Per counter, how far `moved` differ from `base`, summed over them (a
/// counter missing from one side moved by its whole value).
pub fn counter_moves(
    base: &BTreeMap<String, u64>,
    moved: &[BTreeMap<String, u64>],
) -> BTreeMap<String, u64> {
    base.iter()
        .map(|(k, &c)| {
            let sum = moved
                .iter()
                .map(|m| m.get(k).map_or(c, |&d| c.abs_diff(d)))
                .sum();
            (k.clone(), sum)
        })
        .collect()
}

/// The clip-space translation that moves the image by `px` pixels (x
/// right, y up) in a `width × height` frame: pre-multiply a view-projection
/// matrix by it.
pub fn jitter_matrix(px: [f64; 2], width: u32, height: u32) -> glam::Mat4 {
    let (tx, ty) = (2.0 * px[0] / width as f64, 2.0 * px[1] / height as f64);
    glam::Mat4::from_translation(glam::Vec3::new(tx as f32, ty as f32, 0.0))
}

#[cfg(test)]
mod tests {
    use super::Fragile;

    #[test]
    fn two_runs_bounds_add() {
        let a = Fragile {
            jitter_px: 0.0625,
            offsets: 3,
            flipped_pixels: 10,
            bounds: [("misclassified_pct".to_string(), 0.1)].into(),
            counters: [("stencil_updates".to_string(), 100)].into(),
        };
        let b = Fragile {
            flipped_pixels: 4,
            bounds: [
                ("misclassified_pct".to_string(), 0.05),
                ("mean_abs".to_string(), 0.01),
            ]
            .into(),
            counters: [("draws".to_string(), 1)].into(),
            ..a.clone()
        };
        let s = a.plus(&b);
        assert!((s.bounds["misclassified_pct"] - 0.15).abs() < 1e-12);
        assert_eq!(s.bounds["mean_abs"], 0.01);
        assert_eq!(s.counters["stencil_updates"], 100);
        assert_eq!(s.counters["draws"], 1);
        assert_eq!((s.flipped_pixels, s.offsets), (14, 6));
    }
}
