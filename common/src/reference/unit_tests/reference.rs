//! Unit tests of `common::reference` (kept apart so the module stays short).

use std::sync::Arc;

use glam::dcamera::rh::{proj::directx, view::look_at_mat4};

use super::*;
use crate::scene::mesh::Mesh;
use crate::scene::{Camera, Far, Light, LightSize, Object};

/// A quad in XZ facing +Y, side 1, centred at the origin.
fn plane() -> Mesh {
    let p = |x: f32, z: f32| Vec3::new(x, 0.0, z);
    Mesh {
        positions: vec![p(-0.5, -0.5), p(-0.5, 0.5), p(0.5, 0.5), p(0.5, -0.5)],
        indices: vec![0, 1, 2, 0, 2, 3],
        ..Default::default()
    }
}

/// A closed cube of side 1 centred at the origin, counter-clockwise outside.
fn cube() -> Mesh {
    let mut positions = Vec::new();
    for i in 0..8 {
        let c = |bit: u32| if i & bit != 0 { 0.5 } else { -0.5 };
        positions.push(Vec3::new(c(1), c(2), c(4)));
    }
    #[rustfmt::skip]
    let indices = vec![
        0, 4, 6, 0, 6, 2, // -X
        1, 3, 7, 1, 7, 5, // +X
        0, 1, 5, 0, 5, 4, // -Y
        2, 6, 7, 2, 7, 3, // +Y
        0, 2, 3, 0, 3, 1, // -Z
        4, 5, 7, 4, 7, 6, // +Z
    ];
    Mesh {
        positions,
        indices,
        ..Default::default()
    }
}

fn object(mesh: Mesh, model: DMat4, casts_shadow: bool) -> Object {
    Object {
        mesh_name: "test".into(),
        mesh: Arc::new(mesh),
        model,
        color: Vec3::ONE,
        casts_shadow,
    }
}

fn scene(objects: Vec<Object>, lights: Vec<LightKind>, eye: DVec3, target: DVec3) -> Scene {
    let camera = Camera {
        eye,
        target,
        up: DVec3::Y,
        fov_y_deg: 50.0,
        near: 0.1,
        far: Far::Finite(100.0),
        shift: glam::DVec2::ZERO,
    };
    let lights = lights
        .into_iter()
        .map(|kind| Light {
            kind,
            color: Vec3::ONE,
            size: LightSize::HARD,
        })
        .collect();
    Scene {
        name: "test".into(),
        camera,
        ambient: Vec3::ZERO,
        lights,
        objects,
        camera_path: None,
    }
}

/// The origin-relative camera matrix, as the GPU side builds it.
fn view_proj(scene: &Scene, w: u32, h: u32, far: Far) -> Mat4 {
    let c = &scene.camera;
    let o = scene.origin();
    let view = look_at_mat4(c.eye - o, c.target - o, c.up);
    let aspect = w as f64 / h as f64;
    let fov = c.fov_y_deg.to_radians();
    let proj = match far {
        Far::Finite(f) => directx::perspective(fov, aspect, c.near, f),
        Far::Infinite => directx::perspective_infinite(fov, aspect, c.near),
    };
    (proj * view).as_mat4()
}

fn render(scene: &Scene, w: u32, h: u32) -> Reference {
    render_reference(scene, view_proj(scene, w, h, scene.camera.far), w, h)
}

/// The plane-hit pixel nearest to a world point on the plane.
fn plane_pixel_near(r: &Reference, scene: &Scene, world: DVec3) -> usize {
    let target = (world - scene.origin()).as_vec3();
    (0..r.hits.len())
        .filter(|&p| r.hits[p].is_some_and(|h| h.object == 0))
        .min_by(|&a, &b| {
            let d = |p: usize| r.hits[p].unwrap().position.distance(target);
            d(a).total_cmp(&d(b))
        })
        .unwrap()
}

