//! The camera's view frustum as planes: what the culling of casters and
//! of volumes tests bounding spheres against.

use common::glam::{DMat4, DVec3, DVec4};

/// Planes `(n, d)`, `n` of unit length, with n·p + d ≥ 0 inside, from a
/// WebGPU view-projection (depth in [0, 1]). A far plane at infinity is
/// left out.
pub fn frustum_planes(vp: DMat4) -> Vec<(DVec3, f64)> {
    let r = |i: usize| vp.row(i);
    let candidates = [
        r(3) + r(0),
        r(3) - r(0),
        r(3) + r(1),
        r(3) - r(1),
        r(2),
        r(3) - r(2),
    ];
    candidates
        .iter()
        .filter_map(|p: &DVec4| {
            let len = p.truncate().length();
            (len > 1e-9 * p.length().max(1.0)).then(|| (p.truncate() / len, p.w / len))
        })
        .collect()
}
