//! The signed ΔV view of a soft shadow: GPU − exact visibility on the
//! receivers, on a diverging colour scale, so that a penumbra's error
//! shows where the diff view (classified at V = ½) sees none.
//!
//! - blue: the GPU is darker than the exact shadow (ΔV < 0);
//! - red: the GPU is lighter (ΔV > 0, light bleeding into the umbra);
//! - white: the two agree;
//! - the colour's strength is ∛|ΔV| (a ΔV of 0.01 is 22 % of the way to
//!   full colour, 0.125 half of it), so that small errors show;
//! - dark gray: covered, but not a receiver of the light;
//! - [`background`] (a pale blue checker): no geometry.
//!
//! Receivers are [`metrics::compare`]'s: the GPU and the reference see the
//! same object there and it faces the light.

use image::{Rgba, RgbaImage};

use crate::reference::metrics::{self, RECEIVER_MIN_N_DOT_L};
use crate::reference::Reference;

/// ΔV = −1: the GPU is black where the exact shadow is fully lit.
pub const DARKER: [u8; 3] = [33, 102, 172];
/// ΔV = +1: the GPU is fully lit where the exact shadow is black.
pub const LIGHTER: [u8; 3] = [178, 24, 43];
/// Covered by geometry, not a receiver of the light.
pub const NOT_RECEIVER: Rgba<u8> = Rgba([72, 72, 72, 255]);

/// The book's "no geometry here": a pale blue checker of 8-pixel cells,
/// neither lit (white) nor shadowed (black, gray), and textured so that a
/// faint blue of the ΔV scale cannot be taken for it.
pub fn background(x: u32, y: u32) -> Rgba<u8> {
    if ((x / 8) + (y / 8)).is_multiple_of(2) {
        Rgba([200, 219, 238, 255])
    } else {
        Rgba([218, 232, 246, 255])
    }
}

/// Whether a colour is one of [`background`]'s two.
pub fn is_background(c: Rgba<u8>) -> bool {
    c == background(0, 0) || c == background(8, 0)
}

/// The colour of one receiver's ΔV = gpu − exact (clamped to [−1, 1]).
pub fn dv_colour(dv: f32) -> Rgba<u8> {
    let dv = if dv.is_nan() {
        0.0
    } else {
        dv.clamp(-1.0, 1.0)
    };
    let end = if dv < 0.0 { DARKER } else { LIGHTER };
    let t = dv.abs().cbrt();
    let mix = |e: u8| (255.0 + (e as f32 - 255.0) * t).round() as u8;
    Rgba([mix(end[0]), mix(end[1]), mix(end[2]), 255])
}

/// The ΔV of a [`dv_colour`] (to the colour's rounding), or `None` for a
/// colour that is not on the scale.
pub fn dv_of(c: Rgba<u8>) -> Option<f32> {
    let [r, g, b, a] = c.0;
    if a != 255 {
        return None;
    }
    // Which end: the channel that moved most toward it.
    let (end, sign) = if b >= r {
        (DARKER, -1.0)
    } else {
        (LIGHTER, 1.0)
    };
    let t = (255.0 - g as f32) / (255.0 - end[1] as f32);
    let dv = sign * t * t * t;
    let back = dv_colour(dv);
    let close = (0..3).all(|i| (back.0[i] as i32 - c.0[i] as i32).abs() <= 2);
    close.then_some(dv)
}

// ANCHOR: dv_image
/// The ΔV view of `gpu_visibility` for `light`: [`dv_colour`] on the
/// receivers, [`NOT_RECEIVER`] on other covered pixels, [`background`]
/// where neither the GPU nor the reference covers anything.
///
/// Panics if the images are not the reference's size.
pub fn dv_image(
    reference: &Reference,
    light: usize,
    gpu_object_id: &[u32],
    gpu_visibility: &[f32],
) -> RgbaImage {
    let (w, h) = (reference.width, reference.height);
    let n = w as usize * h as usize;
    assert!(
        gpu_object_id.len() == n && gpu_visibility.len() == n,
        "GPU images must be {w}x{h}"
    );
    let exact = &reference.visibility[light];
    let lit_by = &reference.lit_by[light];
    let ids = metrics::reference_object_ids(reference);
    RgbaImage::from_fn(w, h, |x, y| {
        let p = (y * w + x) as usize;
        let same = ids[p] != 0 && gpu_object_id[p] == ids[p];
        if same && lit_by[p] > RECEIVER_MIN_N_DOT_L {
            dv_colour(gpu_visibility[p] - exact[p])
        } else if ids[p] != 0 || gpu_object_id[p] != 0 {
            NOT_RECEIVER
        } else {
            background(x, y)
        }
    })
}
// ANCHOR_END: dv_image

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_round_trip_and_keep_their_sign() {
        assert_eq!(dv_colour(0.0), Rgba([255, 255, 255, 255]));
        assert_eq!(dv_colour(-1.0).0[..3], DARKER);
        assert_eq!(dv_colour(1.0).0[..3], LIGHTER);
        for dv in [-1.0, -0.3, -0.04, 0.0, 0.05, 0.11, 0.7, 1.0] {
            let back = dv_of(dv_colour(dv)).unwrap();
            assert!((back - dv).abs() < 0.02, "{dv} came back as {back}");
            assert!(back.signum() == dv.signum() || dv == 0.0);
        }
        assert!(!is_background(dv_colour(-0.05)));
        assert!(dv_of(background(0, 0)).is_none());
        assert!(dv_of(NOT_RECEIVER).is_none());
    }
}
