//! The error of a soft shadow (lesson 10's area lights), per class of
//! receiver: the umbra, the penumbra and the lit receivers of the exact
//! reference, the deep umbra's leak apart from the spill around the
//! penumbra, the receivers below their own horizon, and the distance between
//! the reference's and the variant's 10 % and 90 % contours (with the exact
//! distance transform it needs). [`super::metrics::compare`] calls
//! [`soft_error`] for a light with a size; the report pools the figures.

use serde::Serialize;

/// A pixel counts as lit from this visibility up.
pub const LIT_THRESHOLD: f32 = 0.5;
// ANCHOR: soft_error
/// The error of a soft shadow (an area light), beside `ErrorStats`' figures
/// over all receivers, per class of receiver.
///
/// Every receiver of the light falls in exactly one class, by the exact
/// reference's visibility `V_ref` there: the **umbra** (`V_ref = 0`, the
/// emitter wholly hidden), the **penumbra** (`0 < V_ref < 1`), the **lit**
/// side (`V_ref = 1`), or, when the reference flags it, **horizon-clipped**
/// (part of the emitter below the receiver's own tangent plane: `V_ref < 1`
/// there without any blocker, so it is kept out of the other three). Each
/// class's mean `|V − V_ref|` comes with its pixel count.
///
/// Inside the umbra and the lit side, [`RIM_PX`] splits what a technique
/// gets wrong near the shadow's edge (**spill**: a kernel too wide, or
/// placed a little off) from what it gets wrong far from it (**leak**:
/// light through the blocker, the variance maps' failure).
///
/// Fields added after the first five default to 0 (`None`) when a record
/// older than them is read.
#[derive(Serialize, serde::Deserialize, Clone, Debug, PartialEq)]
pub struct SoftError {
    /// Receivers in the reference's penumbra: 0 < V_ref < 1.
    pub penumbra_pixels: u64,
    /// Mean |V − V_ref| over those.
    pub penumbra_mean_abs: f64,
    /// Receivers in the reference's umbra: V_ref = 0, the emitter wholly hidden.
    pub umbra_pixels: u64,
    /// Of the umbra, the share (%) the technique calls lit (V > 0.5).
    pub umbra_misclassified_pct: f64,
    /// Of the umbra, the share (%) the technique lights by more than
    /// [`BLEEDING_THRESHOLD`], rim and deep umbra together: any light in
    /// the umbra. [`SoftError::leak_pct`] is the same in the deep umbra alone.
    pub light_bleeding_pct: f64,
    /// Mean |V − V_ref| (= mean V) over the umbra's `umbra_pixels`.
    #[serde(default)]
    pub umbra_mean_abs: f64,
    /// Receivers on the reference's lit side: V_ref = 1, the whole emitter seen.
    #[serde(default)]
    pub lit_pixels: u64,
    /// Mean |V − V_ref| (= mean 1 − V) over those: shadow where there is
    /// none (a blur spilling out of the penumbra, acne under a wide kernel).
    #[serde(default)]
    pub lit_mean_abs: f64,
    /// Umbra receivers farther than [`RIM_PX`] pixels from every receiver
    /// the reference lights at all (V_ref > 0): the deep umbra.
    #[serde(default)]
    pub deep_umbra_pixels: u64,
    /// Mean V over the deep umbra: light leaking through the blocker.
    #[serde(default)]
    pub leak_mean_abs: f64,
    /// Of the deep umbra, the share (%) the technique lights by more than
    /// [`BLEEDING_THRESHOLD`].
    #[serde(default)]
    pub leak_pct: f64,
    /// The receivers next to the penumbra: the umbra's rim (umbra receivers
    /// within [`RIM_PX`] pixels of one with V_ref > 0) and the lit side's
    /// fringe (lit receivers within [`RIM_PX`] pixels of one with
    /// V_ref < 1). The deep umbra, the rim and the lit side's interior
    /// (`lit_pixels` less the fringe) make up the umbra and the lit side.
    #[serde(default)]
    pub spill_pixels: u64,
    /// Mean |V − V_ref| over the `spill_pixels`: light spilling out of the
    /// penumbra into the umbra's rim, and shadow spilling into the lit side.
    #[serde(default)]
    pub spill_mean_abs: f64,
    /// Receivers the reference flags as horizon-clipped (the `horizon_clipped`
    /// argument of [`compare`]), kept out of every class above and of the
    /// contours; 0 where the reference gives no flag.
    #[serde(default)]
    pub horizon_clipped_pixels: u64,
    /// Mean |V − V_ref| over those.
    #[serde(default)]
    pub horizon_clipped_mean_abs: f64,
    /// The contour pixels, both images and both levels together, that
    /// [`SoftError::penumbra_width_error_px`] averages over.
    #[serde(default)]
    pub contour_pixels: u64,
    /// How far (pixels) the technique's 10 % and 90 % visibility contours
    /// lie from the reference's: the symmetric mean contour distance.
    ///
    /// For a level `c` (0.1, then 0.9), an image's `c`-contour is its
    /// receivers with V ≥ c that have a 4-neighbour receiver, on the same
    /// object, with V < c (horizon-clipped receivers left out). Every
    /// contour pixel of the reference is given its Euclidean distance
    /// (pixel centres) to the nearest contour pixel of the technique at the
    /// same level, and every contour pixel of the technique its distance to
    /// the reference's; the figure is the mean of all those distances,
    /// both levels pooled. A technique whose shadow edge is shifted by `s`
    /// pixels scores `s`; one with a hard edge in the middle of a penumbra
    /// `W` pixels wide, about 0.4 `W` (both contours are `W`·0.4 off); a
    /// blur `k` times too wide, about 0.4 (`k` − 1) `W`.
    ///
    /// A level at which neither image has a contour is left out; `None`
    /// (absent from `report.json`, `-` in the table) when one image has a
    /// contour at a level where the other has none (no distance to give),
    /// or when no level has a contour at all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penumbra_width_error_px: Option<f64>,
}

