//! lesson_02 on the CPU: what the lwjgl book's constant 0.05 of depth means under
//! a spot light (`scenes/lesson_02_spot_wide.toml`). Perspective depth is
//! not linear in distance, so the bias is inverted exactly, through the
//! light's own matrix, and compared with the linearisation that the chapter
//! used to quote ("hundreds of metres"), which is wrong this far from z = 0.

use common::glam::DVec3;
use common::scene::camera::light_view_proj;
use common::scene::{LightKind, Scene};

#[test]
fn lesson_02_lwjgl_constant_under_a_spot_light() {
    let scene = Scene::load(&support::scene_path("lesson_02_spot_wide.toml")).expect("scene loads");
    let LightKind::Spot {
        position,
        direction,
        range,
        ..
    } = scene.lights[0].kind
    else {
        panic!("lesson_02_spot_wide.toml has a spot light");
    };
    let m = light_view_proj(&scene, 0).expect("spot light").as_dmat4();
    let light = position - scene.origin();
    let axis = direction.normalize();
    // The scene's centre (origin-relative zero), its distance along the axis
    // and its depth in the map.
    let centre = DVec3::ZERO;
    let d = (centre - light).dot(axis);
    let ndc = m.project_point3(centre);
    // The depth after the lwjgl book's bias, back to a point: exact inversion.
    let biased = m
        .inverse()
        .project_point3(DVec3::new(ndc.x, ndc.y, ndc.z - 0.05));
    let d_biased = (biased - light).dot(axis);
    // The same in closed form, z = f (d − n) / (d (f − n)) inverted, with the
    // light's near and far planes read back from the matrix.
    let near_pt = m.inverse().project_point3(DVec3::new(0.0, 0.0, 0.0));
    let n = (near_pt - light).dot(axis);
    let f = range;
    let closed_form = f * n / (f - (ndc.z - 0.05) * (f - n));
    // The linearisation dz/dd = f n / ((f − n) d²) taken for 0.05 of depth.
    let linearised = 0.05 * (f - n) * d * d / (f * n);
    eprintln!(
        "spot light: near {n:.3} m, far {f:.1} m; the scene's centre {d:.2} m along the axis, depth {:.5}; \
         depth − 0.05 = {:.5} is {d_biased:.3} m from the light (closed form {closed_form:.3} m); \
         the linearisation would say {linearised:.0} m",
        ndc.z,
        ndc.z - 0.05
    );
    assert!(
        (d_biased - closed_form).abs() < 1e-3 * d,
        "the matrix and the formula disagree: {d_biased} against {closed_form}"
    );
    // The comparison is made as if the receiver were a metre or two from the
    // light: every caster farther than that is ignored.
    assert!(
        d_biased < 2.0 && d > 20.0,
        "0.05 of depth moves {d:.1} m to {d_biased:.2} m"
    );
    assert!(
        linearised > 100.0,
        "the linearisation is far off: {linearised:.0} m"
    );
}
