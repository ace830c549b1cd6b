//! The headless runner: renders every variant offscreen, compares it with
//! the exact reference, times it, and writes the outputs the book's
//! appendix "Interfaces" lists (`book/src/appendix/interfaces.md`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use crate::gpu::depth_probe::DepthStorage;
use crate::gpu::render::SceneGpu;
use crate::gpu::targets::{FrameImages, FrameTargets};
use crate::gpu::Gpu;
use crate::measure::baseline::Baseline;
use crate::measure::protocol::{block_order, time_blocks, verdicts, Verdicts, WarmUp};
use crate::measure::report::{combine, AdapterReport, BaselineReport, CameraPathReport, Report};
use crate::measure::report::{TimingCheck, VariantReport};
use crate::measure::timing::{median_times, samples, spread_times, FrameTimes, Timer};
use crate::reference::metrics::{self, ErrorStats, ReferenceStates};
use crate::reference::{cache, dv_view, Reference};
use crate::run::camera_walk::{light_states, PathWalk};
use crate::run::cli::Args;
use crate::run::files::{save, write_json};
use crate::run::instruments::{apply_cli_knobs, knob_values, Instruments};
use crate::run::jittered;
use crate::run::lesson::variant_name;
use crate::scene::camera_path::check_path;
use crate::scene::Scene;

/// What a headless run wrote: the report, and the folder it wrote into.
pub struct HeadlessRun {
    pub report: Report,
    pub out_dir: PathBuf,
}

/// A headless run's GPU, scene, lesson, and the variants it can render,
/// set up as the command line says ([`setup`]).
pub(crate) struct Setup<L: Instruments> {
    pub out_dir: PathBuf,
    pub gpu: Gpu,
    pub sg: SceneGpu,
    pub targets: FrameTargets,
    pub lesson: L,
    pub timer: Timer,
    pub runnable: Vec<L::Variant>,
    pub adapter: AdapterReport,
    pub scene_name: String,
}

/// Checks the command line against the scene and the lesson, opens the
/// GPU and the output folder, builds the lesson and sets its knobs.
pub(crate) fn setup<L: Instruments>(
    args: &Args,
    scene: Scene,
    variants: &[L::Variant],
) -> Result<Setup<L>> {
    let out_dir = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(L::NAME));
    std::fs::create_dir_all(&out_dir)
        .with_context(|| format!("--out: cannot create {}", out_dir.display()))?;
    if scene.camera_path.is_some() && !L::CAPABILITIES.camera_path {
        anyhow::bail!(
            "scene {}: [camera_path]: {} does not re-fit to a moving camera; lessons 01 and 09 do",
            scene.name,
            L::NAME
        );
    }
    check_path(&scene).map_err(|e| anyhow::anyhow!("scene {}: {e}", scene.name))?;
    let names: Vec<String> = variants.iter().map(|&v| variant_name(v)).collect();
    if let Some(f) = (args.fragile_variants.iter()).find(|f| !names.contains(f)) {
        let names = names.join(", ");
        anyhow::bail!("--fragile-variant: {f:?} is not a variant of this run ({names})");
    }
    let gpu = Gpu::open(
        args.backend.as_deref(),
        args.adapter.as_deref(),
        args.depth_format.as_deref(),
        None,
    )?;
    let scene_name = scene.name.clone();
    let depth = gpu.depth_stencil_format();
    let depth_probe = crate::gpu::depth_probe::probe(&gpu, depth)?;
    if depth_probe.storage == DepthStorage::Unknown {
        eprintln!(
            "warning: {}: cannot tell what {depth:?} stores on {} (depth probe: {depth_probe:?}); report.json says \"unknown\"",
            L::NAME,
            gpu.adapter_name()
        );
    }
    let adapter = AdapterReport {
        name: gpu.adapter_name(),
        backend: gpu.backend_name(),
        depth_format: format!("{depth:?}"),
        depth_storage: depth_probe.storage.name().to_string(),
    };
    let sg = SceneGpu::new(&gpu, scene, args.width, args.height)?;
    let targets = sg.frame_targets(&gpu);
    let mut lesson = L::new(&gpu, &sg)?;
    let timer = Timer::new(&gpu);
    let mut runnable = Vec::new();
    for &variant in variants {
        match lesson.unavailable(variant) {
            Some(why) if !args.variants.is_empty() => anyhow::bail!("{why}"),
            Some(why) => eprintln!("note: {}: skipped {why}", L::NAME),
            None => runnable.push(variant),
        }
    }
    if runnable.is_empty() {
        anyhow::bail!("this adapter can render none of the variants (the notes above say why)");
    }
    apply_cli_knobs(&mut lesson, &gpu, &sg, &runnable, &args.knobs)?;
    Ok(Setup {
        out_dir,
        gpu,
        sg,
        targets,
        lesson,
        timer,
        runnable,
        adapter,
        scene_name,
    })
}

