//! The six sweeps before they run: what each shows and expects (its
//! [`Plan`]), and its runs ([`Step`]), with the meshes and scenes they need.

use common::measure::counters::{
    DRAWS, SHADOW_FRAGMENTS, SHADOW_TEXELS_WRITTEN, STENCIL_UPDATES, VOLUME_FRAGMENTS,
    VOLUME_TRIANGLES,
};
use std::path::{Path, PathBuf};

use anyhow::Result;

use super::scenes::{lights_scene, torus_scene, write_torus, Light};
use super::sweep::Unit;
use super::write;
use crate::table::count;

/// The frame size of every sweep but the screen-size one.
pub(super) const WIDTH: u32 = 640;
pub(super) const HEIGHT: u32 = 360;
/// Timed frames a point (one process a point).
pub(super) const FRAMES: u32 = 5;

/// Torus tessellations (minor segments; major = 2 × minor), 4·v² triangles:
/// 1k, 4k, 16k, 64k, 256k and 1M.
const TORUS_MINOR: [u32; 6] = [16, 32, 64, 128, 256, 512];
/// The volume routes' sweep goes on to the 4.2 M-triangle torus (v = 1024),
/// where a route whose buffers pass the adapter's limits is left out.
const TORUS_MINOR_ROUTES: [u32; 7] = [16, 32, 64, 128, 256, 512, 1024];
/// The three volume routes of lesson 05, each run in a process of its own,
/// so that one left out (a limit) does not stop the others.
const ROUTES: [&str; 3] = ["zpass_cpu", "zpass_quads", "zpass_compute"];
/// lesson_01's resolution variants, in order, and their side in texels.
const SHADOW_RES: [(&str, u32); 5] = [
    ("res_256", 256),
    ("res_512", 512),
    ("res_1024", 1024),
    ("res_2048", 2048),
    ("res_4096", 4096),
];
/// Screen sizes of the volume lesson's resolution sweep.
const SCREENS: [(u32, u32); 4] = [(320, 180), (640, 360), (1280, 720), (2560, 1440)];
/// Light counts of the lights sweeps.
const LIGHTS: [u32; 5] = [1, 2, 4, 8, 16];

/// What a sweep shows and expects, before it runs.
pub(super) struct Plan {
    pub(super) name: &'static str,
    pub(super) lesson: &'static str,
    pub(super) title: &'static str,
    pub(super) axis: &'static str,
    /// The plots' x-axis label.
    pub(super) x_label: &'static str,
    pub(super) scene: String,
    pub(super) variants: &'static [&'static str],
    pub(super) passes: &'static [&'static str],
    pub(super) counters: &'static [&'static str],
    /// (variant, key, unit, expected order, expected slope)
    pub(super) curves: Vec<(&'static str, &'static str, Unit, &'static str, f64)>,
}

/// One run of a sweep: a scene (or the default), a frame size, the x of
/// each variant.
pub(super) struct Step {
    pub(super) scene: Option<PathBuf>,
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) variants: Vec<&'static str>,
    /// x and label, for every variant of the run (lesson_01 runs all its
    /// resolutions at once: one x each).
    pub(super) xs: Vec<(&'static str, f64, String)>,
}

/// The six sweeps and their runs; writes the meshes and scenes they need.
pub(super) fn plans(work: &Path) -> Result<Vec<(Plan, Vec<Step>)>> {
    let (torus_02, torus_05) = torus_steps(work)?;
    let (lights_02, lights_05) = lights_steps(work)?;
    let mut out = Vec::new();
    out.extend(triangle_plans(torus_02, torus_05));
    out.extend(resolution_plans());
    out.extend(lights_plans(lights_02, lights_05));
    Ok(out)
}

/// One run of one variant on `scene` at the sweeps' frame size, at `x`.
fn step(scene: PathBuf, variant: &'static str, x: f64, label: String) -> Step {
    Step {
        scene: Some(scene),
        width: WIDTH,
        height: HEIGHT,
        variants: vec![variant],
        xs: vec![(variant, x, label)],
    }
}

/// Writes each torus and its two scenes: the runs of lesson 02 and of lesson 05's routes.
fn torus_steps(work: &Path) -> Result<(Vec<Step>, Vec<Step>)> {
    let mut l02 = Vec::new();
    let mut l05 = Vec::new();
    for v in TORUS_MINOR_ROUTES {
        let dir = work.join(format!("torus_{v}"));
        std::fs::create_dir_all(&dir)?;
        let tris = write_torus(&dir.join("torus.obj"), 2 * v, v)?;
        let s02 = dir.join("lesson_02.toml");
        write(&s02, &torus_scene(Light::Directional))?;
        let s05 = dir.join("lesson_05.toml");
        write(&s05, &torus_scene(Light::Point))?;
        let x = tris as f64;
        if TORUS_MINOR.contains(&v) {
            l02.push(step(s02, "slope_hw", x, count(tris)));
        }
        for route in ROUTES {
            l05.push(step(s05.clone(), route, x, count(tris)));
        }
    }
    Ok((l02, l05))
}

