//! lesson_09's caster culling (`lessons/lesson_09/caster_culling.rs`):
//! each cascade draws a caster only where it can shadow one of the
//! cascade's receivers. The rule on the CPU, on the default scene and on
//! scenes built for one case each (a flat caster with something below it,
//! turned either way; a flat caster with nothing below it; a caster
//! outside the view); then one GPU run: the shadow passes rasterise less
//! than half of what drawing every caster into every cascade did, and a
//! flat awning's shadow is still there.

use std::path::Path;

use common::glam::DVec3;
use common::measure::counters::{CASTERS_DRAWN, DRAWS, SHADOW_FRAGMENTS};
use common::scene::camera::{camera_matrices, light_view_proj};
use common::scene::{LightKind, Scene};
use workbook::lesson_09::cascades::{self, Cascade, Fit, FitOptions, SplitScheme};
use workbook::lesson_09::caster_culling::{CasterCulling, Kept};
use workbook::lesson_09::receivers::{read_depths, Aabb, Grid, LitView, Rect, Region};
use workbook::lesson_09::setup::{self, SceneBox, Setup};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_09");
const SIZE: (u32, u32) = (1280, 720);

/// The default scene's text without its `[camera_path]`.
fn default_scene_text() -> String {
    let text = std::fs::read_to_string(support::scene_path("lesson_09.toml")).unwrap();
    let cut = text.find("[camera_path]").expect("a camera path");
    text[..cut].to_string()
}

/// The default scene, and `extra` objects after its own.
fn scene_with(extra: &str) -> Scene {
    let text = default_scene_text() + extra;
    Scene::parse(&text, "test", Path::new(".")).expect("scene parses")
}

/// `setup`'s cascades for the scene's camera at [`SIZE`], and for each
/// cascade which objects it draws.
fn cull(scene: &Scene, setup: Setup) -> (Vec<Cascade>, Vec<Kept>) {
    let b = SceneBox::new(scene);
    let single = light_view_proj(scene, 0).expect("a light");
    let fit = setup.fit(scene, &b, single, SIZE, 0).expect("fits");
    let LightKind::Directional { direction } = scene.lights[0].kind else {
        panic!("a directional light");
    };
    let m = camera_matrices(scene, SIZE.0, SIZE.1);
    let view = LitView {
        view_proj: m.view_proj.as_dmat4(),
        eye: m.eye.as_dvec3(),
        forward: setup::view_frustum(scene, b.origin, SIZE.0, SIZE.1).forward,
    };
    let culling = CasterCulling::new(scene, b.origin, direction);
    let kept = culling.casters(&view, &fit, setup.resolution, setup.blend as f64);
    (fit, kept)
}

fn k4() -> Setup {
    let best = FitOptions {
        fit: Fit::Sphere,
        snap: true,
        extend: true,
    };
    Setup::cascaded(4, SplitScheme::Practical { lambda: 0.9 }, best)
}

/// The cascades that draw object `o`.
fn drawn_in(kept: &[Kept], o: usize) -> Vec<usize> {
    (0..kept.len())
        .filter(|&i| !kept[i][o].is_empty())
        .collect()
}

/// The area of cascade `i`'s map that object `o` is drawn into, as a
/// share of the map (rectangles may overlap only across objects).
fn share(kept: &[Kept], i: usize, o: usize, resolution: u32) -> f64 {
    let area: u64 = kept[i][o].iter().map(|r| r[2] as u64 * r[3] as u64).sum();
    area as f64 / (resolution as f64).powi(2)
}

/// A ground with nothing on it or under it: every object floats 2.5 m or
/// more above it, so no cascade draws the ground, in any variant's fit.
#[test]
fn lesson_09_culling_drops_a_ground_that_nothing_touches() {
    let mut text = default_scene_text();
    let floating = "[[objects]]\nmesh = \"sphere\"\ntranslate = [-1.0, 3.0, -6.0]\n\n\
                    [[objects]]\nmesh = \"knot\"\ntranslate = [10.0, 6.0, -60.0]\nscale = 8.0\n";
    text = text[..text.find("# Near:").expect("the near objects")].to_string() + floating;
    let scene = Scene::parse(&text, "test", Path::new(".")).expect("scene parses");
    for setup in [k4(), Setup::single(2048), Setup { blend: 0.1, ..k4() }] {
        let (_, kept) = cull(&scene, setup);
        assert_eq!(drawn_in(&kept, 0), Vec::<usize>::new(), "the ground");
        for o in 1..scene.objects.len() {
            assert!(!drawn_in(&kept, o).is_empty(), "object {o} drawn nowhere");
        }
    }
}