/// Light in the reference's umbra above this visibility is bleeding
/// ([`SoftError::light_bleeding_pct`], [`SoftError::leak_pct`]).
pub const BLEEDING_THRESHOLD: f32 = 0.1;

/// How far (pixels, Euclidean, centre to centre) the umbra's rim and the
/// lit side's fringe reach from the other side of the reference's shadow
/// edge ([`SoftError::spill_pixels`]); the umbra beyond is the deep umbra
/// ([`SoftError::deep_umbra_pixels`]).
///
/// Why 3: it is [`EDGE_MARGIN_PX`] + 1. The interior figures already
/// grant every edge 2 pixels, for what a pixel's footprint and a lookup's
/// texel do near an edge; and the reference can itself call the last
/// pixel of a penumbra umbra (its pilot rays miss a cap of the emitter
/// smaller than about 0.4 %, [`crate::reference::area`]), which moves its
/// umbra's edge by up to one more pixel. Light 4 or more pixels inside
/// the umbra is therefore not an edge placed a little wrong: it is light
/// through the blocker, or a filter several pixels wider than the penumbra
/// (both worth seeing). Too small a rim would call every blur's spill a
/// leak; a larger one would hide leaks in thin umbrae (a rim of `r` leaves
/// no deep umbra in an umbra narrower than 2`r` + 1 pixels).
pub const RIM_PX: f32 = 3.0;

/// The contour levels of [`SoftError::penumbra_width_error_px`]: the 10 %
/// and 90 % visibility lines, the penumbra's conventional width.
pub const CONTOUR_LEVELS: [f32; 2] = [0.1, 0.9];
// ANCHOR_END: soft_error

// ANCHOR: soft_images
/// One area light's images as [`soft_error`] reads them, every slice
/// `width × height`, row by row.
#[derive(Clone, Copy, Debug)]
pub struct SoftImages<'a> {
    pub width: u32,
    pub height: u32,
    /// The reference's object per pixel, 0 where nothing is hit
    /// ([`reference_object_ids`]): a contour runs between pixels of one object.
    pub object_id: &'a [u32],
    /// The receivers [`compare`] counts: the GPU and the reference see the
    /// same surface, which faces the light.
    pub receiver: &'a [bool],
    /// The reference's own receivers (a hit facing the light, whatever the
    /// GPU sees): they say where the umbra's rim and the deep umbra lie, so
    /// those do not move with a technique's coverage.
    pub reference_receiver: &'a [bool],
    /// The reference's visibility V_ref.
    pub exact: &'a [f32],
    /// The technique's visibility V.
    pub gpu: &'a [f32],
    /// The reference's horizon-clipped receivers, if it flags them.
    pub horizon_clipped: Option<&'a [bool]>,
}
// ANCHOR_END: soft_images

/// A receiver's class in [`SoftError`], by the reference's V_ref.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SoftClass {
    Umbra,
    Penumbra,
    Lit,
    HorizonClipped,
}

