//! lesson_04's face rectangles (`lessons/lesson_04/face_rects.rs`): each
//! cube face is drawn only over the texels a visible receiver's lookup can
//! read. Two promises, each run with the knob `face_scissor` on and off:
//!
//! - the image is the same, bit for bit: every visibility PNG, with one
//!   tap, 3D PCF and the renderers' wider lookups. A rectangle cut a few
//!   texels too tight, or not widened by a lookup's taps, changes pixels
//!   at the screen's edges, where [`EDGES`] puts shadows;
//! - it draws less, and the counters say so: on [`EDGES`] only the face
//!   below the light is drawn, over part of it, so fewer texels are
//!   admitted, fewer fragments rasterised, and the cube map itself holds
//!   fewer written texels.
//!
//! Small runs (320×180, one frame) on lavapipe: seconds each.

use std::path::{Path, PathBuf};

use common::measure::counters::{FACES_RENDERED, SHADOW_FRAGMENTS, SHADOW_TEXELS_SCISSORED};
use support::LessonRun;

const BIN: &str = env!("CARGO_BIN_EXE_lesson_04");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

/// A floor seen from above by a camera under the light, and two bars above
/// the camera (behind it: no receiver of theirs is visible) whose shadows
/// cross all four edges of the image. The light's range reaches every
/// corner of the floor; the bars reach only the face below the light
/// (−Y). The visible floor is a rectangle in that face, so its
/// rectangle's sides are the image's edges, where the shadows cross them.
const EDGES: &str = r#"
[camera]
eye = [0.0, 3.0, 0.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov_y_deg = 50.0
near = 0.1
far = 30.0

[ambient]
color = [0.1, 0.1, 0.1]

[[lights]]
type = "point"
position = [0.0, 8.0, 0.0]
range = 20.0
color = [1.0, 1.0, 1.0]

[[objects]]
mesh = "plane"
scale = [10.0, 1.0, 10.0]
color = [0.8, 0.8, 0.8]
casts_shadow = false

[[objects]]
mesh = "cube"
translate = [0.0, 4.5, 0.2]
scale = [4.4, 0.1, 0.15]
color = [0.8, 0.3, 0.3]

[[objects]]
mesh = "cube"
translate = [0.25, 4.5, 0.0]
scale = [0.15, 0.1, 4.4]
color = [0.3, 0.3, 0.8]
"#;

/// [`EDGES`] and a cube beside the light, in its +X face, where no
/// receiver lies (the floor would have to reach 8 m out): the scissor
/// skips that face, the whole faces draw it.
const BESIDE: &str = r#"
[[objects]]
mesh = "cube"
translate = [1.0, 8.0, 0.0]
scale = 0.3
color = [0.5, 0.5, 0.5]
"#;

/// One tap at two sizes, hardware depth, 3D PCF (bilinear taps 1.5 texels
/// out), LearnOpenGL's 20-tap disk (world units) and Bevy's offsets and
/// Gaussian: every kind of footprint the rectangles are widened by.
const VARIANTS: [&str; 6] = [
    "linear_256",
    "linear_1024",
    "depth_1024",
    "pcf3d_1024",
    "learnopengl_pcf20",
    "bevy_point",
];

/// `text` as a scene file of its own (each test writes its own).
fn scene(name: &str, text: &str) -> PathBuf {
    let path = support::out_dir(name).join("scene.toml");
    std::fs::write(&path, text).expect("write the test scene");
    path
}

/// `variants` on `scene` (`None`: the default), with the knob
/// `face_scissor` on or off.
fn run(name: &str, scene: Option<&Path>, variants: &[&str], scissor: bool) -> Option<LessonRun> {
    let scene = scene.map(|s| s.display().to_string());
    let mut args = SIZE.to_vec();
    if let Some(s) = &scene {
        args.extend(["--scene", s.as_str()]);
    }
    for v in variants {
        args.extend(["--variant", v]);
    }
    let knob = if scissor {
        "face_scissor=1"
    } else {
        "face_scissor=0"
    };
    args.extend(["--knob", knob]);
    let tag = if scissor { "on" } else { "off" };
    support::run_lesson(BIN, &format!("{name}_{tag}"), &args)
}

fn counter(run: &LessonRun, variant: &str, key: &str) -> u64 {
    support::counter(&run.report, variant, key)
}

/// The files of `dir` whose names hold `part`, sorted.
fn files(dir: &Path, part: &str) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("read the output folder")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.contains(part))
        .collect();
    names.sort();
    names
}

/// Every visibility PNG of `on` is byte for byte the one of `off`.
fn same_images(on: &LessonRun, off: &LessonRun, scene: &str) {
    let names = files(&off.out, "_visibility_l");
    assert_eq!(names.len(), VARIANTS.len() + 1, "{scene}: {names:?}");
    for n in names {
        let a = std::fs::read(on.out.join(&n)).expect("read PNG");
        let b = std::fs::read(off.out.join(&n)).expect("read PNG");
        if a != b {
            let (_, va, _, _) = support::read_visibility(&on.out.join(&n));
            let (_, vb, _, _) = support::read_visibility(&off.out.join(&n));
            let differ = va.iter().zip(&vb).filter(|(x, y)| x != y).count();
            panic!("{scene}: {n} differs in {differ} pixels with the faces scissored: a rectangle leaves out texels a visible pixel reads");
        }
    }
}