/// The default scene: the ground (object 0) is drawn only around the feet
/// of what stands on it, a small share of each map; the 40 m tower 150 m
/// away (object 8) shadows nothing within the first cascade's 8 m, nor
/// the box 2.5 m away (object 1) anything beyond the second's 20 m.
#[test]
fn lesson_09_culling_default_scene() {
    let scene = scene_with("");
    for setup in [k4(), Setup::single(2048), Setup { blend: 0.1, ..k4() }] {
        let (fit, kept) = cull(&scene, setup);
        for i in 0..fit.len() {
            let ground = share(&kept, i, 0, setup.resolution);
            assert!(
                ground < 0.1,
                "cascade {i} draws {ground:.3} of its map's ground"
            );
        }
        for o in 1..scene.objects.len() {
            assert!(!drawn_in(&kept, o).is_empty(), "object {o} drawn nowhere");
        }
    }
    let (_, kept) = cull(&scene, k4());
    // Something stands on the ground in every slice: a ball whose lowest
    // point touches it reads its texels at grazing light.
    assert_eq!(
        drawn_in(&kept, 0),
        [0, 1, 2, 3],
        "the ground under the feet"
    );
    assert!(!drawn_in(&kept, 8).contains(&0), "the tower 150 m away");
    assert!(drawn_in(&kept, 8).contains(&3), "the tower 150 m away");
    assert!(
        drawn_in(&kept, 1).iter().all(|&i| i <= 1),
        "the box 2.5 m away"
    );
    // k4 without the culling: 4 cascades × 11 objects, 44 draws.
    let draws: usize = kept.iter().flatten().map(|r| r.len()).sum();
    assert!(draws < 30, "{draws} caster draws");
}

/// A flat awning 2.5 m over the near ground, 5 m from the camera (object
/// 11): the ground below it is behind it, so the first cascade draws it,
/// whichever way it faces and however it tilts. Moved 3 m below the
/// ground, nothing lies behind it or just in front of it, and no cascade
/// draws it. Half a metre below the ground, with a ball half through it,
/// the ball's lower half is behind it: drawn (the ground hides both from
/// the camera, but the rule does not look at what hides what).
#[test]
fn lesson_09_culling_keeps_flat_casters_with_a_receiver_behind() {
    let awning = |rotate: &str, y: f64| {
        format!(
            "[[objects]]\nmesh = \"plane\"\ntranslate = [-1.5, {y}, -5.0]\nrotate_deg = {rotate}\nscale = 3.0\n"
        )
    };
    for rotate in ["[0.0, 0.0, 0.0]", "[180.0, 0.0, 0.0]", "[20.0, 30.0, 0.0]"] {
        let scene = scene_with(&awning(rotate, 2.5));
        let (_, kept) = cull(&scene, k4());
        assert!(drawn_in(&kept, 11).contains(&0), "awning {rotate}");
    }
    // Below the ground: the ground and everything else are in front of it.
    for rotate in ["[0.0, 0.0, 0.0]", "[180.0, 0.0, 0.0]"] {
        let scene = scene_with(&awning(rotate, -3.0));
        let (_, kept) = cull(&scene, k4());
        assert_eq!(drawn_in(&kept, 11), Vec::<usize>::new(), "floor {rotate}");
    }
    // A ball through the plane (half of it below): drawn again.
    let ball = "[[objects]]\nmesh = \"sphere\"\ntranslate = [-1.5, -0.5, -5.0]\n";
    let floor = "[[objects]]\nmesh = \"plane\"\ntranslate = [-1.5, -0.5, -5.0]\nscale = 3.0\n";
    let scene = scene_with(&format!("{floor}{ball}"));
    let (_, kept) = cull(&scene, k4());
    assert!(drawn_in(&kept, 11).contains(&0), "a ball through the floor");
}