#[test]
fn cube_shadows_the_plane_under_a_straight_down_light() {
    let s = scene(
        vec![
            object(plane(), DMat4::IDENTITY, true),
            object(
                cube(),
                DMat4::from_scale_rotation_translation(
                    DVec3::splat(0.2),
                    Default::default(),
                    DVec3::new(0.0, 0.5, 0.0),
                ),
                true,
            ),
        ],
        vec![LightKind::Directional {
            direction: DVec3::NEG_Y,
        }],
        DVec3::new(0.3, 1.5, 1.5),
        DVec3::ZERO,
    );
    let r = render(&s, 160, 120);
    let (vis, lit) = (&r.visibility[0], &r.lit_by[0]);
    let under = plane_pixel_near(&r, &s, DVec3::ZERO);
    assert_eq!(
        vis[under], 0.0,
        "the plane under the cube's centre must be shadowed"
    );
    assert!(
        lit[under] > 0.99,
        "the plane faces the light: N·L = {}",
        lit[under]
    );
    let corner = plane_pixel_near(&r, &s, DVec3::new(0.45, 0.0, 0.45));
    assert_eq!(vis[corner], 1.0, "a far corner of the plane must be lit");
    // Every plane pixel: shadowed inside the cube's footprint, lit well outside it.
    let origin = s.origin().as_vec3();
    let (mut inside, mut outside) = (0, 0);
    for (p, h) in r.hits.iter().enumerate() {
        let Some(h) = h else { continue };
        let w = h.position + origin;
        let m = w.x.abs().max(w.z.abs());
        if h.object == 0 && m < 0.099 {
            assert_eq!(vis[p], 0.0, "plane at {w} should be shadowed");
            inside += 1;
        } else if h.object == 0 && m > 0.101 {
            assert_eq!(vis[p], 1.0, "plane at {w} should be lit");
            outside += 1;
        } else if h.object == 1 && h.normal.y > 0.99 {
            assert_eq!(vis[p], 1.0, "the cube's top is lit");
        } else if h.object == 1 {
            assert_eq!(
                (vis[p], lit[p]),
                (0.0, 0.0),
                "the cube's sides face away from the light"
            );
        }
    }
    assert!(
        inside > 50 && outside > 1000,
        "{inside} shadowed, {outside} lit plane pixels"
    );
}

#[test]
fn point_light_inside_a_closed_box_shadows_everything_outside() {
    let floor = DMat4::from_scale_rotation_translation(
        DVec3::new(10.0, 1.0, 10.0),
        Default::default(),
        DVec3::new(0.0, -1.0, 0.0),
    );
    let light = LightKind::Point {
        position: DVec3::ZERO,
        range: 50.0,
    };
    let build = |box_casts: bool| {
        scene(
            vec![
                object(plane(), floor, true),
                object(cube(), DMat4::IDENTITY, box_casts),
            ],
            vec![light],
            DVec3::new(3.0, 2.5, 4.0),
            DVec3::new(0.0, -0.5, 0.0),
        )
    };
    let r = render(&build(true), 128, 96);
    let (mut floor_pixels, mut box_pixels) = (0, 0);
    for (p, h) in r.hits.iter().enumerate() {
        let Some(h) = h else { continue };
        assert_eq!(
            r.visibility[0][p], 0.0,
            "pixel {p} on object {} sees the light",
            h.object
        );
        if h.object == 0 {
            assert!(
                r.lit_by[0][p] > 0.0,
                "the floor faces the light and is in range"
            );
            floor_pixels += 1;
        } else {
            assert_eq!(
                r.lit_by[0][p], 0.0,
                "the box's outside faces away from the light"
            );
            box_pixels += 1;
        }
    }
    assert!(floor_pixels > 1000 && box_pixels > 100);
    // A box that casts no shadow lets the light out onto the floor.
    let r = render(&build(false), 128, 96);
    let lit_floor = (0..r.hits.len())
        .filter(|&p| r.hits[p].is_some_and(|h| h.object == 0) && r.visibility[0][p] == 1.0)
        .count();
    assert!(lit_floor > 1000, "only {lit_floor} floor pixels lit");
}

