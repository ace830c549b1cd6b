//! lesson_05 (z-pass shadow volumes): snapshot of the masks and error
//! figures on the default scene, and the z-pass failure measured.
//!
//! Run `cargo insta review` after a change to see what moved.

mod depth_formats;

use std::path::Path;

use common::measure::counters::{
    DRAWS, EDGES_TESTED, SILHOUETTE_EDGES, STENCIL_UPDATES, VOLUME_FRAGMENTS, VOLUME_TRIANGLES,
};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_05");
const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

#[test]
fn lesson_05_snapshot() {
    let Some(run) = support::run_lesson(BIN, "lesson_05_snapshot", &SIZE) else {
        return;
    };
    let mut text = String::new();
    for k in 0..2 {
        text +=
            &format!("reference visibility, light {k} ('#' shadow, '.' lit, ' ' background):\n");
        text += &support::ascii_of(
            &run.out.join(format!("reference_visibility_l{k}.png")),
            64,
            18,
        );
        text += &format!("\n\nzpass_quads visibility, light {k}:\n");
        text += &support::ascii_of(
            &run.out.join(format!("zpass_quads_visibility_l{k}.png")),
            64,
            18,
        );
        text += "\n\n";
    }
    text += "error against the reference (percent, 0.01 points):\n";
    for v in run.report["variants"].as_array().unwrap() {
        text += &support::error_line(v, 2);
        text += "\n";
    }
    text += &support::counter_lines(
        &run.report,
        &[DRAWS.name, VOLUME_TRIANGLES.name, VOLUME_FRAGMENTS.name],
    );
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(
            "lesson_05",
            support::tolerance::adapter_line(&run.report) + &text
        )
    });
}

/// With the camera outside every volume, z-pass is exact (both builds).
#[test]
fn lesson_05_exact_when_the_eye_is_outside() {
    let Some(run) = support::run_lesson_env(BIN, "lesson_05_exact", &SIZE, support::TIMED) else {
        return;
    };
    for v in ["zpass_cpu", "zpass_quads"] {
        let m = support::misclassified(&run, v);
        assert!(m <= 0.5, "{v}: {m:.3}% misclassified");
        let t = &support::variant(&run.report, v)["timing_ms"];
        assert!(
            t["volume"].as_f64().is_some() && t["lighting"].as_f64().is_some(),
            "{v}: volume and lighting timed"
        );
    }
    let cpu = &support::variant(&run.report, "zpass_cpu")["timing_ms"];
    assert!(
        cpu["cpu_silhouette"].as_f64().is_some(),
        "the CPU path reports cpu_silhouette"
    );
    frame_cost_holds_cpu_and_gpu(&run.report);
}

/// Every timed frame's cost (`frame`) holds the CPU's work (`cpu_total`,
/// itself holding `cpu_silhouette`) and the GPU's (`total`): a route that
/// moves work to the CPU does not look free.
fn frame_cost_holds_cpu_and_gpu(report: &serde_json::Value) {
    let variants = report["variants"].as_array().expect("variants");
    for v in variants {
        let name = v["name"].as_str().unwrap_or("?");
        let s = &v["timing_samples_ms"];
        let series = |k: &str| -> Vec<f64> {
            let a = s[k]
                .as_array()
                .unwrap_or_else(|| panic!("{name}: no {k} samples"));
            a.iter().filter_map(|x| x.as_f64()).collect()
        };
        let (frame, cpu, gpu) = (series("frame"), series("cpu_total"), series("total"));
        assert!(!frame.is_empty() && frame.len() == cpu.len() && frame.len() == gpu.len());
        let silhouette = s.get("cpu_silhouette").map(|_| series("cpu_silhouette"));
        for i in 0..frame.len() {
            // A GPU clock and the CPU's may disagree by a hair.
            let slack = 0.05 + 0.01 * frame[i];
            assert!(
                frame[i] + slack >= cpu[i],
                "{name} frame {i}: frame {} < cpu_total {}",
                frame[i],
                cpu[i]
            );
            assert!(
                frame[i] + slack >= gpu[i],
                "{name} frame {i}: frame {} < GPU total {}",
                frame[i],
                gpu[i]
            );
            if let Some(sil) = &silhouette {
                assert!(
                    cpu[i] >= sil[i],
                    "{name} frame {i}: cpu_total {} < cpu_silhouette {}",
                    cpu[i],
                    sil[i]
                );
                assert!(sil[i] > 0.0, "{name}: the silhouette takes no time");
            }
        }
    }
}

