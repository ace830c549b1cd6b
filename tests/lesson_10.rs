//! lesson_10 (soft shadows from area lights): the snapshot (error in and
//! out of the penumbra, bleeding and taps per variant), the bar
//! (PCSS's penumbra error at most half the fixed kernels'), and the five
//! extreme cases, each with the naive technique's failure beside the fix:
//! a contact, a large light, blockers at two heights, a thin occluder over
//! a receiver, grazing light.
//!
//! Run `cargo insta review` after a change to see what moved.

use common::measure::counters::{
    BLOCKER_SEARCH_TAPS, DRAWS, FILTER_TAPS_PER_PIXEL, SHADOW_MAP_SIZE, TEXELS_READ,
};

const BIN: &str = env!("CARGO_BIN_EXE_lesson_10");

fn run(name: &str, scene: Option<&str>, extra: &[&str]) -> Option<support::LessonRun> {
    support::run_small(BIN, name, scene, extra)
}

/// Mean |ΔV| in the reference's penumbra.
fn penumbra(run: &support::LessonRun, variant: &str) -> f64 {
    support::error(&run.report, variant, "penumbra_mean_abs")
}

/// Light bleeding: % of the reference's umbra lit above 0.1.
fn bleeding(run: &support::LessonRun, variant: &str) -> f64 {
    support::error(&run.report, variant, "light_bleeding_pct")
}

/// Variants whose error figures no cross-adapter tolerance holds, left out
/// of the snapshot's figures (their counters stay). `threejs_vsm` keeps,
/// as three.js does, the mean and standard deviation of the map's own
/// perspective depth, which crowds near 1: its variance is the difference
/// of two f32 numbers near 1 that differ in the seventh digit, so a depth
/// a rasteriser rounds otherwise moves its figures (llvmpipe's GL against
/// lavapipe's Vulkan: penumbra |dV| 20.5 % against 22.2 %). Its figures
/// are checked exactly on the records' adapter by `tests/generated.rs`.
const ADAPTER_DEPENDENT: &[&str] = &["threejs_vsm"];

#[test]
fn lesson_10_snapshot() {
    let Some(run) = run("lesson_10_snapshot", None, &[]) else {
        return;
    };
    let mut text = String::from(
        "per variant: blocker-search and filter taps, texels read, and the error against the\n",
    );
    text +=
        "exact visible fraction of the spot's 25 cm disk: misclassified %, mean |V - V_ref| and\n";
    text +=
        "the same in the reference's penumbra (both in percent), light bleeding % of the umbra\n\n";
    for v in run.report["variants"].as_array().expect("variants") {
        let name = v["name"].as_str().unwrap();
        if ADAPTER_DEPENDENT.contains(&name) {
            text += &format!(
                "{name:<16} search {:>2}  filter {:>2}  texels {:>2}  figures: adapter-dependent (see ADAPTER_DEPENDENT)\n",
                support::counter(&run.report, name, BLOCKER_SEARCH_TAPS.name),
                support::counter(&run.report, name, FILTER_TAPS_PER_PIXEL.name),
                support::counter(&run.report, name, TEXELS_READ.name),
            );
            continue;
        }
        text += &format!(
            "{name:<16} search {:>2}  filter {:>2}  texels {:>2}  misclassified {:>5.2}%{}  mean |dV| {:>4.1}%{}  penumbra |dV| {:>4.1}%{}  bleeding {:>5.2}%{}\n",
            support::counter(&run.report, name, BLOCKER_SEARCH_TAPS.name),
            support::counter(&run.report, name, FILTER_TAPS_PER_PIXEL.name),
            support::counter(&run.report, name, TEXELS_READ.name),
            support::error(&run.report, name, "misclassified_pct"),
            support::bound(v, "misclassified_pct", 1.0, 2),
            100.0 * support::error(&run.report, name, "mean_abs"),
            support::bound(v, "mean_abs", 100.0, 1),
            100.0 * penumbra(&run, name),
            support::bound(v, "penumbra_mean_abs", 100.0, 1),
            bleeding(&run, name),
            support::bound(v, "light_bleeding_pct", 1.0, 2),
        );
    }
    text += &support::counter_lines(&run.report, &[DRAWS.name, SHADOW_MAP_SIZE.name]);
    support::tolerance::tolerant(|| {
        insta::assert_snapshot!(
            "lesson_10",
            support::tolerance::adapter_line(&run.report) + &text
        )
    });
}