/// A flat caster alone, 3 m up. Seen from below (the camera behind its
/// plane, on its unlit side, whose lookups move behind it) it reads
/// itself, so it is drawn; seen from above, nothing reads it.
#[test]
fn lesson_09_culling_a_flat_caster_seen_from_behind_reads_itself() {
    let alone = |eye: &str| {
        let text = format!(
            "[camera]\neye = {eye}\ntarget = [0.0, 3.0, -5.0]\nup = [0.0, 1.0, 0.0]\n\
             fov_y_deg = 50.0\nnear = 0.1\nfar = 100.0\n\n\
             [[lights]]\ntype = \"directional\"\ndirection = [0.55, -0.643, 0.532]\n\n\
             [[objects]]\nmesh = \"plane\"\ntranslate = [0.0, 3.0, -5.0]\nscale = 4.0\n"
        );
        let scene = Scene::parse(&text, "test", Path::new(".")).expect("scene parses");
        let (_, kept) = cull(&scene, k4());
        drawn_in(&kept, 0)
    };
    assert!(!alone("[0.0, 1.0, 0.0]").is_empty(), "seen from below");
    assert_eq!(alone("[0.0, 8.0, 0.0]"), Vec::<usize>::new(), "from above");
}

/// `lesson_09_offscreen_caster.toml`: the roof (object 1) above and behind
/// the camera is in no slice, but its shadow is on the ground in view.
#[test]
fn lesson_09_culling_keeps_a_caster_outside_the_view() {
    let scene = Scene::load(&support::scene_path("lesson_09_offscreen_caster.toml")).unwrap();
    let (_, kept) = cull(&scene, k4());
    assert!(!drawn_in(&kept, 1).is_empty(), "the roof");
    // Outside the view and shadowing nothing in it: a ball 30 m behind.
    let text = std::fs::read_to_string(support::scene_path("lesson_09_offscreen_caster.toml"));
    let text = text.unwrap() + "[[objects]]\nmesh = \"sphere\"\ntranslate = [0.0, 2.0, 40.0]\n";
    let scene = Scene::parse(&text, "test", Path::new(".")).unwrap();
    let (_, kept) = cull(&scene, k4());
    let ball = scene.objects.len() - 1;
    assert_eq!(
        drawn_in(&kept, ball),
        Vec::<usize>::new(),
        "the ball behind"
    );
}

/// The search structures leave out no receiver: for boxes scattered over
/// the default scene's field, any query rectangle that a point of a
/// receiver's part falls in is met by that receiver's outline, and the
/// grid hands the receiver to the query.
#[test]
fn lesson_09_culling_grid_and_outlines_miss_nothing() {
    let scene = scene_with("");
    let b = SceneBox::new(&scene);
    let m = camera_matrices(&scene, SIZE.0, SIZE.1);
    let view = LitView {
        view_proj: m.view_proj.as_dmat4(),
        eye: m.eye.as_dvec3(),
        forward: setup::view_frustum(&scene, b.origin, SIZE.0, SIZE.1).forward,
    };
    let light = cascades::light_view(DVec3::new(0.55, -0.643, 0.532));
    let all = Aabb::around(b.corners);
    // A fixed sequence in [0, 1).
    let mut seed = 12345u64;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut point = |lo: DVec3, hi: DVec3| lo + (hi - lo) * DVec3::new(next(), next(), next());
    for (near, far) in [(f64::NEG_INFINITY, 8.0), (8.0, 60.0), (60.0, f64::INFINITY)] {
        let region = Region::new(&view, near, far, all, 1e-6);
        // Boxes about the region's box, up to a fifth of its size.
        let (lo, hi) = (region.bounds.lo, region.bounds.hi);
        let boxes: Vec<(Aabb, Aabb)> = (0..300)
            .map(|_| {
                let c = point(lo - (hi - lo) * 0.2, hi + (hi - lo) * 0.2);
                let h = point(DVec3::ZERO, (hi - lo) * 0.2);
                let w = Aabb {
                    lo: c - h,
                    hi: c + h,
                };
                let l = Aabb::around(w.corners().map(|p| light.transform_point3(p)));
                (w, l)
            })
            .collect();
        let receivers = region.receivers(light, boxes.iter().copied());
        assert!(receivers.len() > 30, "{} receivers", receivers.len());
        let grid = Grid::new(&receivers);
        for r in &receivers {
            let part = boxes[r.index].0.meet(region.bounds);
            for _ in 0..20 {
                let p = light.transform_point3(point(part.lo, part.hi)).truncate();
                let size = point(DVec3::ZERO, DVec3::splat(2.0)).truncate();
                let query = Rect {
                    lo: p - size,
                    hi: p + size * 0.5,
                };
                assert!(r.meets(query), "outline of {} misses {query:?}", r.index);
                let found = grid.near(query).any(|g| g.index == r.index);
                assert!(found, "the grid misses {} at {query:?}", r.index);
            }
        }
    }
}