/// The eye in the umbra, and the near plane in a volume: z-pass misses the
/// "enter" count and the error is large, in the adapter's default depth
/// format and in Depth24PlusStencil8.
#[test]
fn lesson_05_zpass_fails_inside_a_volume() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for format in depth_formats::DEPTH_FORMATS {
        for (name, min) in [
            ("volume_eye_in_umbra.toml", 10.0),
            ("volume_near_slice.toml", 5.0),
        ] {
            let s = scenes.join(name);
            let args = [
                &SIZE[..],
                &["--scene", s.to_str().unwrap(), "--variant", "zpass_quads"],
                &depth_formats::flag(format),
            ]
            .concat();
            let test = format!("lesson_05_{name}_{format}");
            let Some(run) = support::run_lesson(BIN, &test, &args) else {
                return;
            };
            let (depth, storage) = depth_formats::used(&run.report, format);
            let m = support::misclassified(&run, "zpass_quads");
            eprintln!("{name}, {depth} ({storage}): z-pass misclassified {m:.3}%");
            assert!(
                m > min,
                "{name}, {depth}: z-pass should fail here, misclassified {m:.2}%"
            );
        }
    }
}

// ---- the compute route (Extrusion::Compute) ---------------------------

/// Decoded pixels of a PNG (any format), to compare two outputs.
fn pixels(path: &Path) -> Vec<u8> {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
        .into_raw()
}

/// Every PNG `a*` has a twin `b*` with the same pixels, and the cost
/// counters agree: the same triangles, in another order, count the same.
pub fn same_as(run: &support::LessonRun, a: &str, b: &str) {
    let mut compared = 0;
    for entry in std::fs::read_dir(&run.out).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().to_string();
        let Some(rest) = name.strip_prefix(a).filter(|r| r.ends_with(".png")) else {
            continue;
        };
        let (pa, pb) = (run.out.join(&name), run.out.join(format!("{b}{rest}")));
        let (x, y) = (pixels(&pa), pixels(&pb));
        let differ = x.iter().zip(&y).filter(|(p, q)| p != q).count();
        assert!(
            x.len() == y.len() && differ == 0,
            "{name}: {differ} bytes differ from {b}{rest}"
        );
        compared += 1;
    }
    assert!(compared >= 3, "{a}: only {compared} images compared");
    for key in [
        VOLUME_FRAGMENTS.name,
        STENCIL_UPDATES.name,
        VOLUME_TRIANGLES.name,
        DRAWS.name,
        SILHOUETTE_EDGES.name,
        EDGES_TESTED.name,
    ] {
        let (x, y) = (
            support::counter(&run.report, a, key),
            support::counter(&run.report, b, key),
        );
        assert_eq!(x, y, "{key}: {a} {x}, {b} {y}");
    }
    assert!(support::counter(&run.report, a, SILHOUETTE_EDGES.name) > 0);
    let t = &support::variant(&run.report, a)["timing_ms"];
    assert!(
        t["extrude"].as_f64().is_some(),
        "{a}: the extrude pass is timed"
    );
}

/// The compute route draws the CPU route's volumes: the same pixels and
/// costs on the default scene, a non-manifold caster and an open caster.
#[test]
fn lesson_05_compute_matches_cpu() {
    for scene in ["", "volume_nonmanifold.toml", "volume_open_quad.toml"] {
        let path = support::scene_path(if scene.is_empty() {
            "lesson_05.toml"
        } else {
            scene
        });
        let args = [
            &SIZE[..],
            &["--scene", path.to_str().unwrap()],
            &["--variant", "zpass_cpu", "--variant", "zpass_compute"],
        ]
        .concat();
        let name = format!("lesson_05_compute_{}", scene.replace(".toml", ""));
        let Some(run) = support::run_lesson_env(BIN, &name, &args, support::TIMED) else {
            return;
        };
        same_as(&run, "zpass_compute", "zpass_cpu");
    }
}