// ANCHOR: pcss_bar
/// The bar: on the default scene PCSS's mean |ΔV| in the penumbra
/// is at most half that of a fixed disk with the same 16 filter taps, and
/// of one with 32 (as many as PCSS's search and filter together).
#[test]
fn lesson_10_pcss_halves_the_fixed_kernels_penumbra_error() {
    let Some(run) = run(
        "lesson_10_bar",
        None,
        &[
            "--variant",
            "pcss",
            "--variant",
            "pcf_wide_16",
            "--variant",
            "pcf_wide_32",
        ],
    ) else {
        return;
    };
    let pcss = penumbra(&run, "pcss");
    for fixed in ["pcf_wide_16", "pcf_wide_32"] {
        let f = penumbra(&run, fixed);
        assert!(
            pcss <= 0.5 * f,
            "pcss penumbra |dV| {pcss:.4} is not at most half of {fixed}'s {f:.4}"
        );
    }
}
// ANCHOR_END: pcss_bar

/// Tuned to one scene, a fixed disk comes closer to PCSS (measured: 6
/// texels on the default scene, within 1.8×); but the best radius moves
/// from scene to scene with the blockers' heights, and PCSS needs none. For
/// every radius from 4 to 16 texels, some scene (the default, the contact,
/// the large light) has the fixed disk's penumbra error at least twice
/// PCSS's.
#[test]
fn lesson_10_no_fixed_radius_serves_every_scene() {
    let scenes = [
        None,
        Some("lesson_10_contact.toml"),
        Some("lesson_10_large_light.toml"),
    ];
    let mut pcss = Vec::new();
    for (i, &scene) in scenes.iter().enumerate() {
        let name = format!("lesson_10_sweep_pcss_{i}");
        let Some(base) = run(&name, scene, &["--variant", "pcss"]) else {
            return;
        };
        pcss.push(penumbra(&base, "pcss"));
    }
    for r in [4.0, 6.0, 8.0, 12.0, 16.0] {
        let knob = format!("kernel_radius_texels={r}");
        let args = ["--variant", "pcf_wide_16", "--knob", knob.as_str()];
        let mut worst: f64 = 0.0;
        for (i, &scene) in scenes.iter().enumerate() {
            let Some(swept) = run(&format!("lesson_10_sweep_{r}_{i}"), scene, &args) else {
                return;
            };
            worst = worst.max(penumbra(&swept, "pcf_wide_16") / pcss[i]);
        }
        assert!(
            worst >= 2.0,
            "a fixed disk of {r} texels is within {worst:.2}× of pcss on every scene"
        );
    }
}

/// Contact: the penumbra must shrink to nothing where the cube and the
/// sphere touch the floor. PCSS's kernel does; a floor on its width (6
/// texels, the fixed kernel's flaw put back) blurs the contact open and
/// lights the umbra along it.
#[test]
fn lesson_10_contact_shadows_close() {
    let scene = Some("lesson_10_contact.toml");
    let Some(fix) = run("lesson_10_contact", scene, &["--variant", "pcss"]) else {
        return;
    };
    let (p, b) = (penumbra(&fix, "pcss"), bleeding(&fix, "pcss"));
    assert!(p <= 0.07, "pcss penumbra |dV| {p:.4} above 0.07 at contact");
    assert!(
        b <= 0.5,
        "pcss lights {b:.2}% of the contact umbra (> 0.5%)"
    );
    let naive = ["--variant", "pcss", "--knob", "min_filter_texels=6"];
    let Some(naive) = run("lesson_10_contact_floor", scene, &naive) else {
        return;
    };
    let b = bleeding(&naive, "pcss");
    assert!(
        b >= 1.5,
        "a 6-texel floor should light the contact umbra, bleeding {b:.2}%"
    );
}

/// A large light (1 m radius): a blocker hides part of the emitter from
/// receivers far outside the light's size at the receiver. PCSS searches
/// every blocker up to the nearest caster; searching only the light's size
/// at the receiver (Filament's search, put back by a knob) misses the
/// higher casters and narrows their penumbrae.
#[test]
fn lesson_10_large_light_needs_the_wide_search() {
    let scene = Some("lesson_10_large_light.toml");
    let Some(fix) = run("lesson_10_large", scene, &["--variant", "pcss"]) else {
        return;
    };
    let p = penumbra(&fix, "pcss");
    assert!(
        p <= 0.055,
        "pcss penumbra |dV| {p:.4} above 0.055 under a 1 m light"
    );
    let naive = ["--variant", "pcss", "--knob", "search_at_receiver=1"];
    let Some(naive) = run("lesson_10_large_narrow", scene, &naive) else {
        return;
    };
    let n = penumbra(&naive, "pcss");
    assert!(
        n >= 1.5 * p,
        "the narrow search should miss blockers: {n:.4} vs {p:.4}"
    );
}