/// The image is the same with the faces scissored, on the default scene and
/// on [`EDGES`], for every kind of lookup.
#[test]
fn lesson_04_face_rects_change_no_pixel() {
    let edges = scene("lesson_04_face_rects_same_scene", EDGES);
    for (name, path) in [("default", None), ("edges", Some(edges.as_path()))] {
        let run_name = format!("lesson_04_face_rects_same_{name}");
        let (Some(on), Some(off)) = (
            run(&run_name, path, &VARIANTS, true),
            run(&run_name, path, &VARIANTS, false),
        ) else {
            return;
        };
        same_images(&on, &off, name);
        for v in VARIANTS {
            for k in ["misclassified_pct", "false_shadow_pct", "false_lit_pct"] {
                let (a, b) = (
                    support::error(&on.report, v, k),
                    support::error(&off.report, v, k),
                );
                assert_eq!(a, b, "{name}: {v} {k} {a} scissored, {b} whole");
            }
        }
    }
}

/// Pixels of the face below the light (−Y) in the cube map's picture
/// (`<variant>_cube_map.png`, a cross of 128-pixel faces with −Y at the
/// bottom, column 1) that hold a written depth, not the clear's white.
fn written_below_the_light(run: &LessonRun, variant: &str) -> usize {
    let img = image::open(run.out.join(format!("{variant}_cube_map.png")))
        .expect("the cube map's picture")
        .to_luma8();
    let face = img.width() / 4;
    let cell = (face..2 * face).flat_map(|x| (2 * face..3 * face).map(move |y| (x, y)));
    cell.filter(|&(x, y)| img.get_pixel(x, y).0[0] != 255)
        .count()
}

/// On [`EDGES`] the scissor draws less, and every counter of it says so:
/// one face either way, but under a third of its texels admitted, fewer
/// fragments rasterised (the counting passes are scissored too), and in
/// the frame's cube map the bars only inside the face's rectangle. With
/// the knob off, the face is whole again. On [`BESIDE`], the face that
/// only the cube beside the light reaches is not drawn at all.
#[test]
fn lesson_04_face_rects_draw_less_and_count_it() {
    let edges = scene("lesson_04_face_rects_less_scene", EDGES);
    let name = "lesson_04_face_rects_less";
    let (Some(on), Some(off)) = (
        run(name, Some(&edges), &VARIANTS, true),
        run(name, Some(&edges), &VARIANTS, false),
    ) else {
        return;
    };
    for v in VARIANTS {
        let size: u64 = if v == "linear_256" { 256 } else { 1024 };
        let c = |r: &LessonRun, k| counter(r, v, k);
        let faces = (c(&on, FACES_RENDERED.name), c(&off, FACES_RENDERED.name));
        assert_eq!(
            faces,
            (1, 1),
            "{v}: the bars reach only the face below the light"
        );
        assert_eq!(
            c(&off, SHADOW_TEXELS_SCISSORED.name),
            size * size,
            "{v}: a whole face without the scissor"
        );
        let admitted = c(&on, SHADOW_TEXELS_SCISSORED.name);
        assert!(
            admitted > 0 && 3 * admitted < size * size,
            "{v}: {admitted} texels admitted of a face's {}",
            size * size
        );
        let (fragments, fragments_off) = (
            c(&on, SHADOW_FRAGMENTS.name),
            c(&off, SHADOW_FRAGMENTS.name),
        );
        assert!(
            fragments < fragments_off,
            "{v}: shadow_fragments {fragments} scissored, {fragments_off} whole: the counting passes are not scissored"
        );
        let (written, written_off) = (
            written_below_the_light(&on, v),
            written_below_the_light(&off, v),
        );
        assert!(
            written > 0 && written < written_off,
            "{v}: the frame's face below the light holds {written} written pixels of its picture scissored, {written_off} whole: the frame's face passes are not scissored"
        );
    }
    let beside = scene(
        "lesson_04_face_rects_beside_scene",
        &format!("{EDGES}{BESIDE}"),
    );
    let name = "lesson_04_face_rects_beside";
    let one = ["depth_1024"];
    let (Some(on), Some(off)) = (
        run(name, Some(&beside), &one, true),
        run(name, Some(&beside), &one, false),
    ) else {
        return;
    };
    let faces = |r: &LessonRun| counter(r, "depth_1024", FACES_RENDERED.name);
    assert_eq!(
        (faces(&on), faces(&off)),
        (1, 2),
        "the face only the cube beside the light reaches has no visible receiver: not drawn"
    );
}