#[test]
fn spot_light_influence_is_its_range_and_cone() {
    let floor = DMat4::from_scale(DVec3::splat(4.0));
    let spot = LightKind::Spot {
        position: DVec3::new(0.0, 1.0, 0.0),
        direction: DVec3::NEG_Y,
        range: 1.5,
        spot_angle_deg: 60.0,
    };
    let s = scene(
        vec![object(plane(), floor, true)],
        vec![spot],
        DVec3::new(0.0, 3.0, 2.0),
        DVec3::ZERO,
    );
    let r = render(&s, 96, 96);
    let radius = 30f32.to_radians().tan(); // the cone meets the floor here (inside the range)
    let origin = s.origin().as_vec3();
    let (mut inside, mut outside) = (0, 0);
    for (p, h) in r.hits.iter().enumerate() {
        let Some(h) = h else { continue };
        let w = h.position + origin;
        let d = Vec3::new(w.x, 0.0, w.z).length();
        assert_eq!(r.visibility[0][p], 1.0, "nothing occludes the spot");
        if d < radius - 0.01 {
            let expected = 1.0 / (1.0 + d * d).sqrt(); // N·L toward the light 1 unit up
            assert!(
                (r.lit_by[0][p] - expected).abs() < 1e-4,
                "N·L at {w}: {} vs {expected}",
                r.lit_by[0][p]
            );
            inside += 1;
        } else if d > radius + 0.01 {
            assert_eq!(r.lit_by[0][p], 0.0, "outside the cone at {w}");
            outside += 1;
        }
    }
    assert!(
        inside > 200 && outside > 200,
        "{inside} inside, {outside} outside"
    );
}

#[test]
fn primary_rays_follow_the_pixel_convention() {
    let s = scene(
        vec![object(plane(), DMat4::IDENTITY, true)],
        vec![LightKind::Directional {
            direction: DVec3::NEG_Y,
        }],
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(0.1, 0.0, -0.2),
    );
    let (w, h) = (101, 61); // odd sizes: pixel (50, 30) is the image centre
    let target = (s.camera.target - s.origin()).as_vec3();
    for (far, near) in [
        (Far::Finite(100.0), 0.1),
        (Far::Infinite, 0.1),
        (Far::Finite(1e5), 1e-3),
        (Far::Infinite, 1e-3),
    ] {
        let mut s = s.clone();
        s.camera.near = near;
        let vp = view_proj(&s, w, h, far);
        let inv = vp.as_dmat4().inverse();
        // The centre pixel's ray passes through the camera target...
        let (o, d) = primary_ray(inv, 50, 30, w, h);
        assert!((d.length() - 1.0).abs() < 1e-6);
        let closest = o + d * (target - o).dot(d);
        assert!(
            closest.distance(target) < 1e-4,
            "{far:?} near {near}: misses the target by {}",
            closest.distance(target)
        );
        // ...starts on the near plane, and the reference hits the plane there.
        let eye = (s.camera.eye - s.origin()).as_vec3();
        let forward = (target - eye).normalize();
        assert!(((o - eye).dot(forward) - near as f32).abs() < 1e-3 * near as f32);
        let r = render_reference(&s, vp, w, h);
        let hit = r.hits[30 * w as usize + 50].expect("the centre pixel hits the plane");
        assert!(
            hit.position.distance(target) < 1e-4,
            "hit at {} instead of {target}",
            hit.position
        );
        // Row 0 is the top and column 0 the left: the corner ray projects back there.
        let (o, d) = primary_ray(inv, 0, 0, w, h);
        let ndc = vp.project_point3(o + d * 2.0);
        let (x, y) = (0.5 / w as f32 * 2.0 - 1.0, 1.0 - 0.5 / h as f32 * 2.0);
        assert!(
            (ndc.x - x).abs() < 1e-4 && (ndc.y - y).abs() < 1e-4,
            "{ndc} vs ({x}, {y})"
        );
    }
}