/// 1. Triangles: lessons 02 and 05 on a torus at rising tessellation.
fn triangle_plans(l02: Vec<Step>, l05: Vec<Step>) -> [(Plan, Vec<Step>); 2] {
    let torus = "a floor and one torus of n triangles (4·v² for v = 16 … 512), generated";
    let torus_routes =
        "a floor and one torus of n triangles (4·v² for v = 16 … 1024), generated, one process per route and size";
    [
        (
            Plan {
                name: "triangles_lesson_02",
                lesson: "lesson_02",
                title: "Shadow map (lesson 02, slope_hw) against caster triangles",
                axis: "triangles",
                x_label: "caster triangles n (log)",
                scene: format!("{torus}, one directional light"),
                variants: &["slope_hw"],
                passes: &["shadow", "base", "lighting"],
                counters: &[
                    SHADOW_TEXELS_WRITTEN.name,
                    SHADOW_FRAGMENTS.name,
                    DRAWS.name,
                ],
                curves: vec![
                    ("slope_hw", "total", Unit::Ms, "O(n)", 1.0),
                    ("slope_hw", "shadow", Unit::Ms, "O(n)", 1.0),
                    (
                        "slope_hw",
                        SHADOW_TEXELS_WRITTEN.name,
                        Unit::Count,
                        "O(1)",
                        0.0,
                    ),
                    ("slope_hw", SHADOW_FRAGMENTS.name, Unit::Count, "O(1)", 0.0),
                ],
            },
            l02,
        ),
        (
            Plan {
                name: "triangles_lesson_05",
                lesson: "lesson_05",
                title: "Shadow volumes (lesson 05) against caster triangles",
                axis: "triangles",
                x_label: "caster triangles n (log)",
                scene: format!("{torus_routes}, one point light"),
                variants: &ROUTES,
                passes: &[
                    "cpu_total",
                    "cpu_silhouette",
                    "extrude",
                    "volume",
                    "base",
                    "lighting",
                ],
                counters: &[
                    VOLUME_TRIANGLES.name,
                    VOLUME_FRAGMENTS.name,
                    STENCIL_UPDATES.name,
                ],
                curves: vec![
                    ("zpass_cpu", "total", Unit::Ms, "O(n)", 1.0),
                    ("zpass_compute", "cpu_total", Unit::Ms, "O(1)", 0.0),
                    ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(n)", 1.0),
                    ("zpass_cpu", "volume", Unit::Ms, "O(√n)", 0.5),
                    ("zpass_quads", "total", Unit::Ms, "O(n)", 1.0),
                    ("zpass_quads", "volume", Unit::Ms, "O(n)", 1.0),
                    ("zpass_compute", "total", Unit::Ms, "O(n)", 1.0),
                    ("zpass_compute", "extrude", Unit::Ms, "O(n)", 1.0),
                    (
                        "zpass_cpu",
                        VOLUME_TRIANGLES.name,
                        Unit::Count,
                        "O(√n)",
                        0.5,
                    ),
                    (
                        "zpass_quads",
                        VOLUME_TRIANGLES.name,
                        Unit::Count,
                        "O(n)",
                        1.0,
                    ),
                    ("zpass_cpu", VOLUME_FRAGMENTS.name, Unit::Count, "O(1)", 0.0),
                    (
                        "zpass_quads",
                        VOLUME_FRAGMENTS.name,
                        Unit::Count,
                        "O(1)",
                        0.0,
                    ),
                ],
            },
            l05,
        ),
    ]
}