mod compute_triangles {
    use common::glam::Vec3;
    use common::scene::mesh::builtin;
    use workbook::lesson_05::adjacency::Adjacency;
    use workbook::lesson_05::compute::{extrude_once, unavailable};
    use workbook::lesson_05::extrusion::{cpu_volume_reaching, CpuVertex};
    use workbook::lesson_05::silhouette::{caster_adjacency, LightDir};

    /// A triangle list as a sorted multiset of exact bit patterns (the
    /// winding is kept: each triangle's vertices stay in their order).
    fn multiset(v: &[CpuVertex]) -> Vec<[u32; 12]> {
        let mut t: Vec<[u32; 12]> = v
            .chunks_exact(3)
            .map(|t| {
                let words: Vec<u32> = t
                    .iter()
                    .flat_map(|v| [v.position[0], v.position[1], v.position[2], v.w])
                    .map(f32::to_bits)
                    .collect();
                words.try_into().unwrap()
            })
            .collect();
        assert_eq!(v.len() % 3, 0);
        t.sort();
        t
    }

    /// Three pages on one spine (two run it one way, one the other) and
    /// two faces that run one edge the same way: non-manifold and
    /// misoriented edges.
    fn nonmanifold() -> Adjacency {
        let p = [
            Vec3::ZERO,
            Vec3::Y,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(-1.0, 0.5, -1.0),
        ];
        #[rustfmt::skip]
        let indices = [
            0, 1, 2,  0, 2, 3,
            1, 0, 5,  1, 5, 4,
            0, 1, 6,  0, 6, 7,
            0, 1, 8,
        ];
        Adjacency::from_triangles(&p, &indices)
    }

    fn lights() -> Vec<LightDir> {
        let mut lights = vec![
            LightDir::Point(Vec3::new(0.0, 3.0, 0.0)),
            LightDir::Point(Vec3::new(2.0, 3.0, 1.0)),
            LightDir::Point(Vec3::ZERO),
            LightDir::Point(Vec3::new(0.5, 0.7, 0.5)),
            LightDir::Directional(Vec3::new(-0.4, -1.0, -0.3)),
            LightDir::Directional(Vec3::X),
        ];
        for k in 0..12 {
            let a = k as f32 * 2.399_963;
            let d = Vec3::new(a.cos(), (k as f32 / 6.0) - 1.0, a.sin());
            lights.push(LightDir::Directional(d));
            lights.push(LightDir::Point(d * 1.7));
        }
        lights
    }

    /// The compute shader's triangles are `cpu_volume`'s, as multisets:
    /// sides, front cap and back cap, on the built-ins (open `plane` cast
    /// two-sided, as the lesson does) and a non-manifold mesh, at infinity
    /// and with a finite reach.
    #[test]
    fn compute_volume_equals_cpu_volume() {
        let Some(gpu) = support::test_gpu() else {
            return;
        };
        if let Some(why) = unavailable(&gpu) {
            panic!("{why}");
        }
        let mut meshes: Vec<(String, Adjacency)> = ["cube", "sphere", "torus", "knot", "plane"]
            .iter()
            .map(|n| (n.to_string(), caster_adjacency(&builtin(n).unwrap())))
            .collect();
        meshes.push(("non-manifold".into(), nonmanifold()));
        let mut sides = 0;
        for (name, adj) in &meshes {
            for light in lights() {
                for reach in [0.0, 0.25] {
                    let mut cpu = Vec::new();
                    let r = cpu_volume_reaching(adj, light, reach, &mut cpu);
                    let gpu_parts = extrude_once(&gpu, adj, light, reach).unwrap();
                    for (part, (range, got)) in [r.sides, r.front, r.back]
                        .iter()
                        .zip(&gpu_parts)
                        .enumerate()
                    {
                        let want = &cpu[range.start as usize..range.end as usize];
                        assert!(
                            multiset(want) == multiset(got),
                            "{name}, {light:?}, reach {reach}, part {part}: \
                             cpu {} vertices, compute {}",
                            want.len(),
                            got.len()
                        );
                    }
                    sides += gpu_parts[0].len();
                }
            }
        }
        assert!(sides > 0);
    }
}