#[test]
fn geometry_beyond_the_far_plane_is_clipped() {
    let s = scene(
        vec![object(plane(), DMat4::IDENTITY, true)],
        vec![LightKind::Directional {
            direction: DVec3::NEG_Y,
        }],
        DVec3::new(0.0, 5.0, 0.01),
        DVec3::ZERO,
    );
    let (w, h) = (9, 9);
    let hit = |far| render_reference(&s, view_proj(&s, w, h, far), w, h).hits[4 * 9 + 4];
    assert!(hit(Far::Finite(4.0)).is_none());
    assert!(hit(Far::Finite(6.0)).is_some());
    assert!(hit(Far::Infinite).is_some());
}

#[test]
fn empty_scene_is_all_misses() {
    let s = scene(
        Vec::new(),
        vec![LightKind::Directional {
            direction: DVec3::NEG_Y,
        }],
        DVec3::new(0.0, 1.0, 1.0),
        DVec3::ZERO,
    );
    let r = render_reference(&s, view_proj(&s, 8, 4, Far::Infinite), 8, 4);
    assert!(r.hits.iter().all(Option::is_none));
    assert_eq!(r.visibility, vec![vec![0.0; 32]]);
    assert_eq!(r.lit_by, vec![vec![0.0; 32]]);
}

/// The time target: about 10k triangles, one directional light, 1280×720.
/// `cargo test --release -p common --lib -- --ignored --nocapture reference_timing`
#[test]
#[ignore = "timing, run by hand"]
fn reference_timing_10k_triangles_720p() {
    let tris = crate::reference::bvh::tests::sphere(0.5, 40, 60); // 4,680 triangles
    let ball = Mesh {
        positions: tris.iter().flatten().copied().collect(),
        indices: (0..tris.len() as u32 * 3).collect(),
        ..Default::default()
    };
    let at = |x: f64, y: f64, z: f64, s: f64| {
        DMat4::from_scale_rotation_translation(
            DVec3::splat(s),
            Default::default(),
            DVec3::new(x, y, z),
        )
    };
    let objects = vec![
        object(plane(), at(0.0, 0.0, 0.0, 10.0), true),
        object(cube(), at(-1.5, 0.5, 0.5, 1.0), true),
        object(ball.clone(), at(1.0, 0.75, 0.0, 1.5), true),
        object(ball, at(-0.3, 0.4, 1.8, 0.8), true),
    ];
    let light = LightKind::Directional {
        direction: DVec3::new(-0.4, -1.0, -0.3).normalize(),
    };
    let s = scene(
        objects,
        vec![light],
        DVec3::new(4.0, 3.0, 6.0),
        DVec3::new(0.0, 0.5, 0.0),
    );
    let triangles = s.world_triangles().len();
    let vp = view_proj(&s, 1280, 720, s.camera.far);
    let runs: Vec<f64> = (0..5)
        .map(|_| render_reference(&s, vp, 1280, 720).ms)
        .collect();
    let r = render_reference(&s, vp, 1280, 720);
    let covered = r.hits.iter().filter(|h| h.is_some()).count();
    let shadowed = (0..r.hits.len())
        .filter(|&p| r.lit_by[0][p] > 0.05 && r.visibility[0][p] == 0.0)
        .count();
    println!("{triangles} triangles, {} threads, 1280x720: {runs:.1?} ms; {covered} covered, {shadowed} shadowed receivers", rayon::current_num_threads());
}