/// Times every variant, back to back and interleaved with the no-shadow
/// baseline, before any CPU-only work lets the GPU idle
/// (measure::protocol).
pub(crate) fn time_variants<L: Instruments>(s: &mut Setup<L>, args: &Args) -> Result<Verdicts> {
    let baseline = Baseline::new(&s.gpu, &s.sg);
    let order = block_order(s.runnable.len());
    let (lesson, sg, targets, runnable) = (&mut s.lesson, &s.sg, &s.targets, &s.runnable);
    let blocks = time_blocks(
        &mut s.timer,
        &s.gpu,
        WarmUp::with_min_ms(args.warm_up_ms),
        args.frames,
        &order,
        |frame, id| match id {
            Some(i) => lesson.render(frame, sg, targets, runnable[i]),
            None => baseline.render(frame, sg, targets),
        },
    )?;
    let names: Vec<String> = runnable.iter().map(|&v| variant_name(v)).collect();
    Ok(verdicts(&blocks, &names, args.warm_up_ms))
}

/// The no-shadow baseline's times, from the timed blocks.
pub(crate) fn baseline_report(t: &Verdicts) -> BaselineReport {
    BaselineReport {
        timing_ms: median_times(&t.baseline.0),
        timing_spread_ms: spread_times(&t.baseline.0),
        timing_samples_ms: samples(&t.baseline.0),
        blocks: t.baseline.1.clone(),
    }
}

// ANCHOR: run_headless
/// Renders every variant offscreen, compares it with the exact reference,
/// times it, and writes the outputs the book's appendix "Interfaces"
/// lists to the output folder.
pub fn run_headless<L: Instruments>(
    args: &Args,
    scene: Scene,
    variants: &[L::Variant],
) -> Result<HeadlessRun> {
    let mut s = setup::<L>(args, scene, variants)?;
    // 1. Time every variant first (`--no-timing` times nothing: the tests
    //    read no times).
    let timed = match args.no_timing {
        true => None,
        false => Some(time_variants(&mut s, args)?),
    };
    // 2. The exact reference, once for the run.
    let mut truth = Truth::new(&s.sg, &s.out_dir, args)?;
    // 3. Each variant's images, error, counters and checks (untimed).
    let mut rows = Vec::new();
    for (i, variant) in s.runnable.clone().into_iter().enumerate() {
        let times = timed.as_ref().map(|t| &t.variants[i]);
        rows.push(measure_variant(&mut s, &mut truth, args, variant, times)?);
    }
    // 4. The report.
    let report = Report {
        lesson: L::NAME.to_string(),
        adapter: s.adapter,
        width: args.width,
        height: args.height,
        scene: s.scene_name,
        reference_ms: truth.reference.ms,
        frames: args.frames,
        variants: rows,
        baseline: timed.as_ref().map(baseline_report),
        timing_protocol: timed.map(|t| t.protocol),
    };
    write_json(&report, &s.out_dir.join("report.json"))?;
    Ok(HeadlessRun {
        report,
        out_dir: s.out_dir,
    })
}
// ANCHOR_END: run_headless