// ANCHOR: soft_error_fn
/// The [`SoftError`] of one area light's visibility (see its fields for
/// what each figure is).
///
/// Panics if a slice is not `width × height`.
pub fn soft_error(im: &SoftImages) -> SoftError {
    let (w, h) = (im.width as usize, im.height as usize);
    let n = w * h;
    let sizes = [
        im.object_id.len(),
        im.receiver.len(),
        im.reference_receiver.len(),
        im.exact.len(),
        im.gpu.len(),
    ];
    assert!(
        sizes
            .iter()
            .chain(im.horizon_clipped.map(<[bool]>::len).as_ref())
            .all(|&k| k == n),
        "soft_error: the images must be {w}x{h}"
    );
    let clipped = |p: usize| im.horizon_clipped.is_some_and(|c| c[p]);
    // The class of a pixel by the reference alone (`None`: not one of its
    // receivers), and of a receiver `compare` counts.
    let reference_class = |p: usize| -> Option<SoftClass> {
        let v = im.exact[p];
        Some(match () {
            _ if !im.reference_receiver[p] => return None,
            _ if clipped(p) => SoftClass::HorizonClipped,
            _ if v <= 0.0 => SoftClass::Umbra,
            _ if v >= 1.0 => SoftClass::Lit,
            _ => SoftClass::Penumbra,
        })
    };
    let class = |p: usize| reference_class(p).filter(|_| im.receiver[p]);

    // How far each pixel is from the lit side of the reference's shadow
    // edge (a receiver with V_ref > 0) and from its shadowed side (V_ref < 1).
    let lit_side: Vec<bool> = (0..n)
        .map(|p| {
            matches!(
                reference_class(p),
                Some(SoftClass::Penumbra | SoftClass::Lit)
            )
        })
        .collect();
    let shadowed_side: Vec<bool> = (0..n)
        .map(|p| {
            matches!(
                reference_class(p),
                Some(SoftClass::Penumbra | SoftClass::Umbra)
            )
        })
        .collect();
    let to_lit = distance_to(&lit_side, w, h);
    let to_shadowed = distance_to(&shadowed_side, w, h);

    // (pixels, Σ|ΔV|) per class and part of a class.
    #[derive(Default, Clone, Copy)]
    struct Sum {
        pixels: u64,
        abs: f64,
    }
    impl Sum {
        fn add(&mut self, d: f32) {
            self.pixels += 1;
            self.abs += d as f64;
        }
        fn mean(self) -> f64 {
            self.abs / self.pixels.max(1) as f64
        }
    }
    let [mut umbra, mut penumbra, mut lit, mut clip, mut deep, mut spill] = [Sum::default(); 6];
    let (mut umbra_lit, mut bleeding, mut leaking) = (0u64, 0u64, 0u64);
    for p in 0..n {
        let Some(c) = class(p) else { continue };
        let (v, d) = (im.gpu[p], (im.gpu[p] - im.exact[p]).abs());
        match c {
            SoftClass::Umbra => {
                umbra.add(d);
                umbra_lit += u64::from(v > LIT_THRESHOLD);
                bleeding += u64::from(v > BLEEDING_THRESHOLD);
                if to_lit[p] > RIM_PX {
                    deep.add(d);
                    leaking += u64::from(v > BLEEDING_THRESHOLD);
                } else {
                    spill.add(d);
                }
            }
            SoftClass::Penumbra => penumbra.add(d),
            SoftClass::Lit => {
                lit.add(d);
                if to_shadowed[p] <= RIM_PX {
                    spill.add(d);
                }
            }
            SoftClass::HorizonClipped => clip.add(d),
        }
    }
    let pct = |k: u64, of: u64| 100.0 * k as f64 / of.max(1) as f64;
    let (contour_pixels, penumbra_width_error_px) = contour_distance(
        im,
        &|p| matches!(class(p), Some(c) if c != SoftClass::HorizonClipped),
    );
    SoftError {
        penumbra_pixels: penumbra.pixels,
        penumbra_mean_abs: penumbra.mean(),
        umbra_pixels: umbra.pixels,
        umbra_misclassified_pct: pct(umbra_lit, umbra.pixels),
        light_bleeding_pct: pct(bleeding, umbra.pixels),
        umbra_mean_abs: umbra.mean(),
        lit_pixels: lit.pixels,
        lit_mean_abs: lit.mean(),
        deep_umbra_pixels: deep.pixels,
        leak_mean_abs: deep.mean(),
        leak_pct: pct(leaking, deep.pixels),
        spill_pixels: spill.pixels,
        spill_mean_abs: spill.mean(),
        horizon_clipped_pixels: clip.pixels,
        horizon_clipped_mean_abs: clip.mean(),
        contour_pixels,
        penumbra_width_error_px,
    }
}