/// A disk light of radius 0.1 over the plane, 1 up, with and without a
/// small cube between: rays only where the cube is in a pixel's cone.
#[test]
fn an_area_light_casts_rays_only_where_a_caster_is_in_the_cone() {
    let cube_at = |y: f64| {
        object(
            cube(),
            DMat4::from_scale_rotation_translation(
                DVec3::splat(0.1),
                Default::default(),
                DVec3::new(0.0, y, 0.0),
            ),
            true,
        )
    };
    let light = LightKind::Point {
        position: DVec3::new(0.0, 1.0, 0.0),
        range: 10.0,
    };
    let render_with = |objects: Vec<Object>| {
        let mut s = scene(objects, vec![light], DVec3::new(0.3, 1.5, 1.5), DVec3::ZERO);
        s.lights[0].size = LightSize::Radius(0.1);
        render(&s, 120, 90)
    };
    // The plane alone: lit everywhere, no ray, nothing below a horizon.
    let r = render_with(vec![object(plane(), DMat4::IDENTITY, true)]);
    assert_eq!(r.shadow_rays, 0);
    assert!(r.horizon_clipped[0].iter().all(|&c| !c));
    let plane_pixels = r.hits.iter().filter(|h| h.is_some()).count();
    assert!(r.visibility[0]
        .iter()
        .zip(&r.hits)
        .all(|(&v, h)| h.is_none() || v == 1.0));
    // A cube 0.3 up: the strata where it is in the cone, none elsewhere.
    let r = render_with(vec![object(plane(), DMat4::IDENTITY, true), cube_at(0.3)]);
    let full = AreaSampling::DEFAULT.rays();
    assert_eq!(r.shadow_rays % full, 0);
    let sampled = r.shadow_rays / full;
    let soft = (0..r.hits.len())
        .filter(|&p| r.lit_by[0][p] > 0.0 && r.visibility[0][p] < 1.0)
        .count() as u64;
    assert!(
        soft > 50 && sampled >= soft,
        "{soft} in shadow, {sampled} sampled"
    );
    assert!(sampled < plane_pixels as u64 / 2, "{sampled} sampled");
    // The cube's sides face away from the emitter's centre: its horizon
    // hides at least half of the emitter.
    let clipped = r.horizon_clipped[0].iter().filter(|&&c| c).count();
    assert!(clipped > 0, "the cube's sides are flagged");
}

/// The soft-shadow reference's cost on lesson 10's scenes: time and shadow
/// rays, at 640×360 (and 1280×720 with `REFERENCE_COST_720P` set), best
/// of three runs.
/// `cargo test --release -p common --lib -- --ignored --nocapture reference_cost_lesson_10`
#[test]
#[ignore = "timing, run by hand"]
fn reference_cost_lesson_10_scenes() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut names: Vec<_> = std::fs::read_dir(&root)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with("lesson_10") && n.ends_with(".toml"))
        .collect();
    names.sort();
    let sizes: &[(u32, u32)] = match std::env::var("REFERENCE_COST_720P") {
        Ok(_) => &[(640, 360), (1280, 720)],
        Err(_) => &[(640, 360)],
    };
    for &(w, h) in sizes {
        for name in &names {
            let s = Scene::load(&root.join(name)).unwrap();
            let vp = crate::scene::camera::camera_matrices(&s, w, h).view_proj;
            let runs: Vec<Reference> = (0..3).map(|_| render_reference(&s, vp, w, h)).collect();
            let best = runs.iter().map(|r| r.ms).fold(f64::INFINITY, f64::min);
            let r = &runs[0];
            // Receivers of each area light: in its penumbra, its umbra.
            let (mut soft, mut umbra) = (0, 0);
            for k in (0..s.lights.len()).filter(|&k| r.area_light[k]) {
                for p in (0..r.hits.len()).filter(|&p| r.lit_by[k][p] > 0.0) {
                    let v = r.visibility[k][p];
                    soft += usize::from(v > 0.0 && v < 1.0);
                    umbra += usize::from(v == 0.0);
                }
            }
            println!(
                "{name} {w}x{h}: {best:.0} ms (best of 3), {} shadow rays; receivers: {soft} with 0 < V < 1, {umbra} with V = 0",
                r.shadow_rays
            );
        }
    }
}