/// The exact reference of the run's view, what every variant is measured
/// against.
struct Truth {
    reference: Reference,
    /// Each pixel's lit or shadowed state in the reference, per light.
    states: ReferenceStates,
    /// Per pixel, the distance along the camera's forward axis to the
    /// surface it sees (NaN where none): for the lesson's pixel classes.
    view_depth: Vec<f32>,
    /// The camera path's references, one per frame, computed for the first
    /// variant and kept for the others.
    path_references: Vec<(ReferenceStates, Vec<bool>)>,
}

impl Truth {
    /// Casts the reference for the scene's camera (or reads it from the
    /// cache), refuses a view with no receiver, and writes each light's
    /// reference visibility image.
    fn new(sg: &SceneGpu, out_dir: &Path, args: &Args) -> Result<Truth> {
        let reference = cache::reference(&sg.scene, sg.camera.view_proj, args.width, args.height)?;
        check_receivers(sg, &reference)?;
        let c = &sg.scene.camera;
        let forward = (c.target - c.eye).normalize().as_vec3();
        let view_depth = metrics::view_depth(&reference, sg.camera.eye, forward);
        for k in 0..sg.scene.lights.len() {
            save(
                &metrics::reference_visibility_image(&reference, k),
                &out_dir.join(format!("reference_visibility_l{k}.png")),
            )?;
        }
        Ok(Truth {
            states: ReferenceStates::new(&reference),
            reference,
            view_depth,
            path_references: Vec::new(),
        })
    }
}

/// One variant, untimed: its frames up to the one the lesson counts on,
/// its images and their error, the lesson's instruments, the `--fragile`
/// bounds and the camera path; `times` are its timed frames, if any.
fn measure_variant<L: Instruments>(
    s: &mut Setup<L>,
    truth: &mut Truth,
    args: &Args,
    variant: L::Variant,
    times: Option<&(Vec<FrameTimes>, TimingCheck)>,
) -> Result<VariantReport> {
    let v = variant_name(variant);
    let images = render_counted(s, variant)?;
    let color = image::RgbaImage::from_raw(args.width, args.height, images.color.clone())
        .context("colour readback size")?;
    save(&color, &s.out_dir.join(format!("{v}.png")))?;
    let per_light = light_errors(&s.sg, truth, &images, &v, &s.out_dir)?;
    write_instrument_images(s, variant, &v)?;
    let states = light_states(&truth.states, &images);
    let class_map = s.lesson.pixel_classes(&s.sg, variant, &truth.view_depth);
    let classes = match &class_map {
        Some((names, class_of)) => Some(metrics::class_errors(names, class_of, &states)?),
        None => None,
    };
    // Counters first: the path's and the jitter's frames may change
    // what a frame counts.
    let counters = s.lesson.counters(variant).to_report();
    let fragile = match args.measures_bounds(&v) {
        true => {
            let run = jittered::Measured {
                reference: &truth.reference,
                images: &images,
                counters: &counters,
                classes: class_map.as_ref(),
            };
            let (gpu, sg, targets) = (&s.gpu, &mut s.sg, &s.targets);
            let (timer, lesson) = (&mut s.timer, &mut s.lesson);
            Some(jittered::fragile_of(
                gpu, sg, targets, timer, lesson, variant, run,
            )?)
        }
        false => None,
    };
    let camera_path = walk_camera_path(s, truth, variant, &v, &color)?;
    let no_times = Vec::new();
    let (times, check) = match times {
        Some((times, check)) => (times, Some(check.clone())),
        None => (&no_times, None),
    };
    Ok(VariantReport {
        name: v,
        error: combine(&per_light),
        error_per_light: per_light,
        timing_ms: median_times(times),
        timing_spread_ms: spread_times(times),
        timing_samples_ms: samples(times),
        timing_source: s.timer.source(),
        counters,
        knobs: knob_values(&s.lesson, variant),
        camera_path,
        classes,
        timing_check: check,
        fragile,
    })
}

/// Renders `variant`'s frames up to the one the lesson counts on (the
/// targets hold the last timed block's frame) and reads its images: the
/// counters go with the images.
fn render_counted<L: Instruments>(s: &mut Setup<L>, variant: L::Variant) -> Result<FrameImages> {
    for _ in 0..L::CAPABILITIES.counted_on_frame {
        let mut frame = s.timer.frame(&s.gpu);
        s.lesson.render(&mut frame, &s.sg, &s.targets, variant)?;
        frame.finish()?;
    }
    s.targets.read(&s.gpu)
}