/// The view depths each cascade is read at: its slice; the first from −∞
/// and the last to +∞; with a blend band, from the band of the cascade in
/// front of it.
#[test]
fn lesson_09_culling_read_depths() {
    let cascade = |near, far| Cascade {
        near,
        far,
        width: 1.0,
        origin: None,
        view_proj: Default::default(),
    };
    let fit = [cascade(0.1, 5.0), cascade(5.0, 20.0), cascade(20.0, 100.0)];
    let close = |a: f64, b: f64| (a - b).abs() < 0.01;
    let (n0, f0) = read_depths(&fit, 0, 0.0);
    assert!(n0 == f64::NEG_INFINITY && close(f0, 5.0) && f0 > 5.0);
    let (n1, f1) = read_depths(&fit, 1, 0.0);
    assert!(close(n1, 5.0) && n1 < 5.0 && close(f1, 20.0) && f1 > 20.0);
    let (n2, f2) = read_depths(&fit, 2, 0.1);
    assert!(close(n2, 18.5) && n2 < 18.5 && f2 == f64::INFINITY);
}

/// The GPU: `k4` on the default scene with an awning added (no camera
/// path, 320×180). Its shadow passes rasterise less than half of what
/// `k4_nocull` (every caster in every cascade) does in the same run (99 133
/// against 3 577 205 on lavapipe), the two images are the same bit for
/// bit, its counters add up, and the awning's shadow is there: leaving out every flat caster reads 10.8 %
/// of the receivers false lit, against 0.051 % drawn (lavapipe).
#[test]
fn lesson_09_culling_halves_the_fragments_and_keeps_the_shadows() {
    let awning = "[[objects]]\nmesh = \"plane\"\ntranslate = [-1.5, 2.5, -5.0]\nrotate_deg = [180.0, 0.0, 0.0]\nscale = 3.0\n";
    let out = support::out_dir("lesson_09_culling_scene");
    let scene = out.join("awning.toml");
    std::fs::write(&scene, default_scene_text() + awning).unwrap();
    let args = [
        "--width",
        "320",
        "--height",
        "180",
        "--frames",
        "1",
        "--variant",
        "k4",
        "--variant",
        "k4_nocull",
        "--scene",
    ];
    let args = [&args[..], &[scene.to_str().unwrap()]].concat();
    let Some(run) = support::run_lesson(BIN, "lesson_09_culling", &args) else {
        return;
    };
    let c = |k: &str| support::counter(&run.report, "k4", k);
    let fragments = c(SHADOW_FRAGMENTS.name);
    let unculled = support::counter(&run.report, "k4_nocull", SHADOW_FRAGMENTS.name);
    assert!(
        fragments * 2 <= unculled,
        "k4 rasterises {fragments} shadow fragments, more than half of k4_nocull's {unculled}"
    );
    // The image is the same, bit for bit: the visibility and the shaded frame.
    for file in ["visibility_l0.png", ".png"] {
        let read = |v: &str| {
            let name = format!("{v}{}{file}", if file.starts_with('.') { "" } else { "_" });
            std::fs::read(run.out.join(&name)).unwrap_or_else(|e| panic!("{name}: {e}"))
        };
        assert!(
            read("k4") == read("k4_nocull"),
            "k4's {file} differs from k4_nocull's: the culling changed the image"
        );
    }
    // 12 objects, one light: the base and lit passes draw each once.
    let casters = c(CASTERS_DRAWN.name);
    assert_eq!(c(DRAWS.name), 2 * 12 + casters, "{}", DRAWS.name);
    assert!(casters < 4 * 12, "casters drawn {casters}");
    let false_lit = support::error(&run.report, "k4", "false_lit_pct");
    assert!(
        false_lit <= 0.3,
        "k4: false lit {false_lit:.3} %: a shadow went missing"
    );
}