/// The mean |ΔV| between two visibility images in a pixel window.
fn window_error(run: &support::LessonRun, variant: &str, x: u32, y: u32, w: u32, h: u32) -> f64 {
    let read = |name: &str| support::read_visibility(&run.out.join(name));
    let (_, exact, width, _) = read("reference_visibility_l0.png");
    let (_, v, _, _) = read(&format!("{variant}_visibility_l0.png"));
    let mut sum = 0.0;
    for j in y..y + h {
        for i in x..x + w {
            let p = (j * width + i) as usize;
            sum += (v[p] - exact[p]).abs() as f64;
        }
    }
    sum / (w * h) as f64
}

/// Blockers at two heights side by side: near the low board's edge the
/// search finds the high board too, and the mean of the two distances gives
/// one width that is neither's. No single-average PCSS fixes this; the test
/// measures the failure (the window at the junction against the high
/// board's far edge) and bounds it, and PCSS still beats the fixed kernel.
#[test]
fn lesson_10_blockers_at_two_heights_break_the_average() {
    let scene = Some("lesson_10_overlap.toml");
    let Some(run) = run(
        "lesson_10_overlap",
        scene,
        &["--variant", "pcss", "--variant", "pcf_wide_16"],
    ) else {
        return;
    };
    let junction = window_error(&run, "pcss", 280, 130, 40, 80);
    let far_edge = window_error(&run, "pcss", 60, 130, 60, 80);
    assert!(
        junction >= 2.0 * far_edge,
        "the blocker average should fail at the junction: {junction:.4} vs {far_edge:.4}"
    );
    assert!(
        junction <= 0.1,
        "junction mean |dV| {junction:.4} above 0.1"
    );
    let (p, f) = (penumbra(&run, "pcss"), penumbra(&run, "pcf_wide_16"));
    assert!(p <= 0.5 * f, "pcss {p:.4} against the fixed disk's {f:.4}");
}

/// A thin sheet over a box: two depths under one blurred texel, and the
/// variance map's Chebyshev bound lets light through onto the box and the
/// floor around it. The bleeding cut removes it; without it (`vsm`, the
/// flaw put back) it stays.
#[test]
fn lesson_10_thin_occluder_bleeds_without_the_cut() {
    let scene = Some("lesson_10_thin.toml");
    let Some(run) = run(
        "lesson_10_thin",
        scene,
        &["--variant", "vsm", "--variant", "vsm_bleed_cut"],
    ) else {
        return;
    };
    let (plain, cut) = (bleeding(&run, "vsm"), bleeding(&run, "vsm_bleed_cut"));
    assert!(
        cut <= 0.5,
        "vsm_bleed_cut still bleeds {cut:.2}% of the umbra"
    );
    assert!(
        plain >= 1.5,
        "vsm should bleed under the thin sheet: {plain:.2}%"
    );
}

/// Grazing light (80° from the floor's normal): the wide kernels' outer
/// taps see the floor itself in front of the receiver unless each compares
/// with the receiver's plane. Without it (the flaw put back) acne.
#[test]
fn lesson_10_grazing_light_needs_the_receiver_plane() {
    let scene = Some("lesson_10_grazing.toml");
    let Some(fix) = run("lesson_10_grazing", scene, &["--variant", "pcss"]) else {
        return;
    };
    let f = support::error(&fix.report, "pcss", "false_shadow_pct");
    assert!(
        f <= 0.15,
        "pcss false shadow {f:.3}% above 0.15 at grazing light"
    );
    let naive = ["--variant", "pcss", "--knob", "receiver_plane=0"];
    let Some(naive) = run("lesson_10_grazing_flat", scene, &naive) else {
        return;
    };
    let n = support::error(&naive.report, "pcss", "false_shadow_pct");
    assert!(
        n >= 2.0 * f.max(0.1),
        "no receiver plane should acne: {n:.3}% vs {f:.3}%"
    );
}