/// A route whose buffers would pass the adapter's limits is left out with
/// one note naming the variant, the buffer, its size and the limit; the
/// routes that fit still run. `WORKBOOK_MAX_BUFFER_SIZE` gives this adapter
/// a smaller GPU's room: 60 MB holds the dense knot's CPU and compute
/// volumes (47 MB) but not its quads (90 MB). The compute route splits its
/// buffers into chunks of what one binding may hold, so with 4 MB it still
/// runs, alone, and draws the same frame; asked for by name, a route that
/// does not fit is one error line, and a non-zero exit.
#[test]
fn lesson_05_a_route_over_the_limit_is_left_out() {
    let scene = support::scene_path("lesson_05_dense.toml");
    let mut args = SIZE.to_vec();
    args.extend(["--scene", scene.to_str().unwrap()]);
    let env = [("WORKBOOK_MAX_BUFFER_SIZE", "60000000")];
    let Some(run) = support::run_lesson_env(BIN, "lesson_05_small_buffers", &args, &env) else {
        return;
    };
    let notes: Vec<&str> = run
        .stderr
        .lines()
        .filter(|l| l.starts_with("note:"))
        .collect();
    assert_eq!(notes.len(), 1, "one route left out: {}", run.stderr);
    assert!(
        notes[0].contains("skipped zpass_quads: the quad route's vertex buffer for dense_knot")
            && notes[0].contains("(max_buffer_size = 60000000 bytes)"),
        "the note names the variant, the buffer and the limit: {}",
        notes[0]
    );
    let ran: Vec<&str> = (run.report["variants"].as_array().unwrap().iter())
        .map(|v| v["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        ran,
        ["zpass_cpu", "zpass_compute"],
        "the routes that fit run"
    );
    for v in ran {
        let m = support::misclassified(&run, v);
        assert!(m <= 0.5, "{v}: {m:.3}% misclassified");
    }

    // 4 MB: only the compute route, in chunks, and the same frame.
    let env = [("WORKBOOK_MAX_BUFFER_SIZE", "4000000")];
    let Some(run) = support::run_lesson_env(BIN, "lesson_05_chunks", &args, &env) else {
        return;
    };
    let notes = run.stderr.lines().filter(|l| l.starts_with("note:"));
    assert_eq!(
        notes.count(),
        2,
        "the CPU and quad routes left out: {}",
        run.stderr
    );
    let ran: Vec<&str> = (run.report["variants"].as_array().unwrap().iter())
        .map(|v| v["name"].as_str().unwrap())
        .collect();
    assert_eq!(ran, ["zpass_compute"], "the compute route runs in chunks");
    let m = support::misclassified(&run, "zpass_compute");
    assert!(m <= 0.5, "zpass_compute in chunks: {m:.3}% misclassified");

    let out = support::out_dir("lesson_05_no_room");
    let o = support::lesson_command(BIN)
        .env("WORKBOOK_MAX_BUFFER_SIZE", "4000000")
        .args(["--headless", "--out"])
        .arg(&out)
        .args(&args)
        .args(["--variant", "zpass_cpu", "--variant", "zpass_quads"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
    assert!(!o.status.success(), "nothing fits: a non-zero exit");
    assert_eq!(errors.len(), 1, "one error line: {stderr}");
    assert!(
        errors[0].contains("zpass_cpu") && errors[0].contains("(max_buffer_size = 4000000 bytes)"),
        "the error names the variant asked for and the limit: {stderr}"
    );
}
