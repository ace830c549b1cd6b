//! The six sweeps before they run: what each shows and expects (its
//! [`Plan`]), and its runs ([`Step`]), with the meshes and scenes they need.

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
    let mut out = Vec::new();

    // 1. Triangles: a torus at rising tessellation.
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
            l02.push(Step {
                scene: Some(s02),
                width: WIDTH,
                height: HEIGHT,
                variants: vec!["slope_hw"],
                xs: vec![("slope_hw", x, count(tris))],
            });
        }
        for route in ROUTES {
            l05.push(Step {
                scene: Some(s05.clone()),
                width: WIDTH,
                height: HEIGHT,
                variants: vec![route],
                xs: vec![(route, x, count(tris))],
            });
        }
    }
    let torus = "a floor and one torus of n triangles (4·v² for v = 16 … 512), generated";
    let torus_routes =
        "a floor and one torus of n triangles (4·v² for v = 16 … 1024), generated, one process per route and size";
    out.push((
        Plan {
            name: "triangles_lesson_02",
            lesson: "lesson_02",
            title: "Shadow map (lesson 02, slope_hw) against caster triangles",
            axis: "triangles",
            x_label: "caster triangles n (log)",
            scene: format!("{torus}, one directional light"),
            variants: &["slope_hw"],
            passes: &["shadow", "base", "lighting"],
            counters: &["shadow_texels_written", "shadow_fragments", "draws"],
            curves: vec![
                ("slope_hw", "total", Unit::Ms, "O(n)", 1.0),
                ("slope_hw", "shadow", Unit::Ms, "O(n)", 1.0),
                (
                    "slope_hw",
                    "shadow_texels_written",
                    Unit::Count,
                    "O(1)",
                    0.0,
                ),
                ("slope_hw", "shadow_fragments", Unit::Count, "O(1)", 0.0),
            ],
        },
        l02,
    ));
    out.push((
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
            counters: &["volume_triangles", "volume_fragments", "stencil_updates"],
            curves: vec![
                ("zpass_cpu", "total", Unit::Ms, "O(n)", 1.0),
                ("zpass_compute", "cpu_total", Unit::Ms, "O(1)", 0.0),
                ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(n)", 1.0),
                ("zpass_cpu", "volume", Unit::Ms, "O(√n)", 0.5),
                ("zpass_quads", "total", Unit::Ms, "O(n)", 1.0),
                ("zpass_quads", "volume", Unit::Ms, "O(n)", 1.0),
                ("zpass_compute", "total", Unit::Ms, "O(n)", 1.0),
                ("zpass_compute", "extrude", Unit::Ms, "O(n)", 1.0),
                ("zpass_cpu", "volume_triangles", Unit::Count, "O(√n)", 0.5),
                ("zpass_quads", "volume_triangles", Unit::Count, "O(n)", 1.0),
                ("zpass_cpu", "volume_fragments", Unit::Count, "O(1)", 0.0),
                ("zpass_quads", "volume_fragments", Unit::Count, "O(1)", 0.0),
            ],
        },
        l05,
    ));

    // 2. Resolution: lesson_01's shadow-map sizes in one run; the volume
    // lesson's screen size.
    out.push((
        Plan {
            name: "resolution_lesson_01",
            lesson: "lesson_01",
            title: "Shadow map (lesson 01) against shadow-map resolution",
            axis: "shadow map",
            x_label: "shadow-map side s, texels (log)",
            scene: "the default scene (`scenes/lesson_01.toml`), all resolutions in one process"
                .into(),
            variants: &["res_256", "res_512", "res_1024", "res_2048", "res_4096"],
            passes: &["shadow", "base", "lighting"],
            counters: &["shadow_texels_written", "shadow_fragments"],
            curves: vec![
                ("*", "total", Unit::Ms, "O(s²)", 2.0),
                ("*", "shadow", Unit::Ms, "O(s²)", 2.0),
                ("*", "lighting", Unit::Ms, "O(1)", 0.0),
                ("*", "shadow_texels_written", Unit::Count, "O(s²)", 2.0),
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
    ));
    out.push((
        Plan {
            name: "screen_lesson_05",
            lesson: "lesson_05",
            title: "Shadow volumes (lesson 05, zpass_cpu) against screen size",
            axis: "screen",
            x_label: "screen pixels P = width × height (log)",
            scene: "the default scene (`scenes/lesson_05.toml`: a point and a directional light)"
                .into(),
            variants: &["zpass_cpu"],
            passes: &["cpu_silhouette", "volume", "base", "lighting"],
            counters: &["volume_fragments", "stencil_updates", "volume_triangles"],
            curves: vec![
                ("zpass_cpu", "total", Unit::Ms, "O(P)", 1.0),
                ("zpass_cpu", "volume", Unit::Ms, "O(P)", 1.0),
                ("zpass_cpu", "lighting", Unit::Ms, "O(P)", 1.0),
                ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(1)", 0.0),
                ("zpass_cpu", "volume_fragments", Unit::Count, "O(P)", 1.0),
                ("zpass_cpu", "stencil_updates", Unit::Count, "O(P)", 1.0),
                ("zpass_cpu", "volume_triangles", Unit::Count, "O(1)", 0.0),
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
    ));

    // 3. Lights: the default casters under N lights.
    let mut l02 = Vec::new();
    let mut l05 = Vec::new();
    for n in LIGHTS {
        let dir = work.join(format!("lights_{n}"));
        std::fs::create_dir_all(&dir)?;
        let s02 = dir.join("lesson_02.toml");
        write(&s02, &lights_scene(n, Light::Spot))?;
        let s05 = dir.join("lesson_05.toml");
        write(&s05, &lights_scene(n, Light::Point))?;
        l02.push(Step {
            scene: Some(s02),
            width: WIDTH,
            height: HEIGHT,
            variants: vec!["slope_hw"],
            xs: vec![("slope_hw", n as f64, n.to_string())],
        });
        l05.push(Step {
            scene: Some(s05),
            width: WIDTH,
            height: HEIGHT,
            variants: vec!["zpass_cpu"],
            xs: vec![("zpass_cpu", n as f64, n.to_string())],
        });
    }
    let casters = "lesson 01's floor and four casters under N lights on a circle, generated";
    out.push((
        Plan {
            name: "lights_lesson_02",
            lesson: "lesson_02",
            title: "Shadow map (lesson 02, slope_hw) against the number of spot lights",
            axis: "lights",
            x_label: "spot lights N (log)",
            scene: format!("{casters} (spot lights, one 1024² map each)"),
            variants: &["slope_hw"],
            passes: &["shadow", "base", "lighting"],
            counters: &["shadow_texels_written", "draws"],
            curves: vec![
                ("slope_hw", "total", Unit::Ms, "O(N)", 1.0),
                ("slope_hw", "shadow", Unit::Ms, "O(N)", 1.0),
                ("slope_hw", "lighting", Unit::Ms, "O(N)", 1.0),
                (
                    "slope_hw",
                    "shadow_texels_written",
                    Unit::Count,
                    "O(N)",
                    1.0,
                ),
                ("slope_hw", "draws", Unit::Count, "O(N)", 1.0),
            ],
        },
        l02,
    ));
    out.push((
        Plan {
            name: "lights_lesson_05",
            lesson: "lesson_05",
            title: "Shadow volumes (lesson 05, zpass_cpu) against the number of point lights",
            axis: "lights",
            x_label: "point lights N (log)",
            scene: format!("{casters} (point lights)"),
            variants: &["zpass_cpu"],
            passes: &["cpu_silhouette", "volume", "base", "lighting"],
            counters: &["volume_triangles", "volume_fragments", "draws"],
            curves: vec![
                ("zpass_cpu", "total", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "volume", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "cpu_silhouette", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "lighting", Unit::Ms, "O(N)", 1.0),
                ("zpass_cpu", "volume_triangles", Unit::Count, "O(N)", 1.0),
                ("zpass_cpu", "volume_fragments", Unit::Count, "O(N)", 1.0),
                ("zpass_cpu", "draws", Unit::Count, "O(N)", 1.0),
            ],
        },
        l05,
    ));
    Ok(out)
}