/// Every earlier lesson refuses a light with a size, in one line that
/// names lesson 10.
#[test]
fn earlier_lessons_refuse_area_lights() {
    let scene = support::scene_path("lesson_10_contact.toml");
    let out = support::out_dir("lesson_10_refused");
    let o = support::lesson_command(env!("CARGO_BIN_EXE_lesson_03"))
        .args(["--headless", "--out"])
        .arg(&out)
        .arg("--scene")
        .arg(&scene)
        .output()
        .expect("run lesson_03");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "lesson_03 rendered an area light");
    assert!(
        stderr.contains("lights[0].angular_radius_deg") && stderr.contains("lesson_10"),
        "{stderr}"
    );
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
}

/// PCSS with the adaptive filter (`pcss_adaptive`): its 4 rim probes
/// decide only where all four agree, and there the disk agrees with them,
/// so its error is PCSS's: penumbra |dV| within half a point, bleeding
/// within a point. Probes that decide wrongly (a penumbra pixel returned
/// as lit or umbra) move the penumbra's error first.
#[test]
fn lesson_10_adaptive_filter_keeps_pcss_error() {
    let Some(run) = run(
        "lesson_10_adaptive",
        None,
        &["--variant", "pcss", "--variant", "pcss_adaptive"],
    ) else {
        return;
    };
    let (a, b) = (penumbra(&run, "pcss_adaptive"), penumbra(&run, "pcss"));
    assert!(
        (a - b).abs() <= 0.005,
        "pcss_adaptive penumbra |dV| {a:.4} against pcss's {b:.4}"
    );
    let (a, b) = (bleeding(&run, "pcss_adaptive"), bleeding(&run, "pcss"));
    assert!(
        (a - b).abs() <= 1.0,
        "pcss_adaptive bleeding {a:.3} % against pcss's {b:.3} %"
    );
}

/// `pcss_min_max`'s chain answers only where PCSS's taps would answer the
/// same: with the chain and without it (`--knob min_max=0`, the same map
/// without the flat ground) every visibility pixel and every error figure
/// is the same, under the default scene's spot and the grazing scene's sun.
/// And it answers: with `--knob chain_only=1` (its answers alone, the rest
/// black) at least a third of the receiver pixels are answered lit, each
/// lit in the full image too. A chain that answered wrongly anywhere, or
/// never, fails here.
#[test]
fn lesson_10_min_max_chain_answers_as_the_taps_would() {
    let v = ["--variant", "pcss_min_max"];
    for scene in [None, Some("lesson_10_grazing.toml")] {
        let name = |k: &str| format!("lesson_10_min_max_{}_{k}", scene.unwrap_or("default"));
        let knob = |k: &'static str| [&v[..], &["--knob", k]].concat();
        let Some(on) = run(&name("on"), scene, &v) else {
            return;
        };
        let off = run(&name("off"), scene, &knob("min_max=0")).expect("an adapter");
        let only = run(&name("only"), scene, &knob("chain_only=1")).expect("an adapter");
        let image = |r: &support::LessonRun| {
            support::read_visibility(&r.out.join("pcss_min_max_visibility_l0.png"))
        };
        let ((ids, with, ..), (_, without, ..), (_, answers, ..)) =
            (image(&on), image(&off), image(&only));
        let differ = with.iter().zip(&without).filter(|(a, b)| a != b).count();
        assert_eq!(
            differ, 0,
            "{scene:?}: {differ} pixels differ with the chain and without it"
        );
        let figures =
            |r: &support::LessonRun| support::variant(&r.report, "pcss_min_max")["error"].clone();
        assert_eq!(
            figures(&on),
            figures(&off),
            "{scene:?}: the error figures differ"
        );
        let receivers = ids.iter().filter(|&&i| i == 1).count();
        let answered: Vec<usize> = (0..ids.len())
            .filter(|&i| ids[i] == 1 && answers[i] == 1.0)
            .collect();
        let wrong = answered.iter().filter(|&&i| with[i] != 1.0).count();
        eprintln!(
            "{scene:?}: the chain answered {} of {receivers} receiver pixels lit",
            answered.len()
        );
        assert_eq!(
            wrong, 0,
            "{scene:?}: {wrong} pixels answered lit are not lit"
        );
        assert!(
            answered.len() * 3 >= receivers,
            "{scene:?}: the chain answered only {} of {receivers} receiver pixels lit",
            answered.len()
        );
    }
}
