//! Lesson 05's two ways of building shadow volumes draw the same volumes:
//! the degenerate quads (`zpass_quads`) rasterise no more than the CPU
//! silhouettes (`zpass_cpu`), within 10 %, and give the same pixels.
//!
//! Two-sided casters are the hard case: `caster_adjacency` gives each of
//! their triangles a reversed twin, so every interior edge has four faces.
//! A quad per (edge, face) opens one pair of opposite quads per edge, which
//! the stencil cancels only after rasterising both (`holed_sphere`: about
//! 50 000 triangles, five holes). The quads must sum first, as the CPU does.

use std::path::Path;

use common::measure::counters::VOLUME_FRAGMENTS;

const BIN: &str = env!("CARGO_BIN_EXE_lesson_05");

/// Decoded RGBA pixels of a PNG the run wrote.
fn pixels(path: &Path) -> Vec<u8> {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
        .into_raw()
}

fn quads_fill_like_cpu(name: &str, scene: Option<&str>, lights: usize) {
    let scene_path = scene.map(support::scene_path);
    let mut args = vec!["--width", "320", "--height", "180", "--frames", "1"];
    args.extend(["--variant", "zpass_cpu", "--variant", "zpass_quads"]);
    let scene_arg;
    if let Some(p) = &scene_path {
        scene_arg = p.to_string_lossy().to_string();
        args.extend(["--scene", scene_arg.as_str()]);
    }
    let Some(run) = support::run_lesson(BIN, name, &args) else {
        return;
    };
    let r = &run.report;
    let fragments = |v: &str| support::counter(r, v, VOLUME_FRAGMENTS.name);
    let ms = |v: &str| support::variant(r, v)["timing_ms"]["total"].as_f64();
    let (cpu, quads) = (fragments("zpass_cpu"), fragments("zpass_quads"));
    println!(
        "{name}: volume_fragments zpass_cpu {cpu}, zpass_quads {quads} ({:.3}x); \
         frame ms zpass_cpu {:?}, zpass_quads {:?}",
        quads as f64 / cpu.max(1) as f64,
        ms("zpass_cpu"),
        ms("zpass_quads"),
    );
    for key in ["misclassified_pct", "false_shadow_pct", "false_lit_pct"] {
        let (a, b) = (
            support::error(r, "zpass_cpu", key),
            support::error(r, "zpass_quads", key),
        );
        assert_eq!(a, b, "{name}: {key} differs (cpu {a}, quads {b})");
    }
    let mut images = vec![String::new()];
    images.extend((0..lights).map(|k| format!("_visibility_l{k}")));
    for suffix in images {
        let a = run.out.join(format!("zpass_cpu{suffix}.png"));
        let b = run.out.join(format!("zpass_quads{suffix}.png"));
        let (pa, pb) = (pixels(&a), pixels(&b));
        let differ = pa.iter().zip(&pb).filter(|(x, y)| x != y).count();
        assert!(
            pa.len() == pb.len() && differ == 0,
            "{name}: {} and {} differ in {differ} bytes",
            a.display(),
            b.display()
        );
    }
    assert!(
        quads as f64 <= 1.1 * cpu as f64,
        "{name}: zpass_quads rasterises {quads} volume fragments, \
         more than 1.1 x zpass_cpu's {cpu}"
    );
}

/// An open, dense caster: each interior edge of the doubled mesh must
/// cancel in the vertex shader, not in the stencil.
#[test]
fn quads_fill_like_cpu_on_a_holed_sphere() {
    quads_fill_like_cpu("quad_fill_holed", Some("lesson_05_holed.toml"), 1);
}

/// Lesson 05's default scene: the floor is an open (two-sided) caster.
#[test]
fn quads_fill_like_cpu_on_the_default_scene() {
    quads_fill_like_cpu("quad_fill_default", None, 2);
}
