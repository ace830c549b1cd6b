//! Unit tests of `common::reference::cache`.

use super::*;

/// Two pixels, one missed, and two lights (one with a size).
fn small() -> Reference {
    let hit = PixelHit {
        object: 3,
        triangle: 70_000,
        t: 1.25,
        position: Vec3::new(0.1, -2.0, 1e-7),
        normal: Vec3::new(0.0, 1.0, -0.0),
    };
    Reference {
        width: 2,
        height: 1,
        hits: vec![Some(hit), None],
        visibility: vec![vec![1.0, 0.0], vec![0.375, f32::MIN_POSITIVE]],
        lit_by: vec![vec![0.5, 0.0], vec![0.25, 0.0]],
        area_light: vec![false, true],
        horizon_clipped: vec![vec![false, false], vec![true, false]],
        ms: 151.5,
        shadow_rays: 1 << 40,
    }
}

#[test]
fn a_reference_reads_back_bit_for_bit() {
    let r = small();
    let back = from_bytes(&to_bytes(&r)).expect("reads back");
    assert_eq!(format!("{r:?}"), format!("{back:?}"));
    assert_eq!(back.hits, r.hits);
    assert_eq!(back.horizon_clipped, r.horizon_clipped);
}

#[test]
fn a_short_or_foreign_file_is_no_reference() {
    let bytes = to_bytes(&small());
    assert!(from_bytes(&bytes[..bytes.len() - 1]).is_none(), "short");
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(from_bytes(&longer).is_none(), "long");
    let mut foreign = bytes;
    foreign[0] ^= 1;
    assert!(from_bytes(&foreign).is_none(), "another tag");
}