/// 2. Resolution: lesson_01's shadow-map sizes in one run; lesson 05's screen size.
fn resolution_plans() -> [(Plan, Vec<Step>); 2] {
    [
        (
            Plan {
                name: "resolution_lesson_01",
                lesson: "lesson_01",
                title: "Shadow map (lesson 01) against shadow-map resolution",
                axis: "shadow map",
                x_label: "shadow-map side s, texels (log)",
                scene:
                    "the default scene (`scenes/lesson_01.toml`), all resolutions in one process"
                        .into(),
                variants: &["res_256", "res_512", "res_1024", "res_2048", "res_4096"],
                passes: &["shadow", "base", "lighting"],
                counters: &[SHADOW_TEXELS_WRITTEN.name, SHADOW_FRAGMENTS.name],
                curves: vec![
                    ("*", "total", Unit::Ms, "O(s²)", 2.0),
                    ("*", "shadow", Unit::Ms, "O(s²)", 2.0),
                    ("*", "lighting", Unit::Ms, "O(1)", 0.0),
                    ("*", SHADOW_TEXELS_WRITTEN.name, Unit::Count, "O(s²)", 2.0),
                ],
            },
            vec![Step {
                scene: None,
                width: WIDTH,
                height: HEIGHT,
                variants: SHADOW_RES.iter().map(|r| r.0).collect(),
                xs: SHADOW_RES
                    .iter()
                    .map(|&(v, s)| (v, s as f64, format!("{s}²")))
                    .collect(),
            }],
        ),
        (
            Plan {
                name: "screen_lesson_05",
                lesson: "lesson_05",
                title: "Shadow volumes (lesson 05, zpass_cpu) against screen size",
                axis: "screen",
                x_label: "screen pixels P = width × height (log)",
                scene:
                    "the default scene (`scenes/lesson_05.toml`: a point and a directional light)"
                        .into(),
                variants: &["zpass_cpu"],
                passes: &["cpu_silhouette", "volume", "base", "lighting"],
                counters: &[
                    VOLUME_FRAGMENTS.name,
                    STENCIL_UPDATES.name,
                    VOLUME_TRIANGLES.name,
                ],
                curves: vec![
                    ("zpass_cpu", "total", Unit::Ms, "O(P)", 1.0),
                    ("zpass_cpu", "volume", Unit::Ms, "O(P)", 1.0),
                    ("zpass_cpu", "lighting", Unit::Ms, "O(P)", 1.0),
                    ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(1)", 0.0),
                    ("zpass_cpu", VOLUME_FRAGMENTS.name, Unit::Count, "O(P)", 1.0),
                    ("zpass_cpu", STENCIL_UPDATES.name, Unit::Count, "O(P)", 1.0),
                    ("zpass_cpu", VOLUME_TRIANGLES.name, Unit::Count, "O(1)", 0.0),
                ],
            },
            SCREENS
                .iter()
                .map(|&(w, h)| Step {
                    scene: None,
                    width: w,
                    height: h,
                    variants: vec!["zpass_cpu"],
                    xs: vec![("zpass_cpu", (w * h) as f64, format!("{w}×{h}"))],
                })
                .collect(),
        ),
    ]
}

/// Writes the default casters' scenes under N lights: the runs of lessons 02 and 05.
fn lights_steps(work: &Path) -> Result<(Vec<Step>, Vec<Step>)> {
    let mut l02 = Vec::new();
    let mut l05 = Vec::new();
    for n in LIGHTS {
        let dir = work.join(format!("lights_{n}"));
        std::fs::create_dir_all(&dir)?;
        let s02 = dir.join("lesson_02.toml");
        write(&s02, &lights_scene(n, Light::Spot))?;
        let s05 = dir.join("lesson_05.toml");
        write(&s05, &lights_scene(n, Light::Point))?;
        l02.push(step(s02, "slope_hw", n as f64, n.to_string()));
        l05.push(step(s05, "zpass_cpu", n as f64, n.to_string()));
    }
    Ok((l02, l05))
}

/// 3. Lights: lessons 02 and 05 on the default casters under N lights.
fn lights_plans(l02: Vec<Step>, l05: Vec<Step>) -> [(Plan, Vec<Step>); 2] {
    let casters = "lesson 01's floor and four casters under N lights on a circle, generated";
    [
        (
            Plan {
                name: "lights_lesson_02",
                lesson: "lesson_02",
                title: "Shadow map (lesson 02, slope_hw) against the number of spot lights",
                axis: "lights",
                x_label: "spot lights N (log)",
                scene: format!("{casters} (spot lights, one 1024² map each)"),
                variants: &["slope_hw"],
                passes: &["shadow", "base", "lighting"],
                counters: &[SHADOW_TEXELS_WRITTEN.name, DRAWS.name],
                curves: vec![
                    ("slope_hw", "total", Unit::Ms, "O(N)", 1.0),
                    ("slope_hw", "shadow", Unit::Ms, "O(N)", 1.0),
                    ("slope_hw", "lighting", Unit::Ms, "O(N)", 1.0),
                    (
                        "slope_hw",
                        SHADOW_TEXELS_WRITTEN.name,
                        Unit::Count,
                        "O(N)",
                        1.0,
                    ),
                    ("slope_hw", DRAWS.name, Unit::Count, "O(N)", 1.0),
                ],
            },
            l02,
        ),
        (
            Plan {
                name: "lights_lesson_05",
                lesson: "lesson_05",
                title: "Shadow volumes (lesson 05, zpass_cpu) against the number of point lights",
                axis: "lights",
                x_label: "point lights N (log)",
                scene: format!("{casters} (point lights)"),
                variants: &["zpass_cpu"],
                passes: &["cpu_silhouette", "volume", "base", "lighting"],
                counters: &[VOLUME_TRIANGLES.name, VOLUME_FRAGMENTS.name, DRAWS.name],
                curves: vec![
                    ("zpass_cpu", "total", Unit::Ms, "O(N)", 1.0),
                    ("zpass_cpu", "volume", Unit::Ms, "O(N)", 1.0),
                    ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(N)", 1.0),
                    ("zpass_cpu", "lighting", Unit::Ms, "O(N)", 1.0),
                    ("zpass_cpu", VOLUME_TRIANGLES.name, Unit::Count, "O(N)", 1.0),
                    ("zpass_cpu", VOLUME_FRAGMENTS.name, Unit::Count, "O(N)", 1.0),
                    ("zpass_cpu", DRAWS.name, Unit::Count, "O(N)", 1.0),
                ],
            },
            l05,
        ),
    ]
}