/// Each light's error against the reference, with its visibility, diff
/// and (a light with a size) ΔV images written as `{v}_..._l{k}.png`.
fn light_errors(
    sg: &SceneGpu,
    truth: &Truth,
    images: &FrameImages,
    v: &str,
    out_dir: &Path,
) -> Result<Vec<ErrorStats>> {
    let (w, h, reference) = (sg.width, sg.height, &truth.reference);
    let mut per_light = Vec::new();
    for k in 0..sg.scene.lights.len() {
        let vis = &images.visibility[k];
        // Receivers below their own horizon for part of the emitter: apart.
        let clipped = reference.horizon_clipped.get(k).map(Vec::as_slice);
        let cmp = metrics::compare(reference, k, &images.id, vis, clipped);
        save(
            &metrics::visibility_image(&images.id, vis, w, h),
            &out_dir.join(format!("{v}_visibility_l{k}.png")),
        )?;
        save(&cmp.diff, &out_dir.join(format!("{v}_diff_l{k}.png")))?;
        // A soft shadow's error is below the diff's V = ½: its signed ΔV.
        if reference.area_light[k] {
            save(
                &dv_view::dv_image(reference, k, &images.id, vis),
                &out_dir.join(format!("{v}_dv_l{k}.png")),
            )?;
        }
        per_light.push(cmp.stats);
    }
    Ok(per_light)
}

/// The lesson's extra images and its buffer view (`{v}_buffer.png`).
fn write_instrument_images<L: Instruments>(
    s: &Setup<L>,
    variant: L::Variant,
    v: &str,
) -> Result<()> {
    s.lesson.write_extras(&s.gpu, &s.sg, variant, &s.out_dir)?;
    if let Some(b) = s.lesson.buffer_view(&s.gpu, &s.sg, variant)? {
        save(&b.image, &s.out_dir.join(format!("{v}_buffer.png")))?;
    }
    Ok(())
}

/// Along the scene's `[camera_path]`, if it has one: the variant's shimmer
/// (`{v}_shimmer.png`, and over its image) and the path's report.
fn walk_camera_path<L: Instruments>(
    s: &mut Setup<L>,
    truth: &mut Truth,
    variant: L::Variant,
    v: &str,
    color: &image::RgbaImage,
) -> Result<Option<CameraPathReport>> {
    let Some(path) = s.sg.scene.camera_path else {
        return Ok(None);
    };
    let mut walk = PathWalk {
        gpu: &s.gpu,
        sg: &mut s.sg,
        targets: &s.targets,
        timer: &mut s.timer,
        references: &mut truth.path_references,
    };
    let (report, shimmer) = walk.measure(&mut s.lesson, variant, &path)?;
    let lights = s.sg.scene.lights.len();
    let out = &s.out_dir;
    save(
        &shimmer.image(lights),
        &out.join(format!("{v}_shimmer.png")),
    )?;
    let over = shimmer.image_over(lights, color);
    save(&over, &out.join(format!("{v}_shimmer_over.png")))?;
    Ok(Some(report))
}

/// Refuses a view with no receiver: every error figure would be 0.000 %
/// of nothing. Names what the camera sees instead.
fn check_receivers(sg: &SceneGpu, reference: &crate::reference::Reference) -> Result<()> {
    if metrics::reference_receivers(reference) > 0 {
        return Ok(());
    }
    let c = &sg.scene.camera;
    let far = match c.far {
        crate::scene::Far::Finite(f) => format!("{f}"),
        crate::scene::Far::Infinite => "infinite".to_string(),
    };
    let what = if reference.hits.iter().all(Option::is_none) {
        format!(
            "the camera sees no geometry between its near plane ({}) and far plane ({far})",
            c.near
        )
    } else {
        "no surface the camera sees faces a light within the light's reach".to_string()
    };
    anyhow::bail!(
        "scene {}: {what}, so there is no receiver to measure a shadow on: move [camera] (eye, target, near, far) or the lights",
        sg.scene.name
    )
}
