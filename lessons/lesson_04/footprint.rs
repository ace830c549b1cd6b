//! How far a lesson 04 lookup reads around the direction to its receiver
//! (its footprint), in a cube face's texels: what each face's rectangle
//! ([`super::face_rects`]) is widened by. One nearest tap reads the texel of
//! the direction itself; 3D PCF, LearnOpenGL's disk and Bevy's offsets and
//! Gaussian read further.

use super::bevy_card::BEVY_POINT;
use super::cube_map::Storage;
use super::peers::Peer;

/// What a variant's lookup reads around the direction from the light to
/// the receiver: each tap's direction is that direction plus an offset of
/// at most `per_distance` × the receiver's distance from the light, plus
/// `world` + `world_per_view` × its distance from the camera (world
/// units), taken after the receiver moved `towards_light` world units to
/// the light. `bilinear`: every tap blends 2×2 texels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    pub per_distance: f64,
    pub world: f64,
    pub world_per_view: f64,
    pub towards_light: f64,
    pub bilinear: bool,
}

/// The footprint of a lesson 04 lookup on a cube of `size` texels a face
/// whose far plane is `far` (m): one nearest tap reads the direction's own
/// texel; 3D PCF adds `pcf` texels × √3 (its 20 offsets reach the cube's
/// corners, a texel is 2 d / N wide at distance d) and bilinear taps; the
/// renderers' lookups theirs ([`Peer`]). `None` for the exercise's lookup:
/// the student's function picks the texel, so every face stays whole.
pub fn lookup_footprint(
    storage: Storage,
    pcf: f32,
    (peer, bias_world): (Peer, f32),
    size: u32,
    far: f64,
) -> Option<Footprint> {
    let scale = f64::from(peer.params(size).1);
    let sqrt3 = 3f64.sqrt();
    Some(match peer {
        Peer::None if storage == Storage::DepthExercise => return None,
        Peer::None => Footprint {
            per_distance: sqrt3 * f64::from(pcf) * 2.0 / f64::from(size),
            bilinear: pcf > 0.0,
            ..Footprint::default()
        },
        // A disk of (1 + view distance / far) × scale world units, its
        // offsets up to √3 long (the cube's corners).
        Peer::LearnOpenGlDisk => Footprint {
            world: sqrt3 * scale,
            world_per_view: sqrt3 * scale / far,
            ..Footprint::default()
        },
        // The normal offset (scale × the major axis ≤ d), then taps up to
        // POINT_SHADOW_SCALE × the farthest D3D position × d, after the
        // move towards the light.
        Peer::BevyPoint => {
            let p = BEVY_POINT.list("D3D_SAMPLE_POINT_POSITIONS");
            let widest = p.chunks(2).map(|xy| xy[0].hypot(xy[1])).fold(0.0, f64::max);
            Footprint {
                per_distance: scale + BEVY_POINT.num("POINT_SHADOW_SCALE") * widest,
                towards_light: f64::from(bias_world),
                bilinear: true,
                ..Footprint::default()
            }
        }
    })
}

/// How many texels a lookup's taps can read beyond the texel of the
/// direction itself, for receivers at least `r_min` from the light and at
/// most `view_max` from the camera; `None` where the reach is too wide to
/// bound (the whole face).
///
/// A tap at q = p + o (|o| ≤ ρ d, d the receiver's distance) that lands in
/// the face (|u| ≤ 1 there, and m ≥ |q| / √3 ≥ d (1 − ρ) / √3) is read at
/// u(q), and u(p) − u(q) = (u o_m − o_x) / (m − o_m): at most √2 ρ d /
/// (d (1 − ρ) / √3 − ρ d) = √6 ρ / (1 − (1 + √3) ρ) in NDC, N / 2 times
/// that in texels.
pub fn reach_texels(f: Footprint, size: u32, r_min: f64, view_max: f64) -> Option<f64> {
    if r_min <= f.towards_light {
        return None;
    }
    let offset = f.per_distance + (f.world + f.world_per_view * view_max) / r_min;
    let rho = offset / (1.0 - f.towards_light / r_min);
    let grow = 1.0 - (1.0 + 3f64.sqrt()) * rho;
    if !rho.is_finite() || grow < 0.5 {
        return None;
    }
    let taps = f64::from(size) * 0.5 * 6f64.sqrt() * rho / grow;
    // One more for the 2×2 a bilinear tap blends, one for rounding (the
    // GPU's float directions against these doubles).
    Some(taps + f64::from(u8::from(f.bilinear)) + 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One nearest tap reaches one texel (rounding); a reach too wide to
    /// bound gives none (the whole face); 3D PCF's 1.5 texels (up to √3 ×
    /// that off the direction) reach more than that and under 9 texels on
    /// a 1024² face, bilinear and rounding included.
    #[test]
    fn reaches_in_texels() {
        assert_eq!(reach_texels(Footprint::default(), 256, 1.0, 0.0), Some(1.0));
        let wide = Footprint {
            world: 1.0,
            ..Footprint::default()
        };
        assert_eq!(reach_texels(wide, 256, 1.0, 0.0), None);
        let pcf = lookup_footprint(Storage::Depth, 1.5, (Peer::None, 0.0), 1024, 12.0).unwrap();
        let r = reach_texels(pcf, 1024, 1.0, 0.0).unwrap();
        assert!(
            pcf.bilinear && r > 1.5 * 3f64.sqrt() + 2.0 && r < 9.0,
            "{r}"
        );
        assert_eq!(
            lookup_footprint(Storage::DepthExercise, 0.0, (Peer::None, 0.0), 1024, 12.0),
            None
        );
    }
}