/// [`SoftError::contour_pixels`] and
/// [`SoftError::penumbra_width_error_px`] over the pixels where `counts`.
fn contour_distance(im: &SoftImages, counts: &dyn Fn(usize) -> bool) -> (u64, Option<f64>) {
    let (w, h) = (im.width as usize, im.height as usize);
    // The pixels of `vis`'s `c`-contour: V ≥ c, a 4-neighbour below c on
    // the same object.
    let contour = |vis: &[f32], c: f32| -> Vec<bool> {
        (0..w * h)
            .map(|p| {
                let (x, y) = (p % w, p / w);
                let below =
                    |q: usize| counts(q) && im.object_id[q] == im.object_id[p] && vis[q] < c;
                counts(p)
                    && vis[p] >= c
                    && ((x > 0 && below(p - 1))
                        || (x + 1 < w && below(p + 1))
                        || (y > 0 && below(p - w))
                        || (y + 1 < h && below(p + w)))
            })
            .collect()
    };
    let (mut pixels, mut sum, mut unpaired) = (0u64, 0.0f64, false);
    for c in CONTOUR_LEVELS {
        let (a, b) = (contour(im.exact, c), contour(im.gpu, c));
        let (na, nb) = (
            a.iter().filter(|&&x| x).count(),
            b.iter().filter(|&&x| x).count(),
        );
        pixels += (na + nb) as u64;
        match (na, nb) {
            (0, 0) => continue,
            (0, _) | (_, 0) => unpaired = true,
            _ => {
                let (to_a, to_b) = (distance_to(&a, w, h), distance_to(&b, w, h));
                let from = |set: &[bool], to: &[f32]| -> f64 {
                    set.iter()
                        .zip(to)
                        .filter(|(&s, _)| s)
                        .map(|(_, &d)| d as f64)
                        .sum()
                };
                sum += from(&a, &to_b) + from(&b, &to_a);
            }
        }
    }
    let error = (!unpaired && pixels > 0).then(|| sum / pixels as f64);
    (pixels, error)
}
// ANCHOR_END: soft_error_fn

/// For every pixel of a `w × h` image (row by row), the Euclidean distance
/// in pixels, centre to centre, to the nearest pixel where `site` is true;
/// infinite when there is none. Exact: Felzenszwalb and Huttenlocher's
/// squared distance transform, down the columns and then along the rows.
pub fn distance_to(site: &[bool], w: usize, h: usize) -> Vec<f32> {
    assert_eq!(site.len(), w * h, "distance_to: the image must be {w}x{h}");
    let mut d: Vec<f64> = site
        .iter()
        .map(|&s| if s { 0.0 } else { f64::INFINITY })
        .collect();
    let mut line = Vec::with_capacity(w.max(h));
    let mut out = vec![0.0; w.max(h)];
    for x in 0..w {
        line.clear();
        line.extend((0..h).map(|y| d[y * w + x]));
        squared_distance_1d(&line, &mut out[..h]);
        (0..h).for_each(|y| d[y * w + x] = out[y]);
    }
    for y in 0..h {
        line.clear();
        line.extend_from_slice(&d[y * w..(y + 1) * w]);
        squared_distance_1d(&line, &mut out[..w]);
        d[y * w..(y + 1) * w].copy_from_slice(&out[..w]);
    }
    d.iter().map(|&s| s.sqrt() as f32).collect()
}

/// `out[q] = min over p of (q − p)² + f[p]`, the lower envelope of the
/// parabolas rooted at the finite `f[p]` (infinite where there are none).
fn squared_distance_1d(f: &[f64], out: &mut [f64]) {
    // The envelope's parabolas (their roots) and where each begins.
    let (mut roots, mut starts): (Vec<usize>, Vec<f64>) = (Vec::new(), Vec::new());
    for q in (0..f.len()).filter(|&q| f[q].is_finite()) {
        loop {
            let Some(&r) = roots.last() else {
                roots.push(q);
                starts.push(f64::NEG_INFINITY);
                break;
            };
            // Where the parabola at q overtakes the one at r.
            let (qf, rf) = (q as f64, r as f64);
            let s = ((f[q] + qf * qf) - (f[r] + rf * rf)) / (2.0 * (qf - rf));
            if s <= *starts.last().unwrap_or(&f64::NEG_INFINITY) {
                roots.pop();
                starts.pop();
            } else {
                roots.push(q);
                starts.push(s);
                break;
            }
        }
    }
    if roots.is_empty() {
        out.fill(f64::INFINITY);
        return;
    }
    let mut k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while k + 1 < roots.len() && starts[k + 1] < q as f64 {
            k += 1;
        }
        let d = q as f64 - roots[k] as f64;
        *o = d * d + f[roots[k]];
    }
}

#[cfg(test)]
#[path = "unit_tests/soft_metrics.rs"]
mod tests;
